#include "deform/embedded_points.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "beam_fixture.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::BeamOptions;
using testing::MakeBeam;

class EmbeddedPointsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = new ReducedModel(BuildReducedModel(MakeBeam(), BeamOptions(8, ReducedModelKind::kStVK), "beam"));
  }
  static void TearDownTestSuite() { delete model_; }
  static ReducedModel* model_;
};
ReducedModel* EmbeddedPointsTest::model_ = nullptr;

TEST_F(EmbeddedPointsTest, DisplacementIsTheShapeFunctionInterpolationOfTheBasis) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> ux(0, 1), uy(0, 0.25);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 100; ++i) points.emplace_back(ux(rng), uy(rng), uy(rng));
  points.emplace_back(1.0 / 3, 0.1, 0.0);  // on the boundary
  const EmbeddedPoints embedded(model_->mesh, model_->basis, points);
  const Eigen::VectorXd q = testing::RandomVector(model_->r(), 1.0, &rng);
  const Eigen::VectorXd u = model_->basis * q;
  for (int i = 0; i < embedded.size(); ++i) {
    const Eigen::Vector4d b = embedded.barycentric(i);
    EXPECT_GE(b.minCoeff(), -1e-9);
    const Eigen::Vector4i& t = model_->mesh.tets[embedded.tet(i)];
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), d = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a) {
      p += b[a] * model_->mesh.vertices[t[a]];
      d += b[a] * u.segment<3>(3 * t[a]);
    }
    EXPECT_LT((p - points[i]).norm(), 1e-12);
    EXPECT_LT((embedded.Displacement(i, q.data()) - d).norm(), 1e-6 * (1 + d.norm()));
    EXPECT_LT((embedded.Basis(i) * q - d).norm(), 1e-6 * (1 + d.norm()));
  }
}

TEST_F(EmbeddedPointsTest, DeformationGradientMatchesDisplacementDifferences) {
  // Two points in the same tet: u(p2) - u(p1) = (F - I)(p2 - p1) exactly for linear tets
  // with the per-tet gradient.
  const std::vector<Eigen::Vector3d> points = {{0.51, 0.11, 0.12}, {0.52, 0.115, 0.118}};
  const EmbeddedPoints embedded(model_->mesh, model_->basis, points, {}, GradientScheme::kPerTet);
  ASSERT_EQ(embedded.tet(0), embedded.tet(1));
  std::mt19937 rng(7);
  const Eigen::VectorXd q = testing::RandomVector(model_->r(), 1.0, &rng);
  const Eigen::Matrix3d F = embedded.DeformationGradient(0, q.data());
  const Eigen::Vector3d du = embedded.Displacement(1, q.data()) - embedded.Displacement(0, q.data());
  EXPECT_LT((du - (F - Eigen::Matrix3d::Identity()) * (points[1] - points[0])).norm(), 1e-6 * du.norm() + 1e-9);
}

TEST_F(EmbeddedPointsTest, DeformedNormalStaysPerpendicularToDeformedTangents) {
  const Eigen::Vector3d n = Eigen::Vector3d(1, 2, -0.5).normalized();
  const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  const std::vector<Eigen::Vector3d> points = {{0.7, 0.2, 0.05}};
  const EmbeddedPoints embedded(model_->mesh, model_->basis, points, {n});
  std::mt19937 rng(8);
  const Eigen::VectorXd q = testing::RandomVector(model_->r(), 0.5, &rng);
  const Eigen::Matrix3d F = embedded.DeformationGradient(0, q.data());
  ASSERT_GT(F.determinant(), 0.2);
  EXPECT_GT((F - Eigen::Matrix3d::Identity()).norm(), 0.05);  // a real deformation
  const Eigen::Vector3d m = embedded.Normal(0, q.data());
  EXPECT_NEAR(m.norm(), 1.0, 1e-12);
  EXPECT_LT(std::abs(m.dot((F * t1).normalized())), 1e-6);
  EXPECT_LT(std::abs(m.dot((F * t2).normalized())), 1e-6);
  EXPECT_GT(m.dot(F * n), 0);
  // At rest the normal is unchanged.
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model_->r());
  EXPECT_LT((embedded.Normal(0, zero.data()) - n).norm(), 1e-6);
}

TEST_F(EmbeddedPointsTest, PointForceProjectsThroughTheTransposedBasis) {
  const std::vector<Eigen::Vector3d> points = {{0.9, 0.05, 0.2}};
  const EmbeddedPoints embedded(model_->mesh, model_->basis, points);
  const Eigen::Vector3d force(0.3, -2.0, 1.0 / 3);
  Eigen::VectorXd fq = Eigen::VectorXd::Zero(model_->r());
  embedded.AddPointForce(0, force, fq.data());
  EXPECT_LT((fq - embedded.Basis(0).transpose() * force).norm(), 1e-12 * fq.norm());
}

TEST_F(EmbeddedPointsTest, PointsOutsideUseTheNearestTetByExtrapolation) {
  const std::vector<Eigen::Vector3d> points = {{1.02, 0.1, 0.1}};
  const EmbeddedPoints embedded(model_->mesh, model_->basis, points);
  const Eigen::Vector4i& t = model_->mesh.tets[embedded.tet(0)];
  double max_x = 0;
  for (int a = 0; a < 4; ++a) max_x = std::max(max_x, model_->mesh.vertices[t[a]].x());
  EXPECT_NEAR(max_x, 1.0, 1e-12);
  EXPECT_NEAR(embedded.barycentric(0).sum(), 1.0, 1e-12);
}

// Two points a distance EPS apart on either side of a face shared by two tets of the mesh, and
// the face's unit normal.
void StraddleASharedFace(const TetMesh& mesh, double eps, std::vector<Eigen::Vector3d>* points, int* tet_a,
                         int* tet_b) {
  // Find two tets sharing three vertices.
  for (int a = 0; a < mesh.num_tets(); ++a) {
    for (int b = a + 1; b < mesh.num_tets(); ++b) {
      int shared[4], n = 0;
      for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k)
          if (mesh.tets[a][i] == mesh.tets[b][k]) shared[n++] = mesh.tets[a][i];
      if (n != 3) continue;
      const Eigen::Vector3d x0 = mesh.vertices[shared[0]], x1 = mesh.vertices[shared[1]],
                            x2 = mesh.vertices[shared[2]];
      const Eigen::Vector3d c = (x0 + x1 + x2) / 3;
      const Eigen::Vector3d nrm = (x1 - x0).cross(x2 - x0).normalized();
      *points = {c - 0.5 * eps * nrm, c + 0.5 * eps * nrm};
      *tet_a = a;
      *tet_b = b;
      return;
    }
  }
  FAIL() << "no shared face";
}

TEST_F(EmbeddedPointsTest, SmoothGradientsAndCorrectedNormalsAreContinuousAcrossTetFaces) {
  std::vector<Eigen::Vector3d> points;
  int ta = -1, tb = -1;
  StraddleASharedFace(model_->mesh, 1e-7, &points, &ta, &tb);
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -1, 0.6).normalized();
  std::mt19937 rng(11);
  const Eigen::VectorXd q = testing::RandomVector(model_->r(), 0.5, &rng);
  const EmbeddedPoints smooth(model_->mesh, model_->basis, points, {n, n}, GradientScheme::kSmooth);
  const EmbeddedPoints per_tet(model_->mesh, model_->basis, points, {n, n}, GradientScheme::kPerTet);
  ASSERT_NE(smooth.tet(0), smooth.tet(1));  // the two points are in different tets
  const double jump_per_tet =
      (per_tet.DeformationGradient(0, q.data()) - per_tet.DeformationGradient(1, q.data())).norm();
  const double jump_smooth = (smooth.DeformationGradient(0, q.data()) - smooth.DeformationGradient(1, q.data())).norm();
  // The per-tet gradient jumps by a finite amount (the reason for the smooth scheme); the
  // smooth one changes by O(eps).
  EXPECT_GT(jump_per_tet, 1e-3);
  EXPECT_LT(jump_smooth, 1e-5 * (1 + jump_per_tet));
  const double normal_jump = (smooth.CorrectedNormal(0, q.data()) - smooth.CorrectedNormal(1, q.data())).norm();
  EXPECT_LT(normal_jump, 1e-5);
  EXPECT_GT((per_tet.Normal(0, q.data()) - per_tet.Normal(1, q.data())).norm(), 1e-4);
}

TEST_F(EmbeddedPointsTest, SmoothGradientIsExactForAnAffineDeformation) {
  // A basis of affine fields u_j(x) = A_j x: the true gradient is A_j everywhere.
  std::mt19937 rng(12);
  std::normal_distribution<double> g(0, 1);
  const int r = 3;
  std::vector<Eigen::Matrix3d> A(r);
  Eigen::MatrixXd U(3 * model_->mesh.num_vertices(), r);
  for (int j = 0; j < r; ++j) {
    for (int e = 0; e < 9; ++e) A[j](e / 3, e % 3) = g(rng);
    for (int v = 0; v < model_->mesh.num_vertices(); ++v) U.block<3, 1>(3 * v, j) = A[j] * model_->mesh.vertices[v];
  }
  std::vector<Eigen::Vector3d> points;
  std::uniform_real_distribution<double> ux(0, 1), uy(0, 0.25);
  for (int i = 0; i < 50; ++i) points.emplace_back(ux(rng), uy(rng), uy(rng));
  const EmbeddedPoints smooth(model_->mesh, U, points, {}, GradientScheme::kSmooth);
  const double q[r] = {0.02, -0.01, 1.0 / 30};
  const Eigen::Matrix3d F = Eigen::Matrix3d::Identity() + q[0] * A[0] + q[1] * A[1] + q[2] * A[2];
  for (int i = 0; i < smooth.size(); ++i) {
    EXPECT_LT((smooth.DeformationGradient(i, q) - F).norm(), 1e-6 * F.norm()) << i;
  }
}

TEST_F(EmbeddedPointsTest, CorrectedNormalIsTheFirstOrderPushForwardRenormalised) {
  const Eigen::Vector3d n = Eigen::Vector3d(1, 2, -0.5).normalized();
  const std::vector<Eigen::Vector3d> points = {{0.7, 0.2, 0.05}, {0.3, 0.1, 0.2}};
  const EmbeddedPoints embedded(model_->mesh, model_->basis, points, {n, n});
  std::mt19937 rng(13);
  const Eigen::VectorXd dir = testing::RandomVector(model_->r(), 1.0, &rng);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model_->r());
  for (int i = 0; i < 2; ++i) {
    EXPECT_LT((embedded.CorrectedNormal(i, zero.data()) - n).norm(), 1e-6);
    // Against the exact push-forward of the same gradient: the error shrinks as |q|^2.
    double previous = 0;
    for (double s : {0.1, 0.05, 0.025}) {
      const Eigen::VectorXd q = s * dir;
      const Eigen::Vector3d m = embedded.CorrectedNormal(i, q.data());
      EXPECT_NEAR(m.norm(), 1.0, 1e-12);
      const double err = (m - embedded.Normal(i, q.data())).norm();
      if (previous > 1e-9) {
        EXPECT_LT(err, 0.3 * previous) << "s " << s;  // ~ 1/4 per halving
      }
      previous = err;
    }
  }
}

}  // namespace
}  // namespace contactlab
