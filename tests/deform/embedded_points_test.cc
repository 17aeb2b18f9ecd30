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
  // Two points in the same tet: u(p2) - u(p1) = (F - I)(p2 - p1) exactly for linear tets.
  const std::vector<Eigen::Vector3d> points = {{0.51, 0.11, 0.12}, {0.52, 0.115, 0.118}};
  const EmbeddedPoints embedded(model_->mesh, model_->basis, points);
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

}  // namespace
}  // namespace contactlab
