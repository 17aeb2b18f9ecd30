// The vector kernels of deform/reduced_point_batch.h against references computed point by point
// in double: positions from the shape-function interpolation of the basis (not the stored
// rows), normals from EmbeddedPoints::CorrectedNormal, reduced sums from U_i^T N summed in
// double. Every basis stride (r = 1 .. 40), contiguous and indexed points, point counts that
// leave partial vector groups.
#include "deform/reduced_point_batch.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <random>
#include <vector>

#include <hwy/targets.h>

#include "beam_fixture.h"

namespace contactlab {
namespace {

struct Case {
  TetMesh mesh = testing::MakeBeam(TetSplit::kSix, 8);
  Eigen::MatrixXd U;
  std::vector<Eigen::Vector3d> points, normals;
  std::vector<float> x, y, z, nx, ny, nz;  // rest positions and normals, as a pointshell holds them
  EmbeddedPoints embedded;
  Eigen::VectorXd q;
  std::vector<float> q_padded;

  Case(int r, int n, std::uint32_t seed) {
    std::mt19937 rng(seed);
    U = Eigen::MatrixXd::Random(3 * mesh.num_vertices(), r) * 0.05;
    std::uniform_real_distribution<double> ux(0, 1), uy(0, 0.25), un(-1, 1);
    for (int i = 0; i < n; ++i) {
      points.emplace_back(ux(rng), uy(rng), uy(rng));
      normals.push_back(Eigen::Vector3d(un(rng), un(rng), un(rng)).normalized());
      x.push_back(float(points.back().x()));
      y.push_back(float(points.back().y()));
      z.push_back(float(points.back().z()));
      nx.push_back(float(normals.back().x()));
      ny.push_back(float(normals.back().y()));
      nz.push_back(float(normals.back().z()));
    }
    embedded = EmbeddedPoints(mesh, U, points, normals);
    q = testing::RandomVector(r, 1.0, &rng);
    q_padded.assign(std::size_t(kMaxBasisStride), 0.f);
    for (int j = 0; j < r; ++j) q_padded[j] = float(q[j]);
  }
  // Point I's displacement, interpolated from the basis by its tet's shape functions.
  Eigen::Vector3d Displacement(int i) const {
    const Eigen::Vector4d b = embedded.barycentric(i);
    const Eigen::Vector4i& t = mesh.tets[embedded.tet(i)];
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    for (int a = 0; a < 4; ++a) d += b[a] * (U.middleRows(3 * t[a], 3) * q);
    return d;
  }
  Eigen::MatrixXd BasisAt(int i) const {
    const Eigen::Vector4d b = embedded.barycentric(i);
    const Eigen::Vector4i& t = mesh.tets[embedded.tet(i)];
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(3, U.cols());
    for (int a = 0; a < 4; ++a) B += b[a] * U.middleRows(3 * t[a], 3);
    return B;
  }
};

// BODY once with each instruction set this CPU runs and the library was compiled for.
template <class Body>
void ForEachTarget(Body&& body) {
  const std::vector<std::int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  for (std::int64_t target : targets) {
    hwy::SetSupportedTargetsForTest(target);
    SCOPED_TRACE(hwy::TargetName(target));
    body();
  }
  hwy::SetSupportedTargetsForTest(0);
}

// Every other point, backwards: an index list as a tree level gives one (scattered).
std::vector<std::int32_t> ScatteredIndex(int n) {
  std::vector<std::int32_t> index;
  for (int i = n - 1; i >= 0; i -= 2) index.push_back(i);
  return index;
}

class ReducedPointBatchTest : public ::testing::TestWithParam<int> {};

TEST_P(ReducedPointBatchTest, PositionsEqualTheInterpolatedDisplacementToFloatRounding) {
  ForEachTarget([&] {
    const int r = GetParam();
    for (int n : {1, 7, 8, 9, 37, 100}) {
      const Case c(r, n, 11u + unsigned(n));
      std::vector<float> px(n), py(n), pz(n);
      // Contiguous, from point 0 and from an offset.
      for (int begin : {0, n / 3}) {
        const int m = n - begin;
        DeformedPositions(c.embedded, c.x.data(), c.y.data(), c.z.data(), c.q_padded.data(), nullptr, begin, m,
                          px.data(), py.data(), pz.data());
        for (int k = 0; k < m; ++k) {
          const int i = begin + k;
          const Eigen::Vector3d expected = c.points[i] + c.Displacement(i);
          const Eigen::Vector3d got(px[k], py[k], pz[k]);
          EXPECT_LT((got - expected).norm(), 2e-6 * (1 + expected.norm())) << "r " << r << " n " << n << " point " << i;
        }
      }
      const std::vector<std::int32_t> index = ScatteredIndex(n);
      DeformedPositions(c.embedded, c.x.data(), c.y.data(), c.z.data(), c.q_padded.data(), index.data(), 0,
                        int(index.size()), px.data(), py.data(), pz.data());
      for (std::size_t k = 0; k < index.size(); ++k) {
        const int i = index[k];
        const Eigen::Vector3d expected = c.points[i] + c.Displacement(i);
        EXPECT_LT((Eigen::Vector3d(px[k], py[k], pz[k]) - expected).norm(), 2e-6 * (1 + expected.norm()))
            << "r " << r << " n " << n << " indexed point " << i;
      }
    }
  });
}

TEST_P(ReducedPointBatchTest, NormalsEqualTheDoubleCorrectedNormal) {
  ForEachTarget([&] {
    const int r = GetParam();
    const int n = 45;
    const Case c(r, n, 29u);
    const std::vector<std::int32_t> index = ScatteredIndex(n);
    const int m = int(index.size());
    std::vector<float> nx(m), ny(m), nz(m);
    CorrectedNormals(c.embedded, c.nx.data(), c.ny.data(), c.nz.data(), c.q_padded.data(), index.data(), m, nx.data(),
                     ny.data(), nz.data());
    for (int k = 0; k < m; ++k) {
      const Eigen::Vector3d expected = c.embedded.CorrectedNormal(index[k], c.q.data());
      const Eigen::Vector3d got(nx[k], ny[k], nz[k]);
      EXPECT_NEAR(got.norm(), 1.0, 1e-6);
      EXPECT_LT((got - expected).norm(), 2e-6) << "r " << r << " point " << index[k];
    }
  });
}

TEST_P(ReducedPointBatchTest, ReducedSumsEqualTheirDoubleSums) {
  ForEachTarget([&] {
    const int r = GetParam();
    const int n = 53;
    const Case c(r, n, 31u);
    const std::vector<std::int32_t> index = ScatteredIndex(n);
    const int m = int(index.size());
    std::vector<float> d(m);
    for (int k = 0; k < m; ++k) d[k] = -1e-3f * float(k + 1);
    const int stride = c.embedded.basis_stride();
    // Sums start from nonzero values: the kernel adds to them.
    std::vector<float> g(stride, 0.5f), G(std::size_t(r) * stride, 0.25f);
    AddReducedPointSums(c.embedded, c.nx.data(), c.ny.data(), c.nz.data(), index.data(), d.data(), m, g.data(), G.data());
    Eigen::VectorXd g_ref = Eigen::VectorXd::Constant(r, 0.5);
    Eigen::MatrixXd G_ref = Eigen::MatrixXd::Constant(r, r, 0.25);
    for (int k = 0; k < m; ++k) {
      const Eigen::VectorXd w = c.BasisAt(index[k]).transpose() * c.normals[index[k]];
      g_ref += double(d[k]) * w;
      G_ref += w * w.transpose();
    }
    const double scale_g = 1 + g_ref.cwiseAbs().maxCoeff(), scale_G = 1 + G_ref.cwiseAbs().maxCoeff();
    for (int j = 0; j < r; ++j) EXPECT_NEAR(g[j], g_ref[j], 1e-5 * scale_g) << "r " << r << " g " << j;
    for (int b = 0; b < r; ++b) {
      for (int a = 0; a < r; ++a) EXPECT_NEAR(G[std::size_t(b) * stride + a], G_ref(b, a), 1e-5 * scale_G) << "r " << r;
      for (int a = r; a < stride; ++a) EXPECT_EQ(G[std::size_t(b) * stride + a], 0.25f) << "padding changed";
    }
    // Without the stiffness, only g is summed.
    std::vector<float> g2(stride, 0.f);
    AddReducedPointSums(c.embedded, c.nx.data(), c.ny.data(), c.nz.data(), index.data(), d.data(), m, g2.data(), nullptr);
    for (int j = 0; j < r; ++j) EXPECT_NEAR(g2[j], g_ref[j] - 0.5, 1e-5 * scale_g);
  });
}

INSTANTIATE_TEST_SUITE_P(Strides, ReducedPointBatchTest, ::testing::Values(1, 3, 8, 9, 15, 20, 33, 40));

TEST(ReducedPointBatch, StreamReadsEveryRowOnce) {
  Case c(15, 21, 5u);
  const int stride = c.embedded.basis_stride();
  double expected = 0;
  for (int i = 0; i < 21; ++i) {
    expected += double(c.x[i]) + c.y[i] + c.z[i];
    for (int k = 0; k < 3 * stride; ++k) expected += c.embedded.basis_rows()[3 * std::size_t(stride) * i + k];
  }
  EXPECT_NEAR(StreamPointRows(c.embedded, c.x.data(), c.y.data(), c.z.data(), 21), expected, 1e-4 * (1 + std::abs(expected)));
}

}  // namespace
}  // namespace contactlab
