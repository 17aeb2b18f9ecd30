// Tests of the analytic eq. (2) limits (baselines/reference/analytic_references.h) against
// each other and against hand-integrated cases.
#include "baselines/reference/analytic_references.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry/procedural_shapes.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr double kC = 2000;
constexpr int kL = 10;

TEST(AnalyticReferences, SphereHalfspaceIsTheLimitOfSphereSphereAsBGrows) {
  const double R = 1.0 / 30, H = R - 0.003;
  const double F = SphereHalfspaceForceMagnitude(R, H, kC, kL);
  // B a sphere of radius 1000 m whose top touches z = 0: the plane's curvature is negligible.
  const double R_B = 1000;
  const ForceLimit s = SphereSphereLimit(Eigen::Vector3d(0, 0, H), R, Eigen::Vector3d(0, 0, -R_B), R_B,
                                         Eigen::Vector3d::Zero(), kC, kL);
  EXPECT_NEAR(s.on_B.force.z(), -F, 1e-4 * F);
  EXPECT_NEAR(s.on_B.force.head<2>().norm(), 0, 1e-12);
  EXPECT_NEAR(s.max_penetration, R - H, 1e-9);
}

TEST(AnalyticReferences, SphereHalfspaceAtHalfDepthMatchesHandIntegral) {
  // H = 0: mean of d N·z over the lower hemisphere = -R/3 (∫ -R u · u du / ∫ du on [0,1]).
  const double R = 1.0 / 30;
  EXPECT_NEAR(SphereHalfspaceForceMagnitude(R, 0, kC, kL), kC * kL * R / 3, 1e-12);
  const ForceLimit f = SphereHalfspaceLimit(Eigen::Vector3d(0.1, 0.2, 0.3), R, Eigen::Vector3d(0.1, 0.2, 0.3),
                                            Eigen::Vector3d::UnitX(), Eigen::Vector3d(0.1, 0.2, 0.3), kC, kL);
  EXPECT_NEAR(f.on_B.force.x(), -kC * kL * R / 3, 1e-9);  // pushes B away from the sphere
  EXPECT_NEAR(f.on_B.torque.norm(), 0, 1e-12);            // through B's origin here
  EXPECT_NEAR(f.area_inside, 2 * M_PI * R * R, 1e-12);
}

TEST(AnalyticReferences, FineIcospherePolyhedronConvergesToSphereFormula) {
  const double R = 1.0 / 30, H = R - 0.004;
  const TriangleMesh sphere = MakeSphere(R, 6);
  Pose X_WA;
  X_WA.translation = Eigen::Vector3d(0, 0, H);
  const ForceLimit p = PolyhedronHalfspaceLimit(sphere, X_WA, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                                                Eigen::Vector3d(0, 0, -0.05), kC, kL);
  const double F = SphereHalfspaceForceMagnitude(R, H, kC, kL);
  EXPECT_NEAR(p.on_B.force.z(), -F, 0.01 * F);
  EXPECT_LT(p.on_B.force.head<2>().norm(), 0.01 * F);
}

TEST(AnalyticReferences, AxisAlignedBoxMatchesHandIntegral) {
  // Bottom face fully submerged (d = -δ, N = +z), side strips of height δ cancel sideways:
  // F_z = -k L δ 4ab / (4ab + 4(a+b)δ).
  const double a = 1.0 / 30, b = 1.0 / 40, c = 1.0 / 50, delta = 0.002;
  const TriangleMesh box = MakeBox(Eigen::Vector3d(a, b, c), 2);
  Pose X_WA;
  X_WA.translation = Eigen::Vector3d(0.01, 0.02, c - delta);
  const ForceLimit p = PolyhedronHalfspaceLimit(box, X_WA, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(),
                                                Eigen::Vector3d(0.01, 0.02, -0.1), kC, kL);
  const double expected = -kC * kL * delta * 4 * a * b / (4 * a * b + 4 * (a + b) * delta);
  EXPECT_NEAR(p.on_B.force.z(), expected, 1e-9 * std::abs(expected));
  EXPECT_NEAR(p.on_B.force.head<2>().norm(), 0, 1e-9 * std::abs(expected));
  EXPECT_NEAR(p.area_inside, 4 * a * b + 4 * (a + b) * delta, 1e-12);
  // The box sits over B's origin: the resultant passes through it.
  EXPECT_NEAR(p.on_B.torque.norm(), 0, 1e-9 * std::abs(expected));
}

TEST(AnalyticReferences, RejectsOutOfRangeInputs) {
  EXPECT_THROW(SphereHalfspaceForceMagnitude(-1, 0, kC, kL), Error);
  EXPECT_THROW(SphereHalfspaceForceMagnitude(1, 1.5, kC, kL), Error);
  EXPECT_THROW(SphereHalfspaceForceMagnitude(1, 0.5, kC, 0), Error);
  EXPECT_THROW(SphereSphereLimit(Eigen::Vector3d::Zero(), 1, Eigen::Vector3d(0.5, 0, 0), 1, Eigen::Vector3d::Zero(),
                                 kC, kL),
               Error);
  EXPECT_THROW(SphereHalfspaceLimit(Eigen::Vector3d::Zero(), 1, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 2),
                                    Eigen::Vector3d::Zero(), kC, kL),
               Error);
}

}  // namespace
}  // namespace contactlab
