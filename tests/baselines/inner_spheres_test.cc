// Inner Sphere Trees (baselines/inner_spheres): the packing against brute force (inside the
// body, no overlaps), the penetration volume against the exact lens of two balls
// and the exact cap of a ball in a halfspace as coverage rises, K_B against central differences,
// Newton's third law, frame covariance, graceful degradation and the packing's file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>

#include <Eigen/Eigenvalues>

#include "baselines/inner_spheres/inner_sphere_model.h"
#include "baselines/inner_spheres/sphere_packing.h"
#include "baselines/volumetric_cases.h"
#include "contact/test_shells.h"
#include "geometry/pose.h"
#include "geometry/rotation_math.h"
#include "haptics/virtual_coupling.h"
#include "util/error.h"
#include "test_support.h"

namespace contactlab {
namespace {

using testing::At;
using testing::Overlap;
using testing::SampleField;
using testing::Translation;
constexpr double kPi = std::numbers::pi;

std::shared_ptr<DistanceField> Ball(double R, double h) { return testing::BallField(R, h, 3); }

// A slab of half-thickness 0.02 below z = 0, wide in x and y: a halfspace where a ball meets it.
std::shared_ptr<DistanceField> Slab(double h) {
  return SampleField(
      [](const Eigen::Vector3d& p) {
        const Eigen::Vector3d q = (p - Eigen::Vector3d(0, 0, -0.02)).cwiseAbs() - Eigen::Vector3d(0.04, 0.04, 0.02);
        return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
      },
      Eigen::Vector3d(-0.045, -0.045, -0.045), Eigen::Vector3d(0.045, 0.045, 0.005), h);
}

std::shared_ptr<const SpherePacking> Pack(const DistanceField& f, double volume, int spheres) {
  SpherePackingOptions o;
  o.max_spheres = spheres;
  return std::make_shared<const SpherePacking>(BuildSpherePacking(f, volume, o, "test"));
}


TEST(SpherePacking, SpheresAreInsideAndDisjoint) {
  auto f = Ball(0.02, 0.001);
  const double volume = 4.0 / 3.0 * kPi * 0.02 * 0.02 * 0.02;
  auto p = Pack(*f, volume, 400);
  // The first sphere is the ball itself, and then nothing else fits.
  ASSERT_EQ(p->radii.size(), 1u);
  EXPECT_NEAR(p->radii[0], 0.02, 1e-7);
  auto q = Pack(*Slab(0.001), 0.08 * 0.08 * 0.04, 300);
  // (Not strictly largest first: a prototype grows as it moves, sphere_packing.h.)
  EXPECT_EQ(q->radii[0], *std::max_element(q->radii.begin(), q->radii.end()));
  for (std::size_t i = 0; i < q->radii.size(); ++i) {
    // Inside: the exact distance to the slab's surface is at least the radius.
    const Eigen::Vector3d c = q->centers[i];
    const Eigen::Vector3d d = (c - Eigen::Vector3d(0, 0, -0.02)).cwiseAbs() - Eigen::Vector3d(0.04, 0.04, 0.02);
    EXPECT_LE(q->radii[i], -d.maxCoeff() + 1e-6);
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_GE((c - q->centers[j]).norm(), q->radii[i] + q->radii[j] - 1e-9) << i << " overlaps " << j;
    }
  }
  EXPECT_GT(q->Coverage(), 0.3);
  EXPECT_LT(q->Coverage(), 1.0);
}

TEST(SpherePacking, CoverageTargetStopsEarlyAndGrowsWithTheCount) {
  auto f = Slab(0.001);
  const double volume = 0.08 * 0.08 * 0.04;
  double last = 0;
  for (const int n : {10, 100, 1000}) {
    const double c = Pack(*f, volume, n)->Coverage();
    EXPECT_GT(c, last);
    last = c;
  }
  SpherePackingOptions o;
  o.max_spheres = 100000;
  o.coverage = 0.5;
  const SpherePacking p = BuildSpherePacking(*f, volume, o, "test");
  EXPECT_GE(p.Coverage(), 0.5);
  EXPECT_LT(p.radii.size(), 100000u);
  // One sphere fewer is short of the target: it stopped as soon as it got there.
  EXPECT_LT(p.Coverage() - 4.0 / 3.0 * kPi * std::pow(p.radii.back(), 3) / volume, 0.5);
}

TEST(InnerSpheres, TwoBallsGiveTheExactLensAndItsGradient) {
  const double k_V = 1e6;
  auto ball = Pack(*Ball(0.015, 0.001), 4.0 / 3.0 * kPi * std::pow(0.015, 3), 1);
  ASSERT_EQ(ball->radii.size(), 1u);
  InnerSphereModel model(ball, ball, k_V);
  const double R = ball->radii[0];  // the field's sample at the centre (float)
  for (const double d : {0.029, 0.02, 0.01}) {
    const ContactResult r = model.Evaluate(At(Pose::Identity(), Translation(0, d, 0)));
    const double lens = kPi / 12 * (4 * R + d) * (2 * R - d) * (2 * R - d);
    EXPECT_NEAR(model.volume(), lens, 1e-12 * lens) << d;
    // F = -k_V dV/dd along the line of centres; dV/dd of the closed form by differences.
    const double e = 1e-7;
    const double dV = (kPi / 12 * (4 * R + d + e) * std::pow(2 * R - d - e, 2) -
                       kPi / 12 * (4 * R + d - e) * std::pow(2 * R - d + e, 2)) / (2 * e);
    EXPECT_NEAR(r.on_B.force.y(), -k_V * dV, 1e-6 * k_V * std::abs(dV)) << d;
    EXPECT_LT(r.on_B.force.cwiseAbs()[0] + r.on_B.force.cwiseAbs()[2], 1e-12);
  }
}

TEST(InnerSpheres, BallIntoHalfspaceApproachesTheCapVolumeAsCoverageRises) {
  const double R = 0.015, delta = 0.004;
  auto ball_field = Ball(R, 0.0007);
  auto slab_field = Slab(0.0007);
  const double cap = kPi * delta * delta * (3 * R - delta) / 3;
  double last_error = 1;
  for (const int n : {30, 300, 3000}) {
    auto a = Pack(*ball_field, 4.0 / 3.0 * kPi * R * R * R, n);
    auto b = Pack(*slab_field, 0.08 * 0.08 * 0.04, n);
    InnerSphereModel model(a, b, 1e6);
    model.Evaluate(At(Translation(0.0007, 0.0003, R - delta), Pose::Identity()));
    const double error = std::abs(model.volume() - cap) / cap;
    std::printf("spheres %d: coverage %.3f / %.3f, V/V_cap %.3f\n", n, a->Coverage(), b->Coverage(),
                model.volume() / cap);
    EXPECT_LT(error, last_error) << n;
    last_error = error;
  }
  EXPECT_LT(last_error, 0.6);
}

std::vector<testing::Overlap> RandomOverlaps(int n, double distance) { return testing::RandomOverlaps(n, distance, 5); }

class InnerSpherePair : public ::testing::Test {
 protected:
  void SetUp() override {
    a_ = Pack(*Ball(0.012, 0.001), 4.0 / 3.0 * kPi * std::pow(0.012, 3), 200);
    b_ = Pack(*Slab(0.001), 0.08 * 0.08 * 0.04, 300);
  }
  std::shared_ptr<const SpherePacking> a_, b_;
};

TEST_F(InnerSpherePair, StiffnessIsTheDerivativeOfTheWrench) {
  InnerSphereModel model(a_, b_, 1e6, SphereStiffness::kExact);
  int checked = 0;
  for (const Overlap& o : RandomOverlaps(10, 0.01)) {
    Overlap p = o;
    p.X_WB = Pose::Identity();
    p.X_WA.translation = Eigen::Vector3d(0.3 * o.X_WA.translation.x(), 0.3 * o.X_WA.translation.y(), 0.006);
    const ContactResult r = model.Evaluate(At(p.X_WA, p.X_WB));
    if (r.stats.points_in_contact == 0) continue;
    ++checked;
    const Matrix6d K = testing::CentralDifferenceStiffness(
        [&](const Pose& X) { return model.Evaluate(At(p.X_WA, X)).on_B.AsVector(); }, p.X_WB, 1e-7, 1e-6);
    EXPECT_LT((r.K_B - K).norm(), 1e-4 * K.norm()) << r.K_B << "\nvs\n" << K;
  }
  EXPECT_GE(checked, 5);
}

// The wrench is minus the gradient of the potential k_V V: central differences of the volume
// (the lens closed form, summed) in B's pose, translation and rotation. The force is
// conservative, so no cycle of poses does work on B.
TEST_F(InnerSpherePair, WrenchIsMinusTheGradientOfTheVolumePotential) {
  const double k_V = 1e6;
  InnerSphereModel model(a_, b_, k_V);
  int checked = 0;
  for (const Overlap& o : RandomOverlaps(10, 0.01)) {
    const Pose X_WA{o.X_WA.rotation, Eigen::Vector3d(0.3 * o.X_WA.translation.x(), 0.3 * o.X_WA.translation.y(), 0.006)};
    const ContactResult r = model.Evaluate(At(X_WA, Pose::Identity()));
    if (r.stats.points_in_contact < 3) continue;
    ++checked;
    Vector6d grad;
    const double h = 1e-7;
    for (int i = 0; i < 6; ++i) {
      Eigen::Vector3d step = Eigen::Vector3d::Zero();
      step[i % 3] = h;
      auto V = [&](double sign) {
        Pose X_WB = Pose::Identity();
        if (i < 3) {
          X_WB.translation = sign * step;
        } else {
          X_WB.rotation = RotationFromVector(sign * step);
        }
        model.Evaluate(At(X_WA, X_WB));
        return model.volume();
      };
      grad[i] = (V(1) - V(-1)) / (2 * h);
    }
    const Vector6d W = r.on_B.AsVector();
    EXPECT_LT((W + k_V * grad).norm(), 1e-5 * W.norm()) << W.transpose() << "\nvs\n" << -k_V * grad.transpose();
  }
  EXPECT_GE(checked, 5);
}

// K_B against the exact derivative: projected (the default) and halfspace are symmetric and
// negative semidefinite; projected is the exact one's symmetric part with its positive
// eigenvalues set to zero, equal to it where that is already negative semidefinite.
TEST_F(InnerSpherePair, StableStiffnessesAreNegativeSemidefiniteAndProjectTheExactOne) {
  InnerSphereModel exact(a_, b_, 1e6, SphereStiffness::kExact), projected(a_, b_, 1e6),
      halfspace(a_, b_, 1e6, SphereStiffness::kHalfspace);
  ASSERT_EQ(projected.stiffness(), SphereStiffness::kProjected);
  int indefinite = 0, checked = 0;
  for (const Overlap& o : RandomOverlaps(12, 0.012)) {
    const ContactResult e = exact.Evaluate(At(o.X_WA, o.X_WB));
    if (e.stats.points_in_contact == 0) continue;
    ++checked;
    const ContactResult p = projected.Evaluate(At(o.X_WA, o.X_WB)), h = halfspace.Evaluate(At(o.X_WA, o.X_WB));
    EXPECT_EQ(p.on_B.AsVector(), e.on_B.AsVector());
    EXPECT_EQ(h.on_B.AsVector(), e.on_B.AsVector());
    const double scale = e.K_B.norm();
    const Matrix6d S = 0.5 * (e.K_B + e.K_B.transpose());
    Eigen::SelfAdjointEigenSolver<Matrix6d> es(S);
    if (es.eigenvalues().maxCoeff() > 1e-9 * scale) ++indefinite;
    Matrix6d clamped = es.eigenvectors() * es.eigenvalues().cwiseMin(0.0).asDiagonal() * es.eigenvectors().transpose();
    EXPECT_LT((p.K_B - clamped).norm(), 1e-9 * scale);
    for (const Matrix6d* K : {&p.K_B, &h.K_B}) {
      EXPECT_LT((*K - K->transpose()).norm(), 1e-9 * scale);
      EXPECT_LE(Eigen::SelfAdjointEigenSolver<Matrix6d>(*K).eigenvalues().maxCoeff(), 1e-9 * scale);
    }
  }
  EXPECT_GE(checked, 6);
  EXPECT_GE(indefinite, 1);  // the exact derivative is not negative semidefinite: the case is tested
}

// The static virtual coupling (haptics/virtual_coupling.h) at a soft k_vc, the device pose held
// deep in contact: each Newton step moves H on the total energy E = coupling spring + k_V V
// (the volume as its closed form gives it, not the wrench). With a negative semidefinite K_B
// no step climbs; with the exact derivative steps climb (the energy the closed loop puts into
// the hand, docs/results-models.md).
// Returns the energy the counted steps climbed, as a fraction of the largest energy seen.
double ClimbingCouplingSteps(InnerSphereModel& model, double k_vc, double depth, double tilt) {
  VirtualCouplingParams params;
  params.k_vc = k_vc;
  params.max_force = 1e6;   // the linear spring: its energy below is exact
  params.max_torque = 1e6;
  const Pose X_WA = Translation(0.001, -0.002, 0.012);
  const Pose X_WD{Eigen::Quaterniond(Eigen::AngleAxisd(tilt, Eigen::Vector3d(1, 1, 0).normalized())),
                  Eigen::Vector3d(0, 0, depth)};
  auto energy = [&](const Pose& X_WH) {
    model.Evaluate(At(X_WA, X_WH));
    const double u = (X_WD.translation - X_WH.translation).squaredNorm();
    const double phi = CalcRotationVector(X_WD.rotation * X_WH.rotation.conjugate()).squaredNorm();
    return 0.5 * params.k_vc * u + 0.5 * params.k_vc_rot * phi + model.k_V() * model.volume();
  };
  StaticVirtualCoupling coupling(params);
  coupling.Reset(Pose::Identity());
  double climbed = 0;
  double E = energy(coupling.X_WH()), largest = E;
  for (int i = 0; i < 300; ++i) {
    const ContactResult r = model.Evaluate(At(X_WA, coupling.X_WH()));
    coupling.Update(X_WD, r.on_B, r.K_B);
    const double next = energy(coupling.X_WH());
    // From free space (K_B = 0) the first step into contact may overshoot, as any penalty
    // model's: the steps counted start in contact.
    if (r.stats.points_in_contact > 0 && next > E) climbed += next - E;
    E = next;
    largest = std::max(largest, E);
  }
  return climbed / largest;
}

TEST_F(InnerSpherePair, CouplingStepsDescendTheEnergyAtSoftCouplings) {
  InnerSphereModel projected(a_, b_, 1e6), halfspace(a_, b_, 1e6, SphereStiffness::kHalfspace),
      exact(a_, b_, 1e6, SphereStiffness::kExact);
  double exact_climbing = 0;
  for (const double k_vc : {400.0, 2000.0}) {
    for (const double depth : {0.004, 0.008, 0.012}) {
      for (const double tilt : {0.0, 0.3}) {
        const double p = ClimbingCouplingSteps(projected, k_vc, depth, tilt);
        const double h = ClimbingCouplingSteps(halfspace, k_vc, depth, tilt);
        const double e = ClimbingCouplingSteps(exact, k_vc, depth, tilt);
        std::printf("k_vc %g depth %g tilt %g: energy climbed / largest: projected %.2e halfspace %.2e exact %.2e\n",
                    k_vc, depth, tilt, p, h, e);
        // A step along a descent direction may still overshoot a little where the summed lens
        // volume is not convex (a few 1e-3 of the energy); the exact derivative climbs by 1e0.
        EXPECT_LT(p, 5e-3) << k_vc << " " << depth << " " << tilt;
        EXPECT_LT(h, 5e-3) << k_vc << " " << depth << " " << tilt;
        exact_climbing = std::max(exact_climbing, e);
      }
    }
  }
  EXPECT_GT(exact_climbing, 1.0);
}

TEST_F(InnerSpherePair, NewtonsThirdLawAndFrameCovariance) {
  InnerSphereModel ab(a_, b_, 1e6), ba(b_, a_, 1e6);
  const Pose T{Eigen::Quaterniond(0.3, -0.5, 0.7, 0.2).normalized(), Eigen::Vector3d(0.3, -0.1, 0.2)};
  int touching = 0;
  for (const Overlap& o : RandomOverlaps(12, 0.012)) {
    const ContactResult r = ab.Evaluate(At(o.X_WA, o.X_WB));
    if (r.stats.points_in_contact == 0) continue;
    ++touching;
    const double scale = r.on_B.force.norm();
    const ContactResult s = ba.Evaluate(At(o.X_WB, o.X_WA));
    EXPECT_LT((s.on_B.force + r.on_B.force).norm(), 1e-9 * scale);
    const Eigen::Vector3d tau_A = -(r.on_B.torque + (o.X_WB.translation - o.X_WA.translation).cross(r.on_B.force));
    EXPECT_LT((s.on_B.torque - tau_A).norm(), 1e-9 * scale * 0.05);
    const ContactResult t = ab.Evaluate(At(T * o.X_WA, T * o.X_WB));
    EXPECT_LT((t.on_B.force - T.rotation * r.on_B.force).norm(), 1e-9 * scale);
    EXPECT_LT((t.on_B.torque - T.rotation * r.on_B.torque).norm(), 1e-9 * scale * 0.05);
  }
  EXPECT_GE(touching, 6);
}

TEST_F(InnerSpherePair, BudgetDegradesGracefully) {
  InnerSphereModel model(a_, b_, 1e6);
  const Pose X_WA = Translation(0.001, -0.002, 0.002);
  const ContactResult full = model.Evaluate(At(X_WA, Pose::Identity()));
  ASSERT_GT(full.stats.points_in_contact, 10);
  double last_error = 1e300;
  for (const std::int64_t budget : {std::int64_t(20), std::int64_t(200), std::int64_t(2000), full.stats.nodes_visited}) {
    const ContactResult r = model.Evaluate(At(X_WA, Pose::Identity(), budget));
    // The level being expanded when the budget ran out finishes: at most one level's pairs more.
    EXPECT_LE(r.stats.nodes_visited, std::max<std::int64_t>(2 * budget, full.stats.nodes_visited));
    EXPECT_LT(r.on_B.force.z(), 0);  // the slab B is pushed down, away from the ball above it
    const double error = (r.on_B.force - full.on_B.force).norm();
    EXPECT_LE(error, last_error + 1e-12);
    last_error = error;
  }
  EXPECT_LT(last_error, 1e-12 * full.on_B.force.norm());
}

TEST(SpherePacking, FileRoundTripsAndADamagedFileIsNamed) {
  const auto p = Pack(*Ball(0.01, 0.001), 4.0 / 3.0 * kPi * 1e-6, 20);
  testing::TempDir dir;
  const auto path = dir / "p.bin";
  SaveSpherePacking(*p, path);
  const SpherePacking q = LoadSpherePacking(path);
  EXPECT_EQ(q.radii, p->radii);
  EXPECT_EQ(q.centers, p->centers);
  EXPECT_EQ(q.body_volume, p->body_volume);
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 3);
  try {
    LoadSpherePacking(path);
    FAIL() << "a truncated packing was read";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("p.bin"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace contactlab
