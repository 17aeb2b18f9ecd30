// Tests of static virtual coupling (Barbič & James 2008, sec. 5): analytic gradients against
// finite differences, the 6x6 LU solve against a reference, and the felt stiffness bound.
#include "haptics/virtual_coupling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "haptics/halfspace_contact_model.h"
#include "geometry/rotation_math.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Applies the perturbation convention of contact_model.h to X: (dx, dθ) in world coordinates.
Pose Perturb(const Pose& X, const Vector6d& d) {
  return Pose{(RotationFromVector(d.tail<3>()) * X.rotation).normalized(), X.translation + d.head<3>()};
}

// Central finite differences of WRENCH(X_WH) with respect to H's pose.
template <typename F>
Matrix6d FiniteDifferenceGradient(F wrench, const Pose& X_WH, double h) {
  Matrix6d K;
  for (int j = 0; j < 6; ++j) {
    Vector6d d = Vector6d::Zero();
    d[j] = h;
    K.col(j) = (wrench(Perturb(X_WH, d)).AsVector() - wrench(Perturb(X_WH, -d)).AsVector()) / (2 * h);
  }
  return K;
}

Pose RandomPose(std::mt19937& rng, double pos_scale, double max_angle) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Vector3d axis(u(rng), u(rng), u(rng));
  axis.normalize();
  const double angle = max_angle * std::abs(u(rng));
  return Pose{Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)), pos_scale * Eigen::Vector3d(u(rng), u(rng), u(rng))};
}

TEST(RotationMath, RotationVectorInvertsExponential) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int s = 0; s < 200; ++s) {
    Eigen::Vector3d w(u(rng), u(rng), u(rng));
    w *= 3.0 / std::sqrt(3.0) * std::abs(u(rng));  // |w| < pi
    EXPECT_LT((CalcRotationVector(RotationFromVector(w)) - w).norm(), 1e-12) << w.transpose();
  }
  EXPECT_LT(CalcRotationVector(Eigen::Quaterniond::Identity()).norm(), 1e-300);
}

TEST(RotationMath, InverseRightJacobianMatchesFiniteDifferences) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int s = 0; s < 50; ++s) {
    const Eigen::Vector3d phi = 2.5 * Eigen::Vector3d(u(rng), u(rng), u(rng)) / std::sqrt(3.0);
    const Eigen::Matrix3d J = CalcInverseRightJacobian(phi);
    const double h = 1e-6;
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d v = h * Eigen::Vector3d::Unit(j);
      const Eigen::Vector3d fd = (CalcRotationVector(RotationFromVector(phi) * RotationFromVector(v)) -
                                  CalcRotationVector(RotationFromVector(phi) * RotationFromVector(-v))) /
                                 (2 * h);
      EXPECT_LT((J.col(j) - fd).norm(), 1e-7) << "phi " << phi.transpose();
    }
  }
}

// The coupling gradient must match finite differences in the linear region, with the force
// saturated, with the torque saturated, and at large rotation errors.
TEST(VirtualCoupling, GradientMatchesFiniteDifferencesInAllRegimes) {
  std::mt19937 rng(11);
  VirtualCouplingParams p;
  p.k_vc = 700.0 / 3.0;
  p.k_vc_rot = 1.0 / 3.0;
  p.max_force = 5.0;
  p.max_torque = 0.4;
  struct Case {
    double pos, angle;
    const char* name;
  };
  const Case cases[] = {{0.005, 0.2, "linear"}, {0.05, 0.2, "force saturated"}, {0.005, 2.0, "torque saturated"},
                        {0.05, 2.5, "both saturated, large rotation"}};
  for (const Case& c : cases) {
    for (int s = 0; s < 20; ++s) {
      const Pose X_WH = RandomPose(rng, 0.1, 3.0);
      const Pose X_HD = RandomPose(rng, c.pos, c.angle);
      const Pose X_WD = X_WH * X_HD;
      auto wrench = [&](const Pose& X) { return CalcCouplingWrench(X_WD, X, p); };
      const Matrix6d K = CalcCouplingGradient(X_WD, X_WH, p);
      const Matrix6d K_fd = FiniteDifferenceGradient(wrench, X_WH, 1e-7);
      EXPECT_LT((K - K_fd).norm(), 2e-5 * (1 + K.norm())) << c.name << "\nK\n" << K << "\nFD\n" << K_fd;
    }
  }
}

TEST(VirtualCoupling, WrenchSaturatesToMaxForceAndTorque) {
  VirtualCouplingParams p;
  const Pose X_WH = Pose::Identity();
  const Pose X_WD{Eigen::Quaterniond(Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitY())), Eigen::Vector3d(1, 0, 0)};
  const Wrench w = CalcCouplingWrench(X_WD, X_WH, p);
  EXPECT_NEAR(w.force.norm(), p.max_force, 1e-12);
  EXPECT_GT(w.force.x(), 0);  // pulls H toward D
  EXPECT_NEAR(w.torque.norm(), p.max_torque, 1e-12);
  EXPECT_GT(w.torque.y(), 0);
  // Linear region: exactly k (p_D - p_H).
  const Pose X_WD2 = Pose::FromTranslation(Eigen::Vector3d(1e-3, -2e-3, 0.5e-3));
  EXPECT_LT((CalcCouplingWrench(X_WD2, X_WH, p).force - p.k_vc * X_WD2.translation).norm(), 1e-12);
}

TEST(HalfspaceContactModel, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(17);
  HalfspaceContactModel model(MakeBoxSamplePoints(Eigen::Vector3d(0.02, 0.03, 0.01), 3), 1000.0 / 3.0);
  const Pose X_WA = RandomPose(rng, 0.01, 0.3);
  int tested = 0;
  for (int s = 0; s < 40; ++s) {
    Pose X_WB = RandomPose(rng, 0.015, 3.0);
    X_WB.translation += X_WA.translation;
    ContactQuery q;
    q.X_WA = X_WA;
    q.X_WB = X_WB;
    const ContactResult r = model.Evaluate(q);
    if (r.stats.points_in_contact == 0) continue;
    ++tested;
    auto wrench = [&](const Pose& X) {
      ContactQuery qq = q;
      qq.X_WB = X;
      return model.Evaluate(qq).on_B;
    };
    // Tiny steps so no point crosses the plane (the model is piecewise linear in depth).
    const Matrix6d K_fd = FiniteDifferenceGradient(wrench, X_WB, 1e-9);
    EXPECT_LT((r.K_B - K_fd).norm(), 1e-4 * (1 + r.K_B.norm())) << "\nK\n" << r.K_B << "\nFD\n" << K_fd;
  }
  EXPECT_GT(tested, 10);
}

// Update's solve must equal a reference solve of (K_VC + K_C) delta = -(W_VC + W_C) on random
// (non-symmetric, well-conditioned) systems.
TEST(VirtualCoupling, EquilibriumSolveMatchesReferenceOnRandomSystems) {
  std::mt19937 rng(23);
  std::normal_distribution<double> g(0, 1);
  VirtualCouplingParams p;
  p.max_step_translation = p.max_step_rotation = 1e6;  // do not clamp: compare the raw solve
  for (int s = 0; s < 100; ++s) {
    StaticVirtualCoupling vc(p);
    const Pose X_WH = RandomPose(rng, 0.05, 1.0);
    const Pose X_WD = X_WH * RandomPose(rng, 0.005, 0.3);
    vc.Reset(X_WH);
    Matrix6d K_c;
    for (int i = 0; i < 36; ++i) K_c(i / 6, i % 6) = 100.0 * g(rng);
    K_c -= 2000.0 * Matrix6d::Identity();  // contact stiffness: dominantly restoring
    Wrench w_c;
    w_c.force = Eigen::Vector3d(g(rng), g(rng), g(rng));
    w_c.torque = 0.1 * Eigen::Vector3d(g(rng), g(rng), g(rng));
    const CouplingStep step = vc.Update(X_WD, w_c, K_c);
    // Reference: full-pivoting Householder QR.
    const Matrix6d K = CalcCouplingSolveGradient(X_WD, X_WH, p) + K_c;
    const Vector6d rhs = -(CalcCouplingWrench(X_WD, X_WH, p).AsVector() + w_c.AsVector());
    const Vector6d ref = K.fullPivHouseholderQr().solve(rhs);
    EXPECT_LT((step.delta - ref).norm(), 1e-10 * (1 + ref.norm()));
    // The damped move is (1 - alpha) of the solve.
    EXPECT_LT((step.X_WH.translation - X_WH.translation - (1 - p.alpha) * ref.head<3>()).norm(), 1e-12);
  }
}

// In free space H converges to D geometrically (factor alpha per cycle), and the rendered
// wrench is minus the coupling wrench on H.
TEST(VirtualCoupling, FreeSpaceConvergesToDeviceAtRateAlpha) {
  VirtualCouplingParams p;
  StaticVirtualCoupling vc(p);
  const Pose X_WD{Eigen::Quaterniond(Eigen::AngleAxisd(0.1, Eigen::Vector3d(1, 2, 3).normalized())),
                  Eigen::Vector3d(0.002, -0.001, 0.003)};
  vc.Reset(Pose::Identity());
  double prev = X_WD.translation.norm();
  for (int i = 0; i < 30; ++i) {
    const CouplingStep st = vc.Update(X_WD, Wrench{}, Matrix6d::Zero());
    const double err = (X_WD.translation - st.X_WH.translation).norm();
    EXPECT_NEAR(err, p.alpha * prev, 1e-12);
    prev = err;
    EXPECT_LT((st.to_device.force + st.coupling_on_H.force).norm(), 1e-15);
  }
  EXPECT_LT(CalcRotationVector(X_WD.rotation * vc.X_WH().rotation.conjugate()).norm(), 1e-8);
}

// The paper's alpha is the damping of a 1 ms cycle: at any rate H closes a free-space gap as
// gap0 * alpha^(t / 1 ms), so after each millisecond the gap is the same at 500 Hz, 1, 2, 5 and
// 10 kHz (at 1 kHz the cycle's alpha is the paper's own, exactly).
TEST(VirtualCoupling, AtAnyRateTheGapClosesWithThePapersTimeConstant) {
  VirtualCouplingParams paper;
  EXPECT_EQ(CouplingAtRate(paper, 1e-3).alpha, paper.alpha);
  const Pose X_WD = Pose::FromTranslation(Eigen::Vector3d(0.002, -0.001, 0.003));
  const double gap0 = X_WD.translation.norm();
  for (const double hz : {500.0, 1000.0, 2000.0, 5000.0, 10000.0}) {
    const VirtualCouplingParams p = CouplingAtRate(paper, 1.0 / hz);
    EXPECT_GT(p.alpha, 0.0);
    EXPECT_LT(p.alpha, 1.0);
    StaticVirtualCoupling vc(p);
    vc.Reset(Pose::Identity());
    const int cycles_per_4ms = int(std::lround(4e-3 * hz));
    for (int i = 1; i <= cycles_per_4ms; ++i) {
      const CouplingStep st = vc.Update(X_WD, Wrench{}, Matrix6d::Zero());
      const double t = i / hz;
      const double gap = (X_WD.translation - st.X_WH.translation).norm();
      EXPECT_NEAR(gap, gap0 * std::pow(paper.alpha, t / 1e-3), 1e-12 * gap0) << hz << " Hz, cycle " << i;
    }
  }
}

// Paper sec. 5: with l points of stiffness k_C in contact the felt stiffness is
// 1 / (1/(l k_C) + 1/k_VC). Press the device a depth into a halfspace and let H settle.
TEST(VirtualCoupling, FeltStiffnessIsSeriesOfContactAndCoupling) {
  const double k_c = 500.0 / 3.0;
  Eigen::Matrix3Xd pts(3, 4);  // four points in one plane: l = 4 in contact
  pts << 0.01, -0.01, 0.01, -0.01, 0.01, 0.01, -0.01, -0.01, 0, 0, 0, 0;
  HalfspaceContactModel model(pts, k_c);
  VirtualCouplingParams p;
  p.max_force = 100;
  StaticVirtualCoupling vc(p);
  vc.Reset(Pose::FromTranslation(Eigen::Vector3d(0, 0, 0.001)));
  const double depth = 0.002;
  const Pose X_WD = Pose::FromTranslation(Eigen::Vector3d(0, 0, -depth));
  CouplingStep st;
  for (int i = 0; i < 200; ++i) {
    ContactQuery q;
    q.X_WB = vc.X_WH();
    const ContactResult r = model.Evaluate(q);
    st = vc.Update(X_WD, r.on_B, r.K_B);
  }
  const double k_felt = 1.0 / (1.0 / (4 * k_c) + 1.0 / p.k_vc);
  EXPECT_NEAR(st.to_device.force.z(), k_felt * depth, 1e-9);
  EXPECT_LT(k_felt, p.k_vc);
}

TEST(VirtualCoupling, NonFiniteSolveLeavesBodyInPlace) {
  StaticVirtualCoupling vc(VirtualCouplingParams{});
  const Pose X_WH = Pose::FromTranslation(Eigen::Vector3d(0.01, 0, 0));
  vc.Reset(X_WH);
  Matrix6d K_c = Matrix6d::Zero();
  K_c(0, 0) = std::numeric_limits<double>::quiet_NaN();
  const CouplingStep st = vc.Update(Pose::Identity(), Wrench{}, K_c);
  EXPECT_FALSE(st.solve_ok);
  EXPECT_EQ(st.X_WH.translation, X_WH.translation);
}

TEST(VirtualCoupling, InvalidParametersAreRejectedByName) {
  VirtualCouplingParams p;
  p.alpha = 1.0;
  try {
    StaticVirtualCoupling vc(p);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("alpha"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace contactlab
