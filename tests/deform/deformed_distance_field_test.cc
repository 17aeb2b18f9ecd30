// The deformed distance field (paper sec. 4.2) against independent references: the rest field
// at q = 0, rigid motions applied through the proxies, the weights of eq. (3), C^0 continuity
// in x and q, the many-point query against the one-point one, and the exact distance to the deformed surface mesh (closest triangle by a BVH,
// sign by the winding number) in the contact band.
#include "deform/deformed_distance_field.h"

#include <gtest/gtest.h>
#include <hwy/targets.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "beam_fixture.h"
#include "deform/deformed_field_batch.h"
#include "deform/reduced_model.h"
#include "geometry/procedural_shapes.h"
#include "sdf/build_distance_field.h"
#include "sdf/triangle_bvh.h"
#include "sdf/unsigned_distance_grid.h"
#include "sdf/winding_number.h"
#include "util/error.h"

namespace contactlab {
namespace {

// A body: its surface mesh, rest field and a reduced model on the field's voxel tet mesh.
struct Body {
  TriangleMesh mesh;
  std::shared_ptr<const DistanceField> field;
  ReducedModel model;
};

Body MakeBody(const TriangleMesh& mesh, int resolution, int cells, int modes, const Anchoring& anchoring) {
  Body b;
  b.mesh = mesh;
  DistanceFieldOptions fo;
  fo.resolution = resolution;
  fo.show_progress = false;
  b.field = std::make_shared<const DistanceField>(BuildDistanceField(mesh, fo));
  VoxelMeshOptions vo;
  vo.cells = cells;
  ReducedModelOptions o;
  o.modes = modes;
  o.kind = ReducedModelKind::kLinear;
  o.material = testing::BeamMaterial();
  o.anchoring = anchoring;
  o.show_progress = false;
  b.model = BuildReducedModel(BuildVoxelTetMesh(*b.field, vo), o, mesh.name);
  return b;
}

// A square bar along z (0.1 x 0.1 x 0.5 m, every face cut into 16 x 16 squares so the surface
// follows the deformation), anchored at its lower end (z <= -0.2).
const Body& Bar() {
  static const Body b = MakeBody(MakeBox(Eigen::Vector3d(0.05, 0.05, 0.25), 16), 48, 12, 6, Anchoring::BelowPlane(Eigen::Vector3d::UnitZ(), -0.2));
  return b;
}

// A torus around z (radii 0.15, 0.05), anchored on its x <= -0.1 side.
const Body& Torus() {
  static const Body b = MakeBody(MakeTorus(0.15, 0.05, 32, 12), 48, 14, 6, Anchoring::BelowPlane(Eigen::Vector3d::UnitX(), -0.1));
  return b;
}

DeformedDistanceField MakeField(const Body& b, int proxies = 40, int k = 5, int domains = 1, double overlap = -1) {
  DeformedFieldOptions o;
  o.proxies = proxies;
  o.neighbours = k;
  o.domains = domains;
  o.overlap = overlap;
  return DeformedDistanceField(b.field, b.model.mesh, b.model.basis, o, "test body");
}

// Random q scaled so the largest vertex displacement of the simulation mesh is MAX_DISPLACEMENT.
Eigen::VectorXd ScaledQ(const ReducedModel& model, double max_displacement, std::mt19937* rng) {
  Eigen::VectorXd q = testing::RandomVector(model.r(), 1.0, rng);
  const Eigen::VectorXd u = model.basis * q;
  double m = 0;
  for (Eigen::Index v = 0; v < u.size(); v += 3) m = std::max(m, u.segment<3>(v).norm());
  return q * (max_displacement / m);
}

// Exact signed distance to the surface mesh deformed by the model at Q.
class ExactDeformedDistance {
 public:
  ExactDeformedDistance(const Body& b, const Eigen::VectorXd& q) : mesh_(b.mesh) {
    const EmbeddedPoints vertices(b.model.mesh, b.model.basis, b.mesh.vertices);
    for (int v = 0; v < mesh_.num_vertices(); ++v) mesh_.vertices[v] = vertices.Position(v, q.data());
    bvh_ = std::make_unique<TriangleBvh>(FlattenTriangles(mesh_));
  }
  double operator()(const Eigen::Vector3d& x) const {
    std::int32_t t = -1;
    const double d = std::sqrt(bvh_->ClosestSquared(x.data(), std::numeric_limits<double>::infinity(), &t));
    return WindingNumber(mesh_, x) > 0.5 ? -d : d;
  }

 private:
  TriangleMesh mesh_;
  std::unique_ptr<TriangleBvh> bvh_;
};

// Random points near the rest surface (within BAND of it), rest frame.
std::vector<Eigen::Vector3d> NearSurfacePoints(const DistanceField& field, double band, int count, std::mt19937* rng) {
  const Aabb box = field.box();
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> out;
  while (int(out.size()) < count) {
    const Eigen::Vector3d p = box.min + (box.max - box.min).cwiseProduct(Eigen::Vector3d(u(*rng), u(*rng), u(*rng)));
    if (std::abs(field.Distance(p)) <= band) out.push_back(p);
  }
  return out;
}

TEST(DeformedDistanceField, AtRestEqualsTheRestField) {
  for (int domains : {1, 3}) {
    // Cut faces lie 6 cells inside the neighbouring domain: a sample within a cell of the
    // surface interpolates no cut value.
    const Body& b = Bar();
    const double h = b.field->spacing();
    const DeformedDistanceField f = MakeField(b, 40, 5, domains, 6 * h);
    DeformedFieldState rest(f), zero(f);
    const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(f.r());
    zero.Update(f, q0.data());
    std::mt19937 rng(3);
    for (const Eigen::Vector3d& x : NearSurfacePoints(*b.field, h, 400, &rng)) {
      const double expected = b.field->Distance(x);
      EXPECT_NEAR(f.Distance(rest, x), expected, 1e-5 * h) << "domains " << domains;
      EXPECT_NEAR(f.Distance(zero, x), expected, 1e-5 * h) << "domains " << domains;
    }
  }
}

TEST(DeformedDistanceField, RigidMotionThroughTheProxiesIsExact) {
  const Body& b = Torus();
  const DeformedDistanceField f = MakeField(b);
  DeformedFieldState s(f);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  const Eigen::Vector3d t(0.03, -0.02, 0.05);
  for (int i = 0; i < f.num_slots(); ++i) s.Set(f, i, R * f.proxies().rest_position(i) + t, R);
  std::mt19937 rng(4);
  for (const Eigen::Vector3d& X : NearSurfacePoints(*b.field, 0.03, 400, &rng)) {
    const Eigen::Vector3d x = R * X + t;
    EXPECT_NEAR(f.Distance(s, x), b.field->Distance(X), 2e-6) << X.transpose();
  }
}

TEST(DeformedDistanceField, TranslationModesMoveTheFieldExactly) {
  // A basis of the three translations: F = I everywhere and every proxy moves by q.
  const Body& b = Bar();
  const TetMesh& mesh = b.model.mesh;
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(3 * mesh.num_vertices(), 3);
  for (int v = 0; v < mesh.num_vertices(); ++v) U.block<3, 3>(3 * v, 0).setIdentity();
  DeformedFieldOptions o;
  const DeformedDistanceField f(b.field, mesh, U, o, "translated capsule");
  DeformedFieldState s(f);
  const Eigen::Vector3d q(0.04, -0.01, 0.02);
  s.Update(f, q.data());
  std::mt19937 rng(5);
  for (const Eigen::Vector3d& X : NearSurfacePoints(*b.field, 0.03, 300, &rng)) {
    EXPECT_NEAR(f.Distance(s, X + q), b.field->Distance(X), 2e-6);
  }
}

TEST(DeformedDistanceField, WeightsAreNonNegativeSumToOneAndVanishAtTheKthNeighbour) {
  const Body& b = Torus();
  for (int k : {2, 5, 8}) {
    const DeformedDistanceField f = MakeField(b, 40, k);
    DeformedFieldState s(f);
    std::mt19937 rng(6);
    const Eigen::VectorXd q = ScaledQ(b.model, 0.03, &rng);
    s.Update(f, q.data());
    for (const Eigen::Vector3d& x : NearSurfacePoints(*b.field, 0.05, 200, &rng)) {
      const float xf[3] = {float(x.x()), float(x.y()), float(x.z())};
      int slots[kMaxProxyNeighbours];
      float w[kMaxProxyNeighbours];
      ASSERT_EQ(f.Weights(s, 0, xf, slots, w), k);
      double sum = 0;
      for (int i = 0; i < k; ++i) {
        EXPECT_GE(w[i], 0.f);
        sum += w[i];
        if (i > 0) {
          EXPECT_LE(w[i], w[i - 1] + 1e-6f);  // nearer proxies weigh more
        }
      }
      EXPECT_NEAR(sum, 1.0, 1e-5);
      EXPECT_EQ(w[k - 1], 0.f);
      // The k neighbours are the k nearest deformed proxies (brute force).
      std::vector<double> all;
      for (int i = 0; i < f.num_slots(); ++i) {
        all.push_back((x - s.position(i).cast<double>()).norm());
      }
      std::sort(all.begin(), all.end());
      EXPECT_NEAR((x - s.position(slots[k - 1]).cast<double>()).norm(), all[k - 1], 1e-6);
    }
  }
}

// Largest jump of d between consecutive samples of a path, for two sample spacings: a C^0
// function's jumps shrink with the spacing; a discontinuity's do not.
TEST(DeformedDistanceField, ContinuousInXAcrossNeighbourSwitches) {
  const Body& b = Torus();
  const DeformedDistanceField f = MakeField(b, 40, 5, 2);
  DeformedFieldState s(f);
  std::mt19937 rng(7);
  const Eigen::VectorXd q = ScaledQ(b.model, 0.03, &rng);
  s.Update(f, q.data());
  // A circle around the torus, crossing many proxies' neighbourhoods.
  auto path = [](double t) { return Eigen::Vector3d(0.19 * std::cos(t), 0.19 * std::sin(t), 0.01); };
  for (int n : {20000, 80000}) {
    double max_jump = 0;
    int switches = 0, last = -1;
    double prev = f.Distance(s, path(0));
    for (int i = 1; i <= n; ++i) {
      int nearest;
      const double d = f.Distance(s, path(2 * M_PI * i / n), &nearest);
      max_jump = std::max(max_jump, std::abs(d - prev));
      switches += nearest != last;
      last = nearest;
      prev = d;
    }
    EXPECT_GT(switches, 10);  // the path does cross neighbour switches
    // Path step 2 pi 0.19 / n; a Lipschitz bound of 10 covers the pull-back's stretch.
    EXPECT_LT(max_jump, 10 * 2 * M_PI * 0.19 / n) << n << " samples";
  }
}

TEST(DeformedDistanceField, ContinuousInQ) {
  const Body& b = Bar();
  const DeformedDistanceField f = MakeField(b);
  DeformedFieldState s(f);
  std::mt19937 rng(8);
  const Eigen::VectorXd q1 = ScaledQ(b.model, 0.05, &rng);
  const std::vector<Eigen::Vector3d> xs = NearSurfacePoints(*b.field, 0.02, 50, &rng);
  for (int n : {2000, 8000}) {
    std::vector<double> prev(xs.size());
    double max_jump = 0;
    for (int i = 0; i <= n; ++i) {
      const Eigen::VectorXd q = q1 * (double(i) / n);
      s.Update(f, q.data());
      for (std::size_t a = 0; a < xs.size(); ++a) {
        const double d = f.Distance(s, xs[a]);
        if (i > 0) max_jump = std::max(max_jump, std::abs(d - prev[a]));
        prev[a] = d;
      }
    }
    // The proxies move at most 0.05 m over the path; allow a stretch factor of 10.
    EXPECT_LT(max_jump, 10 * 0.05 / n) << n << " steps";
  }
}

// RMS and largest error in the contact band |d| <= 2 cells against the exact deformed distance.
void ExpectBandError(const Body& b, int domains, double max_displacement_fraction, double rms_cells, double max_cells) {
  const DeformedDistanceField f = MakeField(b, 40, 5, domains);
  DeformedFieldState s(f);
  const double h = b.field->spacing();
  const double size = b.mesh.Bounds().size().maxCoeff();
  std::mt19937 rng(9);
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd q = ScaledQ(b.model, max_displacement_fraction * size, &rng);
    s.Update(f, q.data());
    const ExactDeformedDistance exact(b, q);
    double sum2 = 0, worst = 0;
    int n = 0;
    std::uniform_real_distribution<double> u(0, 1);
    const Aabb box = b.field->box();
    while (n < 400) {
      const Eigen::Vector3d x = box.min + (box.max - box.min).cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
      const double e = exact(x);
      if (std::abs(e) > 2 * h) continue;
      const double err = f.Distance(s, x) - e;
      sum2 += err * err;
      worst = std::max(worst, std::abs(err));
      ++n;
    }
    const double rms = std::sqrt(sum2 / n);
    EXPECT_LT(rms, rms_cells * h) << b.mesh.name << " trial " << trial << ": rms " << rms / h << " cells";
    EXPECT_LT(worst, max_cells * h) << b.mesh.name << " trial " << trial << ": max " << worst / h << " cells";
  }
}

TEST(DeformedDistanceField, MatchesTheExactDeformedDistanceInTheContactBand) {
  // Target: RMS <= 0.5 cell for a largest displacement of 10% of the body's size.
  ExpectBandError(Bar(), 1, 0.10, 0.5, 2.0);
  ExpectBandError(Torus(), 1, 0.10, 0.5, 2.0);
  ExpectBandError(Torus(), 3, 0.10, 0.5, 2.0);
}

TEST(DeformedDistanceField, DomainsCoverTheBodyAndHoldKProxies) {
  const Body& b = Bar();
  DeformedFieldOptions o;
  o.regions = {DomainRegion::Halfspace(Eigen::Vector3d::UnitZ(), 0.0)};  // only the lower half
  EXPECT_THROW(DeformedDistanceField(b.field, b.model.mesh, b.model.basis, o, "capsule"), Error);
  o.regions.push_back(DomainRegion::Halfspace(-Eigen::Vector3d::UnitZ(), 0.0));
  const DeformedDistanceField two(b.field, b.model.mesh, b.model.basis, o, "capsule");
  EXPECT_EQ(two.num_domains(), 2);
  o.regions = {};
  o.domains = 21;  // more than half the 40 proxies
  EXPECT_THROW(DeformedDistanceField(b.field, b.model.mesh, b.model.basis, o, "capsule"), Error);
  o.domains = 1;
  o.neighbours = 1;
  EXPECT_THROW(DeformedDistanceField(b.field, b.model.mesh, b.model.basis, o, "capsule"), Error);
}

// The batched query (deform/deformed_field_batch.h) against the one-point query, on every
// instruction set compiled: the same nearest slot and d to float rounding, for k from 2 to the
// largest, one and three domains, points in the band, far outside the box, on a proxy (all
// weight on it) and batch sizes that leave partial vectors and batches.
TEST(DeformedDistanceField, ManyPointQueryEqualsTheOnePointQuery) {
  std::mt19937 rng(41);
  const Body& body = Torus();
  const double h = body.field->spacing();
  for (const auto& [k, domains] :
       std::vector<std::pair<int, int>>{{2, 1}, {5, 1}, {5, 3}, {8, 2}, {5, 6}, {kMaxProxyNeighbours, 1}}) {
    const DeformedDistanceField field = MakeField(body, 40, k, domains);
    DeformedFieldState state(field);
    const Eigen::VectorXd q = ScaledQ(body.model, 0.02, &rng);
    state.Update(field, q.data());
    std::vector<float> x, y, z;
    std::uniform_real_distribution<float> u(-0.25f, 0.25f), uz(-0.08f, 0.08f);
    for (int i = 0; i < 150; ++i) x.push_back(u(rng)), y.push_back(u(rng)), z.push_back(uz(rng));
    for (int i = 0; i < 5; ++i) x.push_back(3.f + float(i)), y.push_back(-2.f), z.push_back(0.5f);  // far outside
    for (int i = 0; i < 7; ++i) {  // on a proxy: its weight dominates
      const Eigen::Vector3f p = state.position(field.slot_begin(0) + i);
      x.push_back(p.x()), y.push_back(p.y()), z.push_back(p.z());
    }
    for (int n : {1, 7, int(x.size())}) {
      const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
      for (std::int64_t target : targets) {
        hwy::SetSupportedTargetsForTest(target);
        std::vector<float> d(n);
        std::vector<std::int32_t> nearest(n, -2);
        const std::int64_t answered =
            DeformedFieldDistances(field, state, x.data(), y.data(), z.data(), n, d.data(), nearest.data());
        EXPECT_GE(answered, n);
        EXPECT_LE(answered, std::int64_t(n) * domains);
        // Far points and most points of one part need not ask every domain.
        if (domains > 1 && n == int(x.size())) EXPECT_LT(answered, std::int64_t(n) * domains);
        for (int i = 0; i < n; ++i) {
          const float p[3] = {x[i], y[i], z[i]};
          int slot = -3;
          const float expected = field.Distance(state, p, &slot);
          ASSERT_NEAR(d[i], expected, 1e-5 * h + 1e-6 * std::abs(expected))
              << hwy::TargetName(target) << " k " << k << " domains " << domains << " point " << i;
          ASSERT_EQ(nearest[i], slot) << hwy::TargetName(target) << " k " << k << " point " << i;
        }
      }
      hwy::SetSupportedTargetsForTest(0);
    }
  }
}

// DeformedFieldDomainBounds against each domain's distance formed independently (its k nearest slots
// and weights, the pull-backs, the domain's own rest field), under deformations up to a fifth of
// the body's size, for points in and around the body and far away: never above it, and a real
// bound (positive) for most domains at points around the body under small deformations.
TEST(DeformedDistanceField, DomainLowerBoundNeverExceedsTheDomainsDistance) {
  std::mt19937 rng(43);
  for (const Body* body : {&Torus(), &Bar()}) {
    const DeformedDistanceField field = MakeField(*body, 40, 5, 4);
    DeformedFieldState state(field);
    for (double displacement : {0.0, 0.01, 0.05, 0.1}) {
      const Eigen::VectorXd q = ScaledQ(body->model, displacement, &rng);
      state.Update(field, q.data());
      std::uniform_real_distribution<float> u(-0.6f, 0.6f);
      int bounded = 0;
      for (int i = 0; i < 400; ++i) {
        const float x[3] = {u(rng), u(rng), u(rng)};
        for (int dom = 0; dom < field.num_domains(); ++dom) {
          int slots[kMaxProxyNeighbours];
          float w[kMaxProxyNeighbours];
          const int n = field.Weights(state, dom, x, slots, w);
          double expected = 0;
          for (int m = 0; m < n; ++m) {
            const float* a = state.pullback(slots[m]);
            const Eigen::Vector3d X(a[9] + a[0] * x[0] + a[1] * x[1] + a[2] * x[2],
                                    a[10] + a[3] * x[0] + a[4] * x[1] + a[5] * x[2],
                                    a[11] + a[6] * x[0] + a[7] * x[1] + a[8] * x[2]);
            if (w[m] != 0.f) expected += w[m] * field.domain_field(dom).Distance(X);
          }
          float bound;
          DeformedFieldDomainBounds(field, state, dom, &x[0], &x[1], &x[2], 1, &bound);
          ASSERT_LE(bound, expected) << "displacement " << displacement << " domain " << dom << " point " << i;
          if (bound > 0) ++bounded;
        }
      }
      if (displacement <= 0.01) EXPECT_GT(bounded, 400) << "displacement " << displacement;  // of 1600
    }
  }
}

}  // namespace
}  // namespace contactlab
