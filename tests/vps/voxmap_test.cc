// Tests of the VPS voxmaps (McNeely et al. 1999 sec. 4.1; 2006 sec. 3): classification of a
// sampled sphere field against the exact sphere, 2-bit packing, and the 8-bit layer map
// against a brute-force Chebyshev distance transform.
#include "baselines/vps/voxmap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "baselines/vps/wide_voxmap.h"
#include "contact/test_shells.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::SampleField;

// Field of a sphere of radius R at the origin, on a grid of spacing H.
std::shared_ptr<DistanceField> SphereField(double R, double h) {
  const Eigen::Vector3d lo = Eigen::Vector3d::Constant(-1.3 * R), hi = Eigen::Vector3d::Constant(1.3 * R);
  return SampleField([R](const Eigen::Vector3d& p) { return p.norm() - R; }, lo, hi, h);
}

// Smallest and largest distance from the origin over voxel (i, j, k) of MAP.
void VoxelRadiusRange(const Voxmap& map, int i, int j, int k, double* rmin, double* rmax) {
  const Eigen::Vector3d lo = map.origin() + map.voxel_size() * Eigen::Vector3d(i, j, k);
  const Eigen::Vector3d hi = lo + Eigen::Vector3d::Constant(map.voxel_size());
  const Eigen::Vector3d nearest = Eigen::Vector3d::Zero().cwiseMax(lo).cwiseMin(hi);
  const Eigen::Vector3d farthest = lo.cwiseAbs().cwiseMax(hi.cwiseAbs());
  *rmin = nearest.norm();
  *rmax = farthest.norm();
}

bool IsContact(VoxelClass c) { return c == VoxelClass::kSurface || c == VoxelClass::kInterior; }

// Every voxel of the sphere's voxmap is checked against the exact sphere of radius R.
void CheckSphereVoxmap(double R, double h, double voxel_size) {
  SCOPED_TRACE("R " + std::to_string(R) + " h " + std::to_string(h) + " voxel " + std::to_string(voxel_size));
  auto field = SphereField(R, h);
  VoxmapOptions options;
  options.voxel_size = voxel_size;
  const Voxmap map = BuildVoxmap(*field, options);
  const double v = map.voxel_size();
  EXPECT_DOUBLE_EQ(v, voxel_size > 0 ? voxel_size : h);
  const double half_diagonal = 0.5 * std::sqrt(3.0) * v;
  const double tol = 0.02 * v;  // trilinear interpolation error of |p| - R at these sizes
  const Eigen::Vector3i n = map.dims();
  std::int64_t counts[4] = {0, 0, 0, 0};
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const VoxelClass c = map.Get(i, j, k);
        ++counts[int(c)];
        const double r = map.Centre(i, j, k).norm();
        double rmin, rmax;
        VoxelRadiusRange(map, i, j, k, &rmin, &rmax);
        // The true surface clearly crosses the voxel: it must be a surface voxel.
        if (rmin < R - tol && rmax > R + tol) {
          EXPECT_EQ(c, VoxelClass::kSurface) << "voxel " << i << " " << j << " " << k << " r " << r;
        }
        switch (c) {
          case VoxelClass::kSurface:  // within half a diagonal of the surface
            EXPECT_LE(std::abs(r - R), half_diagonal + tol) << i << " " << j << " " << k;
            break;
          case VoxelClass::kInterior:  // inside, and not within the inscribed ball's reach
            EXPECT_LT(r, R - 0.5 * v + tol) << i << " " << j << " " << k;
            break;
          default:
            EXPECT_GT(r, R + 0.5 * v - tol) << i << " " << j << " " << k;
        }
        // Proximity exactly when a non-contact voxel has a contact voxel among its 26 neighbours.
        if (!IsContact(c)) {
          bool near_contact = false;
          for (int dk = -1; dk <= 1; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di) {
                const int a = i + di, b = j + dj, e = k + dk;
                if (a < 0 || b < 0 || e < 0 || a >= n.x() || b >= n.y() || e >= n.z()) continue;
                near_contact = near_contact || IsContact(map.Get(a, b, e));
              }
          EXPECT_EQ(c == VoxelClass::kProximity, near_contact) << i << " " << j << " " << k;
        }
      }
  for (int c = 0; c < 4; ++c) EXPECT_EQ(counts[c], map.count(VoxelClass(c)));
  // Counts against area and volume: a surface of area A crosses about 1.5 A / v^2 voxels (the
  // mean of |nx| + |ny| + |nz| over directions); interior plus half the surface voxels fill
  // the volume.
  const double area = 4 * M_PI * R * R, volume = 4.0 / 3.0 * M_PI * R * R * R;
  const double surface = double(map.count(VoxelClass::kSurface));
  const double interior = double(map.count(VoxelClass::kInterior));
  EXPECT_NEAR(surface / (1.5 * area / (v * v)), 1.0, 0.15);
  EXPECT_NEAR((interior + 0.5 * surface) * v * v * v / volume, 1.0, 0.05);
  EXPECT_GT(map.count(VoxelClass::kProximity), 0);
  EXPECT_GT(map.count(VoxelClass::kFree), 0);
}

TEST(Voxmap, SphereVoxelsAreClassifiedByTheirDistanceToTheTrueSurface) {
  CheckSphereVoxmap(0.05, 0.004, 0);  // voxels on the field's grid
}

TEST(Voxmap, SphereVoxelsAreClassifiedCorrectlyAtAVoxelSizeOffTheFieldGrid) {
  CheckSphereVoxmap(0.05, 0.003, 0.0051);  // 1.7 field spacings, corners between grid points
}

TEST(Voxmap, MemoryIsCeilOfVoxelsOverFourBytes) {
  std::mt19937 rng(7);
  for (const Eigen::Vector3i& dims : {Eigen::Vector3i(1, 1, 1), Eigen::Vector3i(4, 4, 4), Eigen::Vector3i(3, 5, 7),
                                     Eigen::Vector3i(2, 3, 1), Eigen::Vector3i(17, 1, 2)}) {
    Voxmap map(Eigen::Vector3d(0.1, -0.2, 0.3), 1.0 / 3.0, dims);
    const std::int64_t n = dims.prod();
    EXPECT_EQ(map.memory_bytes(), std::size_t((n + 3) / 4)) << dims.transpose();
    // Packing round trip: every voxel keeps its own class, neighbours in the byte untouched.
    std::vector<VoxelClass> expected(static_cast<std::size_t>(n));
    std::int64_t counts[4] = {0, 0, 0, 0};
    for (std::int64_t idx = 0; idx < n; ++idx) {
      expected[std::size_t(idx)] = VoxelClass(rng() % 4);
      map.Set(idx, expected[std::size_t(idx)]);
    }
    for (std::int64_t idx = 0; idx < n; ++idx) {
      EXPECT_EQ(map.Get(idx), expected[std::size_t(idx)]) << idx;
      ++counts[int(expected[std::size_t(idx)])];
    }
    for (int c = 0; c < 4; ++c) EXPECT_EQ(map.count(VoxelClass(c)), counts[c]);
  }
  auto field = SphereField(0.05, 0.004);
  const Voxmap built = BuildVoxmap(*field);
  EXPECT_EQ(built.memory_bytes(), std::size_t((built.num_voxels() + 3) / 4));
  EXPECT_EQ(built.dims(), (field->dims().array() - 1).matrix());  // one voxel per field cell
}

TEST(Voxmap, LocateFindsTheVoxelContainingAPointAndNothingOutside) {
  const Voxmap map(Eigen::Vector3d(-1, -1, -1), 0.25, Eigen::Vector3i(8, 4, 2));
  int i, j, k;
  ASSERT_TRUE(map.Locate(-0.9f, -0.01f, -0.51f, &i, &j, &k));
  EXPECT_EQ(i, 0);
  EXPECT_EQ(j, 3);
  EXPECT_EQ(k, 1);
  ASSERT_TRUE(map.Locate(0.99f, -0.99f, -0.99f, &i, &j, &k));
  EXPECT_EQ(i, 7);
  EXPECT_FALSE(map.Locate(1.01f, 0.f, -0.9f, &i, &j, &k));
  EXPECT_FALSE(map.Locate(0.f, 0.f, -0.5f, &i, &j, &k));  // z beyond 2 voxels
  EXPECT_FALSE(map.Locate(-1.01f, -0.9f, -0.9f, &i, &j, &k));
  EXPECT_FALSE(map.Locate(NAN, 0.f, -0.9f, &i, &j, &k));
}

TEST(WideVoxmap, LayersAreChebyshevDistancesToTheNearestContactVoxel) {
  auto field = SphereField(0.05, 0.006);
  VoxmapOptions options;
  options.voxel_size = 0.005;
  const Voxmap map = BuildVoxmap(*field, options);
  const WideVoxmap wide = BuildWideVoxmap(map);
  EXPECT_EQ(wide.memory_bytes(), std::size_t(map.num_voxels()));
  EXPECT_EQ(wide.dims(), map.dims());
  const Eigen::Vector3i n = map.dims();
  std::vector<Eigen::Vector3i> contact;
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i)
        if (IsContact(map.Get(i, j, k))) contact.emplace_back(i, j, k);
  ASSERT_FALSE(contact.empty());
  int max_layer = 0;
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const VoxelClass c = map.Get(i, j, k);
        const std::uint8_t w = wide.Get(i, j, k);
        if (c == VoxelClass::kSurface) {
          EXPECT_EQ(w, kWideSurface);
        } else if (c == VoxelClass::kInterior) {
          EXPECT_EQ(w, kWideInterior);
        } else {
          int chebyshev = 1 << 30;
          for (const auto& q : contact) {
            chebyshev = std::min(chebyshev, (q - Eigen::Vector3i(i, j, k)).cwiseAbs().maxCoeff());
          }
          EXPECT_EQ(int(w), std::min(chebyshev, int(kWideMaxLayer))) << i << " " << j << " " << k;
          EXPECT_EQ(w == kWideProximity, c == VoxelClass::kProximity);
          max_layer = std::max(max_layer, int(w));
        }
      }
  EXPECT_GE(max_layer, 3);  // the grid reaches a few layers out
}

TEST(WideVoxmap, LayersAreCappedAt254) {
  Voxmap map(Eigen::Vector3d::Zero(), 0.001, Eigen::Vector3i(300, 1, 2));
  map.Set(map.Index(0, 0, 0), VoxelClass::kSurface);
  map.Set(map.Index(299, 0, 1), VoxelClass::kInterior);
  const WideVoxmap wide = BuildWideVoxmap(map);
  EXPECT_EQ(wide.Get(0, 0, 0), kWideSurface);
  EXPECT_EQ(wide.Get(0, 0, 1), 1);
  EXPECT_EQ(wide.Get(100, 0, 0), 100);
  EXPECT_EQ(wide.Get(150, 0, 1), 149);  // nearer to the interior voxel at 299
  EXPECT_EQ(wide.Get(299, 0, 1), kWideInterior);
  Voxmap lone(Eigen::Vector3d::Zero(), 0.001, Eigen::Vector3i(400, 1, 1));
  lone.Set(0, VoxelClass::kSurface);
  const WideVoxmap far = BuildWideVoxmap(lone);
  EXPECT_EQ(far.Get(253, 0, 0), 253);
  EXPECT_EQ(far.Get(254, 0, 0), kWideMaxLayer);
  EXPECT_EQ(far.Get(399, 0, 0), kWideMaxLayer);
}

TEST(Voxmap, BadVoxelSizesThrowNamingTheField) {
  auto field = SphereField(0.05, 0.004);
  field->mutable_info().source = "ball.sdf";
  VoxmapOptions options;
  options.voxel_size = 1e-6;  // ~10^15 voxels
  try {
    BuildVoxmap(*field, options);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("voxmap of ball.sdf"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("voxels"), std::string::npos) << e.what();
  }
  options.voxel_size = NAN;
  EXPECT_THROW(BuildVoxmap(*field, options), Error);
  EXPECT_THROW(BuildVoxmap(DistanceField(), {}), Error);
  EXPECT_THROW(Voxmap(Eigen::Vector3d::Zero(), -1.0, Eigen::Vector3i(2, 2, 2)), Error);
  EXPECT_THROW(Voxmap(Eigen::Vector3d::Zero(), 1.0, Eigen::Vector3i(2, 0, 2)), Error);
}

}  // namespace
}  // namespace contactlab
