// The reduced StVK force and tangent stiffness (deform/reduced_forces.h, evaluated through the
// packed symmetric product) against a plain evaluation of the cubic polynomial
//   f_i = A_ij q_j + B_ijl q_j q_l + C_ijlm q_j q_l q_m,   K = df/dq,
// written out index by index here, and against finite differences of the force.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <map>
#include <random>
#include <vector>

#include "beam_fixture.h"
#include "deform/reduced_forces.h"
#include "deform/symmetric_packed_product.h"
#include "util/error.h"

namespace contactlab {
namespace {

// f and K from the stored coefficients by the definition, every index summed over 0..r-1:
// B_ijl = B(pair(i, j), l), C_ijlm = C(pair(i, j), pair(l, m)) / (l == m ? 1 : 2).
void PlainForceAndStiffness(const ReducedInternalForces& forces, const Eigen::VectorXd& q, Eigen::VectorXd* f,
                            Eigen::MatrixXd* K) {
  const int r = forces.r();
  const Eigen::MatrixXd& A = forces.linear();
  const Eigen::MatrixXd& B = forces.quadratic();
  const Eigen::MatrixXd& C = forces.cubic();
  auto b = [&](int i, int j, int l) { return B(forces.Pair(i, j), l); };
  auto c = [&](int i, int j, int l, int m) { return C(forces.Pair(i, j), forces.Pair(l, m)) / (l == m ? 1.0 : 2.0); };
  f->setZero(r);
  K->setZero(r, r);
  for (int i = 0; i < r; ++i)
    for (int j = 0; j < r; ++j) {
      (*f)[i] += A(i, j) * q[j];
      (*K)(i, j) += A(i, j);
      for (int l = 0; l < r; ++l) {
        (*f)[i] += b(i, j, l) * q[j] * q[l];
        (*K)(i, j) += 2 * b(i, j, l) * q[l];
        for (int m = 0; m < r; ++m) {
          (*f)[i] += c(i, j, l, m) * q[j] * q[l] * q[m];
          (*K)(i, j) += 3 * c(i, j, l, m) * q[l] * q[m];
        }
      }
    }
}

// Random coefficients with the symmetries of a StVK model: A symmetric, B_ijl and C_ijlm
// unchanged under any permutation of their indices; stored as ReducedInternalForces takes them.
ReducedInternalForces RandomSymmetricForces(int r, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  const int np = r * (r + 1) / 2;
  std::vector<int> pair(r * r);
  for (int i = 0, p = 0; i < r; ++i)
    for (int j = i; j < r; ++j, ++p) pair[i * r + j] = pair[j * r + i] = p;
  Eigen::MatrixXd A(r, r), B(np, r), C(np, np);
  for (int i = 0; i < r; ++i)
    for (int j = i; j < r; ++j) A(i, j) = A(j, i) = (i == j ? 10.0 : 0.0) + u(*rng);
  // A value per sorted index tuple, read back through the sorted indices.
  std::map<std::vector<int>, double> value;
  auto sym = [&](std::vector<int> idx) {
    std::sort(idx.begin(), idx.end());
    auto [it, inserted] = value.try_emplace(idx, 0.0);
    if (inserted) it->second = u(*rng);
    return it->second;
  };
  for (int i = 0; i < r; ++i)
    for (int j = i; j < r; ++j)
      for (int l = 0; l < r; ++l) {
        B(pair[i * r + j], l) = sym({i, j, l});
        for (int m = l; m < r; ++m) C(pair[i * r + j], pair[l * r + m]) = sym({i, j, l, m}) * (l == m ? 1.0 : 2.0);
      }
  return ReducedInternalForces(ReducedModelKind::kStVK, A, B, C, "random coefficients");
}

// Evaluate (f, K, and f alone) equals the plain sums to rounding at random q, and K matches
// central differences of f.
void ExpectEvaluateMatchesPlainPolynomial(const ReducedInternalForces& forces, double q_scale, std::mt19937* rng) {
  const int r = forces.r();
  auto ws = forces.MakeWorkspace();
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = testing::RandomVector(r, q_scale, rng);
    Eigen::VectorXd f_ref;
    Eigen::MatrixXd K_ref;
    PlainForceAndStiffness(forces, q, &f_ref, &K_ref);
    ReducedVector f(r), f_only(r);
    ReducedMatrix K(r, r);
    forces.Evaluate(q, &f, &K, &ws);
    forces.Evaluate(q, &f_only, nullptr, &ws);
    EXPECT_LT((Eigen::VectorXd(f) - f_ref).norm(), 1e-12 * f_ref.norm()) << "r " << r << " trial " << trial;
    EXPECT_LT((Eigen::MatrixXd(K) - K_ref).norm(), 1e-12 * K_ref.norm()) << "r " << r << " trial " << trial;
    EXPECT_EQ(Eigen::VectorXd(f_only), Eigen::VectorXd(f));
    EXPECT_EQ(Eigen::MatrixXd(K), Eigen::MatrixXd(K.transpose()));  // exactly symmetric
    // K against central differences of f along a random direction (the cubic's third
    // derivative makes the error O(e^2)).
    const Eigen::VectorXd d = testing::RandomVector(r, 1.0, rng);
    const double e = 1e-5 * q_scale;
    ReducedVector fp(r), fm(r);
    forces.Evaluate(q + e * d, &fp, nullptr, &ws);
    forces.Evaluate(q - e * d, &fm, nullptr, &ws);
    const Eigen::VectorXd fd = (fp - fm) / (2 * e);
    EXPECT_LT((Eigen::VectorXd(K * d) - fd).norm(), 1e-7 * fd.norm()) << "r " << r << " trial " << trial;
  }
}

TEST(ReducedForcesPolynomial, EvaluateEqualsPlainCubicForRandomSymmetricCoefficients) {
  std::mt19937 rng(7);
  for (int r : {1, 2, 5, 15}) {  // npairs 1, 3, 15 (odd: the packed product's last single row), 120
    const ReducedInternalForces forces = RandomSymmetricForces(r, &rng);
    ExpectEvaluateMatchesPlainPolynomial(forces, 1.0 / 3.0, &rng);
  }
}

TEST(ReducedForcesPolynomial, EvaluateEqualsPlainCubicForBeamModel) {
  std::mt19937 rng(8);
  for (int r : {5, 15}) {
    const ReducedModel model =
        BuildReducedModel(testing::MakeBeam(), testing::BeamOptions(r, ReducedModelKind::kStVK), "beam");
    ExpectEvaluateMatchesPlainPolynomial(model.forces, 1.0, &rng);
  }
}

TEST(ReducedForcesPolynomial, RejectsAsymmetricCubicCoefficients) {
  std::mt19937 rng(9);
  const ReducedInternalForces forces = RandomSymmetricForces(3, &rng);
  Eigen::MatrixXd C = forces.cubic();
  C(0, 4) += 0.5;
  EXPECT_THROW(ReducedInternalForces(ReducedModelKind::kStVK, forces.linear(), forces.quadratic(), C, "asymmetric"),
               Error);
}

TEST(SymmetricPackedProduct, EqualsDenseProductForEverySize) {
  std::mt19937 rng(10);
  for (int n = 1; n <= 21; ++n) {  // every tail length for vectors of 2, 4 and 8 doubles
    const Eigen::VectorXd x = testing::RandomVector(n, 1.0, &rng);
    Eigen::MatrixXd S = Eigen::MatrixXd::Zero(n, n);
    std::vector<double> packed(PackedUpperSize(n));
    for (int p = 0; p < n; ++p)
      for (int k = p; k < n; ++k) {
        S(p, k) = S(k, p) = testing::RandomVector(1, 1.0, &rng)[0];
        packed[PackedUpperRowStart(p, n) + (k - p)] = S(p, k);
      }
    Eigen::VectorXd y(n);
    SymmetricPackedProduct(packed.data(), n, x.data(), y.data());
    const Eigen::VectorXd y_ref = S * x;
    EXPECT_LT((y - y_ref).norm(), 1e-14 * (1 + y_ref.norm())) << "n " << n;
  }
  RecordProperty("simd_target", SymmetricPackedProductTarget());
}

}  // namespace
}  // namespace contactlab
