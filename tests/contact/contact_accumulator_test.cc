// The accumulator's wrench and gradient against the eq. (1) sums written out with explicit
// 3x3 matrix products, K = sum over points of the derivative of k d N and of p x (k d N).
#include "contact/contact_accumulator.h"

#include <gtest/gtest.h>

#include <random>

namespace contactlab {
namespace {

Eigen::Matrix3d SkewOf(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

TEST(ContactAccumulator, GradientEqualsExplicitMatrixProducts) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  auto random_vector = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  ContactAccumulator acc;
  Eigen::Vector3d F = Eigen::Vector3d::Zero(), T = Eigen::Vector3d::Zero();
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero(), MP = M, PM = M, PMP = M;
  for (int i = 0; i < 50; ++i) {
    const Eigen::Vector3d p = 0.05 * random_vector(), N = random_vector().normalized();
    const Eigen::Vector3d g = i % 2 ? N : random_vector().normalized();  // halfspace and field rules
    const double d = -1e-3 * (1 + u(rng));
    acc.Add(p, N, d, g);
    F += d * N;
    T += p.cross(d * N);
    const Eigen::Matrix3d Mi = N * g.transpose(), P = SkewOf(p);
    M += Mi;
    MP += Mi * P;
    PM += P * Mi;
    PMP += P * Mi * P;
  }
  PenaltyParams penalty;
  penalty.k_C = 300;
  penalty.L = 0;  // no count scaling: K is k_C times the sums
  const Pose X_WB = Pose::Identity();
  ContactResult r;
  acc.Finish(penalty, X_WB, &r);
  const double k = penalty.k_C;
  EXPECT_LT((r.on_B.force - k * F).norm(), 1e-12);
  EXPECT_LT((r.on_B.torque - k * T).norm(), 1e-12);
  Matrix6d K;
  K << -k * M, k * MP, SkewOf(k * F) - k * PM, k * PMP;
  EXPECT_LT((r.K_B - K).cwiseAbs().maxCoeff(), 1e-9 * K.cwiseAbs().maxCoeff());
  EXPECT_EQ(r.stats.points_in_contact, 50);
}

}  // namespace
}  // namespace contactlab
