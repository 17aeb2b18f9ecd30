// The pressure-field (hydroelastic) model (baselines/pressure_field) against closed forms:
// a compliant sphere on a rigid halfspace, two equal compliant spheres, two compliant cubes
// pressed face to face; Newton's third law and frame covariance; K_B against central
// differences of the wrench; what it refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "baselines/pressure_field/contact_patches.h"
#include "baselines/pressure_field/lattice_blocks.h"
#include "baselines/pressure_field/pressure_field_model.h"
#include "baselines/pressure_field/pressure_field_params.h"
#include "baselines/volumetric_cases.h"
#include "contact/test_shells.h"
#include "scene/scene.h"
#include "util/config_node.h"
#include "geometry/pose.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::At;
using testing::Overlap;
using testing::SampleField;
using testing::Translation;
constexpr double kPi = std::numbers::pi;

// A ball of radius R at the origin, sampled with a grid node at its centre.
std::shared_ptr<DistanceField> Ball(double R, double h) { return testing::BallField(R, h, 4); }

// The halfspace z < 0 (exact under trilinear interpolation).
std::shared_ptr<DistanceField> Halfspace(double h) {
  return SampleField([](const Eigen::Vector3d& p) { return p.z(); }, Eigen::Vector3d(-0.05, -0.05, -0.03),
                     Eigen::Vector3d(0.05, 0.05, 0.03), h);
}

// A cube of half-size A at the origin (exact signed distance of a box).
std::shared_ptr<DistanceField> Cube(double a, double h) {
  const double m = std::ceil((a + 4 * h) / h) * h;
  return SampleField(
      [a](const Eigen::Vector3d& p) {
        const Eigen::Vector3d q = p.cwiseAbs() - Eigen::Vector3d::Constant(a);
        return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
      },
      Eigen::Vector3d::Constant(-m), Eigen::Vector3d::Constant(m), h);
}

// Elandt et al.'s compliant sphere (radius R, modulus E) against a rigid halfspace at depth
// DELTA, with the contact plane at height H above the centre: (E/R)[R π a² - (2π/3)(R³ - H³)].
double SphereForce(double E, double R, double H) {
  const double a2 = R * R - H * H;
  return E / R * (R * kPi * a2 - 2 * kPi / 3 * (R * R * R - H * H * H));
}


// MODEL, a compliant ball (A, radius R, modulus E) on a rigid halfspace (B, z < 0), against
// SphereForce at depths of 1, 4 and 10 mm, on a 1 mm lattice.
void ExpectSphereOnRigidHalfspace(PressureFieldModel& model, double R, double E, const std::string& what) {
  for (const double delta : {0.001, 0.004, 0.01}) {
    const ContactResult r = model.Evaluate(At(Translation(0.0003, -0.0002, R - delta), Pose::Identity()));
    const double H = R - delta;
    const double expected = SphereForce(E, R, H);
    SCOPED_TRACE(::testing::Message() << what << " delta " << delta);
    // Trilinear interpolation of the ball's distance overestimates it by up to h²/R inside, a
    // few per cent of the pressure when the depth is one cell; 1 % from two cells on.
    std::printf("sphere on rigid halfspace, %s, depth %g: force error %+.2f%%\n", what.c_str(), delta,
                100 * (-r.on_B.force.z() / expected - 1));
    EXPECT_NEAR(-r.on_B.force.z(), expected, (delta < 0.002 ? 0.04 : 0.01) * expected);  // pushes B down
    EXPECT_LT(r.on_B.force.head<2>().norm(), 1e-3 * expected);
    EXPECT_NEAR(r.stats.contact_area, kPi * (R * R - H * H), 0.02 * kPi * (R * R - H * H));
    EXPECT_EQ(r.stats.patches, 1);
    EXPECT_NEAR(r.stats.max_penetration, delta, 0.05 * delta);
    // The pressure's centre is under A's centre: torque about B's origin is c x F.
    const Eigen::Vector3d c(0.0003, -0.0002, 0);
    EXPECT_LT((r.on_B.torque - c.cross(r.on_B.force)).norm(), 1e-3 * expected * R);
  }
}

TEST(PressureField, CompliantSphereOnRigidHalfspaceMatchesTheClosedForm) {
  const double R = 0.02, E = 1e5;
  // A's field finer than B's (the lattice on A) and equal (the lattice on B).
  for (const double h_B : {0.002, 0.001}) {
    PressureFieldModel model({Ball(R, 0.001), E, false}, {Halfspace(h_B), 0, true});
    ExpectSphereOnRigidHalfspace(model, R, E, "h_B " + std::to_string(h_B));
  }
}

// pressure_lattice > 1: the surface extracted on every 2nd or 4th grid line of the finer field.
// On a ball field of 0.5 and 0.25 mm the lattice is 1 mm, as in the test above, and must meet
// the closed form within the same tolerances.
TEST(PressureField, CoarserLatticeOnAFinerFieldMatchesTheSphereClosedForm) {
  const double R = 0.02, E = 1e5;
  for (const int lattice : {2, 4}) {
    PressureFieldOptions o;
    o.lattice = lattice;
    PressureFieldModel model({Ball(R, 0.001 / lattice), E, false}, {Halfspace(0.002), 0, true}, o);
    ASSERT_NEAR(model.spacing(), 0.001, 1e-12);
    ExpectSphereOnRigidHalfspace(model, R, E, "lattice " + std::to_string(lattice));
  }
}

// A rigid ball of radius R whose lowest point is DELTA deep in a compliant halfspace (modulus E,
// its field D deep): the pressure E z / D over the ball's cap integrates to E / D times the
// cap's volume, pi delta^2 (3R - delta) / 3, straight up.
double RigidBallForce(double E, double D, double R, double delta) {
  return E / D * kPi * delta * delta * (3 * R - delta) / 3;
}

// A ball far stiffer than the plate it presses is the rigid ball: the surface is the ball's
// boundary, carrying the plate's pressure. Stiffness enters as the bodies' compliances in series
// (pressure_law.h): a modulus of 1e40 Pa once multiplied the fields' rounding into 1e18 N.
TEST(PressureField, StiffBallOnASoftPlateGivesTheRigidBallForceUpToAModulusOf1e40) {
  const double R = 0.02, E = 1e5, D = 0.03;  // the halfspace's field reaches 3 cm deep
  for (const double E_ball : {1e15, 1e20, 1e40, 0.0}) {
    const bool rigid = E_ball == 0;
    PressureFieldModel model({Ball(R, 0.001), rigid ? 1e5 : E_ball, rigid}, {Halfspace(0.001), E, false});
    ASSERT_NEAR(model.depth_B(), D, 1e-9);
    for (const double delta : {0.002, 0.006}) {
      const ContactResult r = model.Evaluate(At(Translation(0.0003, -0.0002, R - delta), Pose::Identity()));
      const double expected = RigidBallForce(E, D, R, delta);
      SCOPED_TRACE(::testing::Message() << "ball modulus " << (rigid ? "rigid" : std::to_string(E_ball)) << " delta "
                                        << delta);
      std::printf("ball of modulus %g on a 1e5 Pa plate, depth %g: %.6g N, rigid-ball limit %.6g N\n", E_ball, delta,
                  -r.on_B.force.z(), expected);
      // Trilinear interpolation of the ball's distance: 2 % low at 2 mm (two cells), 1 % from 6 mm.
      EXPECT_NEAR(-r.on_B.force.z(), expected, (delta < 0.004 ? 0.03 : 0.01) * expected);
      EXPECT_LT(r.on_B.force.head<2>().norm(), 1e-3 * expected);
      EXPECT_NEAR(r.stats.contact_area, 2 * kPi * R * delta, 0.03 * 2 * kPi * R * delta);  // the cap's area
    }
  }
}

// Moduli at the ends of their range (pressure_field_params.h) give the closed form: two equal
// spheres meet on the mid-plane, each carrying SphereForce at half the overlap.
TEST(PressureField, EqualSpheresAtTheModulusBoundsMatchTheClosedForm) {
  const double R = 0.015, delta = 0.004;
  for (const double E : {kMinPressureModulus, kMaxPressureModulus}) {
    PressureFieldModel model({Ball(R, 0.001), E, false}, {Ball(R, 0.001), E, false});
    const ContactResult r = model.Evaluate(At(Pose::Identity(), Translation(0, 0, 2 * R - delta)));
    const double expected = SphereForce(E, R, R - delta / 2);
    EXPECT_NEAR(r.on_B.force.z(), expected, 0.015 * expected) << E;
    EXPECT_TRUE(r.K_B.allFinite()) << E;
  }
}

// The surface kept for display (KeepContactSurface) is the one integrated, placed in the world:
// on a rigid plane turned and moved in the world, a disc of radius a = sqrt(R² - H²) in the
// plane, the pressure at each corner the sphere's E (1 - r/R), and the linear pressure over the
// triangles sums to the force.
TEST(PressureField, TheKeptSurfaceIsTheDiscOnTheRigidPlaneWithTheSpheresPressure) {
  const double R = 0.02, E = 1e5, delta = 0.006, H = R - delta;
  PressureFieldModel model({Ball(R, 0.001), E, false}, {Halfspace(0.001), 0, true});
  ContactSurface kept;
  model.LatestContactSurface(&kept);
  EXPECT_TRUE(kept.corners.empty());
  ASSERT_TRUE(model.KeepContactSurface(100000));
  const Pose X_WB{Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 0.5).normalized())),
                  Eigen::Vector3d(0.3, -0.1, 0.2)};
  const Pose X_WA = X_WB * Translation(0.0004, 0.0003, H);
  const ContactResult r = model.Evaluate(At(X_WA, X_WB));
  model.LatestContactSurface(&kept);
  ASSERT_GT(kept.corners.size(), 30u);
  ASSERT_EQ(kept.corners.size() % 3, 0u);
  ASSERT_EQ(kept.pressure.size(), kept.corners.size());
  const Eigen::Vector3d n = X_WB.R().col(2), o = X_WB.translation, c = X_WA.translation;
  double area = 0, force = 0;
  for (std::size_t i = 0; i < kept.corners.size(); ++i) {
    const Eigen::Vector3d x = kept.corners[i].cast<double>();
    EXPECT_NEAR((x - o).dot(n), 0, 1e-6);                   // in B's plane
    EXPECT_LE((x - c).norm(), R + 1e-3);                     // inside A
    EXPECT_NEAR(kept.pressure[i], E * (1 - (x - c).norm() / R), 0.02 * E);
  }
  for (std::size_t i = 0; i < kept.corners.size(); i += 3) {
    const Eigen::Vector3d a = kept.corners[i].cast<double>(), b = kept.corners[i + 1].cast<double>(),
                          d = kept.corners[i + 2].cast<double>();
    const double t = 0.5 * (b - a).cross(d - a).norm();
    area += t;
    force += t * (kept.pressure[i] + kept.pressure[i + 1] + kept.pressure[i + 2]) / 3;
  }
  EXPECT_NEAR(area, kPi * (R * R - H * H), 0.02 * kPi * (R * R - H * H));
  EXPECT_NEAR(area, r.stats.contact_area, 1e-5 * area);
  EXPECT_NEAR(force, r.on_B.force.norm(), 1e-4 * force);
  // At most the triangles asked for; none once apart.
  model.KeepContactSurface(10);
  model.Evaluate(At(X_WA, X_WB));
  model.LatestContactSurface(&kept);
  EXPECT_EQ(kept.corners.size(), 30u);
  model.Evaluate(At(X_WB * Translation(0, 0, 2 * R), X_WB));
  model.LatestContactSurface(&kept);
  EXPECT_TRUE(kept.corners.empty());
}

TEST(PressureField, EqualCompliantSpheresMeetOnTheMidPlane) {
  const double R = 0.015, E = 2e5;
  PressureFieldModel model({Ball(R, 0.001), E, false}, {Ball(R, 0.001), E, false});
  for (const double delta : {0.002, 0.006}) {
    const ContactResult r = model.Evaluate(At(Pose::Identity(), Translation(0, 0, 2 * R - delta)));
    const double expected = SphereForce(E, R, R - delta / 2);
    SCOPED_TRACE(::testing::Message() << "delta " << delta);
    std::printf("equal spheres, overlap %g: force error %+.2f%%\n", delta, 100 * (r.on_B.force.z() / expected - 1));
    EXPECT_NEAR(r.on_B.force.z(), expected, (delta < 0.004 ? 0.03 : 0.015) * expected);  // B above A is pushed up
    EXPECT_LT(r.on_B.force.head<2>().norm(), 1e-3 * expected);
    EXPECT_EQ(r.stats.patches, 1);
  }
}

// A box of half-sizes HALF at the origin (exact signed distance).
std::shared_ptr<DistanceField> Box(const Eigen::Vector3d& half, double h) {
  const Eigen::Vector3d m = ((half.array() + 4 * h) / h).ceil().matrix() * h;
  return SampleField(
      [half](const Eigen::Vector3d& p) {
        const Eigen::Vector3d q = p.cwiseAbs() - half;
        return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
      },
      -m, m, h);
}

TEST(PressureField, CubeFacePressedIntoAWiderBlockMatchesTheRimIntegral) {
  // A cube of half-size a under a block B twice as wide (same depth a, same modulus, so the
  // same pressure per metre of depth k = E/a), overlapping by delta. On the surface the
  // pressure is k times A's depth there, min(c, a - |x|, a - |y|) with c = delta/2 (a mid-plane
  // chamfered at 45 degrees toward A's side faces), so F_z = k ∫∫ min(c, a-|x|, a-|y|) dx dy =
  // k (4/3)(a³ - (a - c)³) and the area is (2a - 2c)² + √2 (4a² - (2a - 2c)²).
  const double a = 0.01, E = 1e5, h = 0.0005;
  PressureFieldModel model({Cube(a, h), E, false}, {Box(Eigen::Vector3d(2 * a, 2 * a, a), h), E, false});
  for (const double delta : {0.002, 0.004}) {
    const ContactResult r = model.Evaluate(At(Pose::Identity(), Translation(0, 0, 2 * a - delta)));
    const double c = delta / 2;
    const double expected = E / a * 4.0 / 3.0 * (a * a * a - (a - c) * (a - c) * (a - c));
    const double inner = (2 * a - 2 * c) * (2 * a - 2 * c);
    const double area = inner + std::sqrt(2.0) * (4 * a * a - inner);
    SCOPED_TRACE(::testing::Message() << "delta " << delta);
    std::printf("cube into block, overlap %g: force error %+.2f%%, area error %+.2f%%\n", delta,
                100 * (r.on_B.force.z() / expected - 1), 100 * (r.stats.contact_area / area - 1));
    EXPECT_NEAR(r.on_B.force.z(), expected, 0.02 * expected);
    EXPECT_LT(r.on_B.force.head<2>().norm(), 1e-3 * expected);
    EXPECT_NEAR(r.stats.contact_area, area, 0.03 * area);
    EXPECT_EQ(r.stats.patches, 1);
  }
}

TEST(PressureField, TwoSeparateContactsAreTwoPatches) {
  // A bar resting on two balls: two contact surfaces.
  const double R = 0.01;
  auto two_balls = SampleField(
      [R](const Eigen::Vector3d& p) {
        return std::min((p - Eigen::Vector3d(-0.02, 0, 0)).norm(), (p - Eigen::Vector3d(0.02, 0, 0)).norm()) - R;
      },
      Eigen::Vector3d(-0.035, -0.015, -0.015), Eigen::Vector3d(0.035, 0.015, 0.015), 0.001);
  PressureFieldModel model({two_balls, 1e5, false}, {Halfspace(0.001), 0, true});
  const ContactResult r = model.Evaluate(At(Translation(0, 0, R - 0.003), Pose::Identity()));
  EXPECT_EQ(r.stats.patches, 2);
  EXPECT_NEAR(-r.on_B.force.z(), 2 * SphereForce(1e5, R, R - 0.003), 0.02 * 2 * SphereForce(1e5, R, R - 0.003));
}

// Random poses with the two bodies overlapping: a sphere into a rounded cube.
std::vector<testing::Overlap> RandomOverlaps(int n, double distance) { return testing::RandomOverlaps(n, distance, 11); }

// The patch count against a flood fill over the lattice: random sets of cells in a 12^3
// lattice (with CountPatches' index margin), sparse to dense, joined by face, edge or corner.
TEST(PressureField, PatchCountMatchesAFloodFillOfTheCells) {
  constexpr int kN = 12, kMargin = 4;
  const std::int64_t stride_j = kN + kMargin, stride_k = stride_j * (kN + kMargin);
  std::mt19937 rng(5);
  for (const double density : {0.02, 0.08, 0.2, 0.5}) {
    for (int trial = 0; trial < 10; ++trial) {
      std::vector<std::uint8_t> occupied(kN * kN * kN);
      std::vector<std::int64_t> cells;
      for (int k = 0; k < kN; ++k) {
        for (int j = 0; j < kN; ++j) {
          for (int i = 0; i < kN; ++i) {
            if (std::uniform_real_distribution<double>(0, 1)(rng) >= density) continue;
            occupied[i + kN * (j + kN * k)] = 1;
            cells.push_back(i + stride_j * j + stride_k * k);
          }
        }
      }
      std::shuffle(cells.begin(), cells.end(), rng);
      // Flood fill with the 26 neighbours.
      int expected = 0;
      std::vector<std::uint8_t> seen(occupied.size());
      for (int start = 0; start < int(occupied.size()); ++start) {
        if (!occupied[start] || seen[start]) continue;
        ++expected;
        std::vector<int> stack = {start};
        seen[start] = 1;
        while (!stack.empty()) {
          const int c = stack.back();
          stack.pop_back();
          const int i = c % kN, j = c / kN % kN, k = c / (kN * kN);
          for (int dk = -1; dk <= 1; ++dk) {
            for (int dj = -1; dj <= 1; ++dj) {
              for (int di = -1; di <= 1; ++di) {
                const int a = i + di, b = j + dj, e = k + dk;
                if (a < 0 || b < 0 || e < 0 || a >= kN || b >= kN || e >= kN) continue;
                const int d = a + kN * (b + kN * e);
                if (occupied[d] && !seen[d]) {
                  seen[d] = 1;
                  stack.push_back(d);
                }
              }
            }
          }
        }
      }
      std::vector<std::int32_t> parent(cells.size());
      EXPECT_EQ(CountPatches(cells.data(), std::int64_t(cells.size()), stride_j, stride_k, parent.data()), expected)
          << "density " << density << " trial " << trial;
    }
  }
}

TEST(PressureField, NewtonsThirdLawHoldsExactlyWhenTheRolesAreExchanged) {
  auto ball = Ball(0.012, 0.0008);
  auto cube = Cube(0.01, 0.001);
  PressureFieldModel ab({ball, 1e5, false}, {cube, 3e5, false});
  PressureFieldModel ba({cube, 3e5, false}, {ball, 1e5, false});
  int touching = 0;
  for (const Overlap& o : RandomOverlaps(12, 0.018)) {
    const ContactResult r = ab.Evaluate(At(o.X_WA, o.X_WB));
    const ContactResult s = ba.Evaluate(At(o.X_WB, o.X_WA));
    if (r.stats.contact_area == 0) continue;
    ++touching;
    const double scale = r.on_B.force.norm();
    EXPECT_LT((s.on_B.force + r.on_B.force).norm(), 1e-12 * scale);
    // Torques about each body's origin: tau_A = -(tau_B + (o_B - o_A) x F_B).
    const Eigen::Vector3d expected = -(r.on_B.torque + (o.X_WB.translation - o.X_WA.translation).cross(r.on_B.force));
    EXPECT_LT((s.on_B.torque - expected).norm(), 1e-9 * scale * 0.02);
    EXPECT_DOUBLE_EQ(s.stats.contact_area, r.stats.contact_area);
  }
  EXPECT_GE(touching, 8);
}

TEST(PressureField, WrenchIsFrameCovariant) {
  auto ball = Ball(0.012, 0.001);
  auto cube = Cube(0.01, 0.001);
  PressureFieldModel model({ball, 1e5, false}, {cube, 1e5, false});
  const Pose T{Eigen::Quaterniond(0.3, -0.5, 0.7, 0.2).normalized(), Eigen::Vector3d(0.3, -0.1, 0.2)};
  for (const Overlap& o : RandomOverlaps(8, 0.018)) {
    const ContactResult r = model.Evaluate(At(o.X_WA, o.X_WB));
    const ContactResult s = model.Evaluate(At(T * o.X_WA, T * o.X_WB));
    const double scale = std::max(r.on_B.force.norm(), 1e-9);
    EXPECT_LT((s.on_B.force - T.rotation * r.on_B.force).norm(), 1e-5 * scale);
    EXPECT_LT((s.on_B.torque - T.rotation * r.on_B.torque).norm(), 1e-5 * scale * 0.02);
    EXPECT_NEAR(s.stats.contact_area, r.stats.contact_area, 1e-5 * r.stats.contact_area + 1e-12);
  }
}

TEST(PressureField, StiffnessMatchesCentralDifferencesOfTheWrench) {
  auto ball = Ball(0.012, 0.001);
  auto cube = Cube(0.01, 0.001);
  PressureFieldModel model({ball, 1e5, false}, {cube, 2e5, false});
  PressureFieldOptions plain;
  plain.stiffness = false;
  PressureFieldModel wrench_only({ball, 1e5, false}, {cube, 2e5, false}, plain);
  int checked = 0;
  for (const Overlap& o : RandomOverlaps(10, 0.016)) {
    const ContactResult r = model.Evaluate(At(o.X_WA, o.X_WB));
    if (r.stats.contact_area < 2e-5) continue;
    ++checked;
    const Matrix6d K = testing::CentralDifferenceStiffness(
        [&](const Pose& X) { return wrench_only.Evaluate(At(o.X_WA, X)).on_B.AsVector(); }, o.X_WB, 2e-5, 2e-3);
    // Rows in N and N m, columns per metre and per radian: compare each block on its own scale.
    for (int bi = 0; bi < 2; ++bi) {
      for (int bj = 0; bj < 2; ++bj) {
        const Eigen::Matrix3d a = r.K_B.block<3, 3>(3 * bi, 3 * bj), b = K.block<3, 3>(3 * bi, 3 * bj);
        const double scale = std::max(a.norm(), b.norm());
        SCOPED_TRACE(::testing::Message() << "block " << bi << bj << "\n" << a << "\nvs\n" << b);
        EXPECT_LT((a - b).norm(), 0.1 * scale + 1e-9);
      }
    }
  }
  EXPECT_GE(checked, 5);
}

// The lattice body's field at a block's vertices is read from its grid where the block lies
// inside it: the same as the field's own interpolation at those points, on every lattice
// spacing, for blocks inside the grid and blocks that reach past it.
TEST(PressureField, BlockSamplesAreTheFieldAtTheLatticeVertices) {
  auto ball = Ball(0.012, 0.001);
  const DistanceField& f = *ball;
  for (const int lattice : {1, 2, 3}) {
    const double h = f.spacing() * lattice;
    const Eigen::Vector3d origin = f.origin() + f.spacing() * Eigen::Vector3d(1, 2, 0);
    const int reach = int(f.dims().x() / lattice);
    int inside = 0, outside = 0;
    for (const std::array<std::int32_t, 3> blk : {std::array<std::int32_t, 3>{0, 0, 0}, {2, 3, 1}, {reach - 3, 1, 2},
                                                   {reach - 1, reach - 2, 0}}) {
      float phi[kBlockVerts];
      SampleBlock(f, origin, h, blk, phi);
      bool all_in = true;
      for (int k = 0; k < kVerts; ++k) {
        for (int j = 0; j < kVerts; ++j) {
          for (int i = 0; i < kVerts; ++i) {
            const Eigen::Vector3d x = origin + h * Eigen::Vector3d(blk[0] + i, blk[1] + j, blk[2] + k);
            all_in = all_in && f.Inside(x);
            // To the rounding of a float interpolation at float coordinates (a few units in the
            // last place of the position and of the value).
            EXPECT_NEAR(phi[VertexIndex(i, j, k)], f.Distance(x), 1e-6 * (std::abs(f.Distance(x)) + x.cwiseAbs().maxCoeff()))
                << "lattice " << lattice << " block " << blk[0] << " " << blk[1] << " " << blk[2];
          }
        }
      }
      ++(all_in ? inside : outside);
    }
    EXPECT_GE(inside, 2);
    EXPECT_GE(outside, 1);
  }
}

// The time budget counts lattice cells. Past it the lattice doubles until the cells fit, so the
// answer is that of the model configured on the coarser lattice (the same fields on the same
// grid), wrench and K_B, and the stat says how many doublings; within it nothing changes.
TEST(PressureField, ABudgetBelowTheCellsCoarsensTheLatticeAsTheLatticeKeyWould) {
  auto ball = Ball(0.012, 0.001);
  auto cube = Cube(0.01, 0.001);
  PressureFieldModel model({ball, 1e5, false}, {cube, 2e5, false});
  int degraded_seen = 0;
  for (const Overlap& o : RandomOverlaps(6, 0.016)) {
    ContactQuery q = At(o.X_WA, o.X_WB);
    const ContactResult full = model.Evaluate(q);
    if (full.stats.contact_area < 2e-5) continue;
    EXPECT_EQ(full.stats.degraded, 0);
    // The cells of the blocks kept: nodes_visited less the octree nodes (at most a few hundred).
    q.node_budget = full.stats.nodes_visited * 10;
    const ContactResult roomy = model.Evaluate(q);
    EXPECT_EQ(roomy.stats.degraded, 0);
    EXPECT_EQ(roomy.on_B.AsVector(), full.on_B.AsVector());
    for (const std::int64_t budget : {full.stats.nodes_visited / 3, full.stats.nodes_visited / 20, std::int64_t(64)}) {
      q.node_budget = budget;
      const ContactResult r = model.Evaluate(q);
      ASSERT_GE(r.stats.degraded, 1) << "budget " << budget;
      ASSERT_LE(r.stats.degraded, kMaxLatticeDoublings);
      degraded_seen = std::max(degraded_seen, r.stats.degraded);
      PressureFieldOptions coarse;
      coarse.lattice = 1 << r.stats.degraded;
      PressureFieldModel reference({ball, 1e5, false}, {cube, 2e5, false}, coarse);
      const ContactResult c = reference.Evaluate(At(o.X_WA, o.X_WB));
      EXPECT_EQ(r.on_B.AsVector(), c.on_B.AsVector()) << "budget " << budget;
      EXPECT_EQ(r.K_B, c.K_B) << "budget " << budget;
      EXPECT_EQ(r.stats.points_in_contact, c.stats.points_in_contact);
    }
  }
  EXPECT_GE(degraded_seen, 2);
}

// B's pose moved along coordinate C of a world twist: C < 3 translates by STEP along world axis
// C, C >= 3 rotates by STEP (radians) about world axis C - 3 through B's origin.
Pose TwistedPose(const Pose& X_WB, int c, double step) {
  Pose X = X_WB;
  if (c < 3) {
    X.translation[c] += step;
  } else {
    Eigen::Vector3d w = Eigen::Vector3d::Zero();
    w[c - 3] = step;
    X.rotation = (RotationFromVector(w) * X.rotation).normalized();
  }
  return X;
}

// K_B is the exact derivative of the discretised wrench, carried through the integration in
// forward mode. The reference: central differences of whole evaluations (every block culled
// and every cell cut again at the moved pose), with either body the lattice one, compliant or
// rigid. The wrench is smooth in the pose except where a moved vertex of the lattice crosses a
// face of the other field's grid (a kink: the trilinear field's gradient jumps) or the cut of a
// cell changes shape, and the fields are sampled at float positions, which blurs a difference
// at a step of 1e-3 cells by about 1e-3 of it. Measured: half the columns agree to 5e-4 of their
// size, 90 % to 2e-3, all to 1 %; the median difference halves with the step down to 3e-3
// cells and then stays, as the kinks and the float positions predict. So 90 % of the columns
// must agree to 3e-3 and every one to 2 %. A derivative that left out the rotation of the sums'
// frame, the moment arm of B's origin, a clip or the pressure's change along the surface is
// off by far more.
TEST(PressureField, StiffnessIsTheDerivativeOfTheDiscretisedWrench) {
  auto ball = Ball(0.012, 0.001);
  auto fine_ball = Ball(0.012, 0.0008);
  auto cube = Cube(0.01, 0.001);
  struct Case {
    PressureFieldSide A, B;
  };
  const Case cases[] = {{{ball, 1e5, false}, {cube, 2e5, false}},       // B the lattice body
                        {{fine_ball, 1e5, false}, {cube, 2e5, false}},  // A the lattice body
                        {{ball, 1e5, false}, {cube, 0, true}},
                        {{fine_ball, 0, true}, {cube, 3e5, false}}};
  PressureFieldOptions plain;
  plain.stiffness = false;
  int columns = 0, close = 0;
  double worst = 0;
  for (const Case& k : cases) {
    PressureFieldModel model(k.A, k.B);
    PressureFieldModel wrench_only(k.A, k.B, plain);
    const double step_x = 1e-3 * model.spacing(), step_w = step_x / 0.02;
    for (const Overlap& o : RandomOverlaps(10, 0.016)) {
      const ContactResult r = model.Evaluate(At(o.X_WA, o.X_WB));
      if (r.stats.contact_area < 2e-5) continue;
      const Vector6d w0 = wrench_only.Evaluate(At(o.X_WA, o.X_WB)).on_B.AsVector();
      EXPECT_EQ(r.on_B.AsVector(), w0) << "the wrench does not depend on whether K_B is taken";
      for (int c = 0; c < 6; ++c) {
        const double step = c < 3 ? step_x : step_w;
        const Vector6d plus = wrench_only.Evaluate(At(o.X_WA, TwistedPose(o.X_WB, c, step))).on_B.AsVector();
        const Vector6d minus = wrench_only.Evaluate(At(o.X_WA, TwistedPose(o.X_WB, c, -step))).on_B.AsVector();
        const Vector6d reference = (plus - minus) / (2 * step);
        const Vector6d column = r.K_B.col(c);
        // Force rows and torque rows, each on its own scale.
        const double f = std::max(column.head<3>().norm(), reference.head<3>().norm()) + 1e-12;
        const double t = std::max(column.tail<3>().norm(), reference.tail<3>().norm()) + 1e-15;
        const double error = std::max((column.head<3>() - reference.head<3>()).norm() / f,
                                      (column.tail<3>() - reference.tail<3>()).norm() / t);
        ++columns;
        if (error <= 3e-3) ++close;
        worst = std::max(worst, error);
      }
    }
  }
  std::printf("K_B columns within 3e-3 of central differences: %d of %d; largest difference %.3g\n", close, columns,
              worst);
  EXPECT_GE(columns, 120);
  EXPECT_GE(close, columns - columns / 10);
  EXPECT_LT(worst, 0.02);
}

// Both bodies at 1e307 Pa once rendered no contact at all (E / depth overflowed); 1e306 gave
// 8.6e300 N. The modulus row bounds it to physical values (pressure_field_params.h): a scene
// past either bound is refused when it loads, naming the key and the range, and one at the
// bounds loads (EqualSpheresAtTheModulusBoundsMatchTheClosedForm renders them).
TEST(PressureField, ModulusOf1e307IsRefusedWhenTheSceneLoadsNamingTheKeyAndRange) {
  auto scene = [](const std::string& modulus) {
    return "name: stiff\nbodies:\n"
           "  - {name: ball, mesh: \"sphere:0.02\", role: pointshell, pressure_field: {modulus: " + modulus + "}}\n"
           "  - {name: plate, mesh: \"box:0.05,0.05,0.01\", role: field, pressure_field: {modulus: " + modulus + "}}\n";
  };
  for (const std::string modulus : {"1e307", "1.1e15", "0.5"}) {
    try {
      ParseScene(ConfigNode::LoadString(scene(modulus), "stiff.yaml"));
      ADD_FAILURE() << "modulus " << modulus << " was accepted";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("pressure_field.modulus: must be in [1, 1e+15], got " + modulus), std::string::npos) << what;
    }
  }
  for (const std::string modulus : {"1", "1e15"}) {
    EXPECT_NO_THROW(ParseScene(ConfigNode::LoadString(scene(modulus), "stiff.yaml"))) << modulus;
  }
}

TEST(PressureField, RefusesSoupsAndTwoRigidBodies) {
  auto soup = Ball(0.01, 0.001);
  std::const_pointer_cast<DistanceField>(soup)->mutable_info().mode = "soup";
  std::const_pointer_cast<DistanceField>(soup)->mutable_info().source = "holed-cup.obj";
  try {
    PressureFieldModel({soup, 1e5, false}, {Ball(0.01, 0.001), 1e5, false});
    FAIL() << "a soup's field was accepted";
  } catch (const Error& e) {
    // It names the body, its mesh and the fix.
    const std::string what = e.what();
    EXPECT_NE(what.find("body A (mesh holed-cup.obj)"), std::string::npos) << what;
    EXPECT_NE(what.find("soup"), std::string::npos) << what;
    EXPECT_NE(what.find("close its holes"), std::string::npos) << what;
  }
  try {
    PressureFieldModel({Ball(0.01, 0.001), 1e5, true}, {Ball(0.01, 0.001), 1e5, true});
    FAIL() << "two rigid bodies were accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("both bodies are rigid"), std::string::npos) << e.what();
  }
}

TEST(PressureField, ApartGivesNothing) {
  PressureFieldModel model({Ball(0.01, 0.001), 1e5, false}, {Ball(0.01, 0.001), 1e5, false});
  const ContactResult r = model.Evaluate(At(Pose::Identity(), Translation(0, 0, 0.0205)));
  EXPECT_EQ(r.on_B.force, Eigen::Vector3d::Zero());
  EXPECT_EQ(r.stats.contact_area, 0);
  EXPECT_EQ(r.stats.patches, 0);
}

}  // namespace
}  // namespace contactlab
