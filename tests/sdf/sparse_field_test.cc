// The narrow-band field (sdf/sparse_field.h) against independent references: the dense closed
// pipeline (ray-crossing signs, band and propagation) on the very same fine grid, and exact
// signed distances from a BVH with pseudo-normals; its vectorised lookups against its scalar
// one on every instruction set; its file round trip and its refusals.
#include "sdf/sparse_field.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <vector>

#include "geometry/procedural_shapes.h"
#include "sdf/batch_distance.h"
#include "sdf/build_distance_field.h"
#include "sdf/mesh_signed_distance.h"
#include "sdf/signed_distance_grid.h"
#include "test_support.h"
#include "util/error.h"

namespace contactlab {
namespace {

// A torus (curved, with a hole whose far side is close to the near side) and its sparse field
// at 128 cells, plus the dense closed-pipeline field on the same fine grid.
struct TorusFields {
  TriangleMesh mesh;
  DistanceField sparse, dense;
  double h = 0;
  TorusFields() {
    mesh = MakeTorus(0.04, 0.012, 96, 48);
    mesh.name = "torus";
    DistanceFieldOptions o;
    o.resolution = 128;
    o.storage = FieldStorage::kSparse;
    o.show_progress = false;
    sparse = BuildDistanceField(mesh, o);
    h = sparse.spacing();
    FieldGrid grid;
    grid.origin = sparse.origin();
    grid.spacing = h;
    grid.dims = sparse.dims();
    dense = DistanceField(grid.origin, h, grid.dims, ComputeSignedDistance(mesh, grid, 3));
  }
};

const TorusFields& Torus() {
  static const TorusFields* t = new TorusFields;
  return *t;
}

TEST(SparseField, BandSamplesEqualTheDenseFieldOnTheSameGridAndAreStored) {
  const TorusFields& t = Torus();
  const SparseFieldStorage& s = *t.sparse.sparse();
  ASSERT_EQ(t.sparse.dims(), t.dense.dims());
  EXPECT_EQ(t.sparse.dims().maxCoeff(), 129);
  const double band = 3 * t.h;
  std::int64_t in_band = 0;
  for (int k = 0; k < t.dense.dims().z(); ++k)
    for (int j = 0; j < t.dense.dims().y(); ++j)
      for (int i = 0; i < t.dense.dims().x(); ++i) {
        const double d = t.dense.value(i, j, k);
        if (std::abs(d) > band) continue;
        ++in_band;
        const int bx = std::min(i / 8, s.bricks.x() - 1), by = std::min(j / 8, s.bricks.y() - 1),
                  bz = std::min(k / 8, s.bricks.z() - 1);
        ASSERT_GE(s.slot[s.BrickIndex(bx, by, bz)], 0) << "grid point " << i << " " << j << " " << k;
        ASSERT_NEAR(t.sparse.value(i, j, k), d, 0.51 * s.quantum + 1e-7 * std::abs(d))
            << "grid point " << i << " " << j << " " << k;
      }
  EXPECT_GT(in_band, 10000);
  // The 16-bit step is far below a voxel: stored values lie within band + 14 voxels.
  EXPECT_LT(s.quantum, 17.0 / 32767 * t.h * 1.001);
  // Even at this low resolution most bricks hold no samples (the share falls as the
  // resolution grows: the band's volume goes as 1/resolution).
  EXPECT_LT(s.num_stored() * 2, std::int64_t(s.slot.size()));
  EXPECT_LT(t.sparse.memory_bytes() * 2, t.dense.memory_bytes());
}

TEST(SparseField, LookupsAreExactInTheBandAndALowerBoundOutsideIt) {
  const TorusFields& t = Torus();
  const MeshSignedDistance exact(t.mesh, "torus");
  const Aabb box = t.sparse.box();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const double h = t.h, H = 8 * h;
  int near = 0, far_out = 0, far_in = 0;
  for (int n = 0; n < 40000; ++n) {
    const Eigen::Vector3d p = box.min + (box.max - box.min).cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const double d = exact.Distance(p);
    const double sp = t.sparse.Distance(p);
    if (std::abs(d) <= 2 * h) {
      // Every corner of the cell is within the band: the dense field's trilinear value.
      ++near;
      ASSERT_NEAR(sp, t.dense.Distance(p), 2 * t.sparse.sparse()->quantum + 1e-6 * h);
    } else if (d > 0) {
      ++far_out;
      ASSERT_GT(sp, 0) << "outside point read as inside";
      ASSERT_LE(sp, d + 0.05 * h) << "the bound outside the band overestimates";
    } else {
      ++far_in;
      ASSERT_LT(sp, 0) << "inside point read as outside";
      ASSERT_NEAR(sp, d, H) << "depth beyond the band is the coarse field's";
    }
  }
  EXPECT_GT(near, 300);
  EXPECT_GT(far_out, 10000);
  EXPECT_GT(far_in, 300);
  // Outside the box: the Fig. 5(c) bound, below the true distance.
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(box.max.x() + 0.01, 0, 0), Eigen::Vector3d(0, box.min.y() - 0.03, 0.01)}) {
    EXPECT_GT(t.sparse.Distance(p), 0);
    EXPECT_LE(t.sparse.Distance(p), exact.Distance(p));
  }
}

TEST(SparseField, GradientIsTheInterpolantsAndMatchesTheScalarValue) {
  const TorusFields& t = Torus();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.055, 0.055);
  const double step = 1e-4 * t.h;
  int checked = 0;
  for (int n = 0; n < 2000; ++n) {
    const Eigen::Vector3d p(u(rng), u(rng), 0.3 * u(rng));
    Eigen::Vector3d g;
    const double v = t.sparse.DistanceAndGradient(p, &g);
    // The scalar lookup rounds the point to float: up to ~1e-5 voxels at these coordinates.
    ASSERT_NEAR(v, t.sparse.Distance(p), 2e-5 * t.h + 1e-6 * std::abs(v));
    // Central differences inside one cell (skip points near a cell face, where the
    // interpolant's gradient jumps, and points where the steps reach another of the bounds
    // outside the band: the gradient differs on either side of such a switch).
    const Eigen::Vector3d c = (p - t.sparse.origin()) / t.h;
    if (((c.array() - c.array().floor()).min(c.array().ceil() - c.array())).minCoeff() < 0.01) continue;
    Eigen::Vector3d fd;
    bool smooth = true;
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero(), g_plus, g_minus;
      e[a] = step;
      fd[a] = (t.sparse.DistanceAndGradient(p + e, &g_plus) - t.sparse.DistanceAndGradient(p - e, &g_minus)) / (2 * step);
      smooth = smooth && (g_plus - g).norm() < 1e-3 && (g_minus - g).norm() < 1e-3;
    }
    if (!smooth) continue;
    ASSERT_LT((fd - g).norm(), 1e-5) << "at " << p.transpose();
    ++checked;
  }
  EXPECT_GT(checked, 1500);
}

TEST(SparseField, BatchLookupsEqualTheScalarOnEveryInstructionSet) {
  const TorusFields& t = Torus();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-0.07f, 0.07f);
  std::vector<float> x, y, z;
  for (int n = 0; n < 3001; ++n) {
    x.push_back(u(rng));
    y.push_back(u(rng));
    z.push_back(0.4f * u(rng));
  }
  // Points near the surface (within 5 voxels): vectors mostly in stored bricks with a few
  // lanes outside them, the other path of the vectorised lookup.
  std::uniform_real_distribution<double> angle(0, 2 * M_PI), offset(-5, 5);
  for (int n = 0; n < 3000; ++n) {
    const double a = angle(rng), b = angle(rng), r = 0.012 + offset(rng) * t.h;
    x.push_back(float((0.04 + r * std::cos(b)) * std::cos(a)));
    y.push_back(float((0.04 + r * std::cos(b)) * std::sin(a)));
    z.push_back(float(r * std::sin(b)));
  }
  x.push_back(std::numeric_limits<float>::quiet_NaN());
  y.push_back(0);
  z.push_back(0);
  const int n = int(x.size());
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (std::int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    std::vector<float> d(n);
    BatchDistances(t.sparse, kIdentityTransform, x.data(), y.data(), z.data(), nullptr, n, d.data());
    for (int i = 0; i < n - 1; ++i) {
      const float s = t.sparse.Distance(x[i], y[i], z[i]);
      ASSERT_NEAR(d[i], s, 1e-4f * float(t.h))
          << hwy::TargetName(target) << " point " << i;
    }
    EXPECT_EQ(d[n - 1], std::numeric_limits<float>::infinity()) << hwy::TargetName(target);
  }
  hwy::SetSupportedTargetsForTest(0);
}

TEST(SparseField, FileRoundTripKeepsEveryLookupAndACorruptSlotIsRefused) {
  const TorusFields& t = Torus();
  const testing::TempDir dir;
  const std::filesystem::path file = dir / "torus.sdf";
  SaveDistanceField(t.sparse, file);
  const DistanceField back = LoadDistanceField(file);
  ASSERT_NE(back.sparse(), nullptr);
  EXPECT_EQ(back.dims(), t.sparse.dims());
  EXPECT_EQ(back.memory_bytes(), t.sparse.memory_bytes());
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-0.06f, 0.06f);
  for (int n = 0; n < 2000; ++n) {
    const float x = u(rng), y = u(rng), z = 0.3f * u(rng);
    ASSERT_EQ(back.Distance(x, y, z), t.sparse.Distance(x, y, z));
  }
  EXPECT_NE(DescribeDistanceField(back).find("sparse"), std::string::npos);
  // A slot pointing past the stored bricks, with a valid checksum: refused by name.
  SparseFieldStorage bad = *t.sparse.sparse();
  bad.slot[0] = std::int32_t(bad.num_stored());
  EXPECT_THROW(DistanceField(t.sparse.origin(), t.h, bad), Error);
}

TEST(SparseField, RefusesWhatItCannotBuild) {
  DistanceFieldOptions o;
  o.storage = FieldStorage::kSparse;
  o.show_progress = false;
  TriangleMesh open = MakeBox(Eigen::Vector3d(0.02, 0.03, 0.01));
  open.triangles.pop_back();
  open.name = "open-box";
  o.resolution = 64;
  try {
    BuildDistanceField(open, o);
    ADD_FAILURE() << "an open mesh was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("open-box"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("watertight"), std::string::npos) << e.what();
  }
  TriangleMesh box = MakeBox(Eigen::Vector3d(0.02, 0.03, 0.01));
  box.name = "box";
  o.resolution = 100;
  EXPECT_THROW(BuildDistanceField(box, o), Error);
  o.resolution = 64;
  o.band_voxels = 0;
  EXPECT_THROW(BuildDistanceField(box, o), Error);
  EXPECT_THROW(ParseFieldStorage("bricked", "test"), Error);
}

}  // namespace
}  // namespace contactlab
