// Barbič & James 2008, sec. 4.1: deformable pointshell and BD-tree bounds.
#include "deform/deformable_pointshell.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace contactlab {
namespace {

std::vector<Eigen::Vector3d> Column3(const std::vector<float>& x, const std::vector<float>& y,
                                     const std::vector<float>& z) {
  std::vector<Eigen::Vector3d> v(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) v[i] = Eigen::Vector3d(x[i], y[i], z[i]);
  return v;
}

}  // namespace

DeformablePointshell::DeformablePointshell(std::shared_ptr<const Pointshell> shell, const TetMesh& mesh,
                                           const Eigen::MatrixXd& U)
    : shell_(std::move(shell)) {
  if (!shell_ || shell_->num_points() == 0 || shell_->num_levels() == 0) {
    Fail("deformable pointshell", "needs a non-empty pointshell");
  }
  const Pointshell& s = *shell_;
  points_ = EmbeddedPoints(mesh, U, Column3(s.x, s.y, s.z), Column3(s.nx, s.ny, s.nz), GradientScheme::kSmooth);
  const int r = points_.r();
  const int N = s.num_nodes();
  // Each point's basis rows (3 x r), in double for the spread computation.
  std::vector<Eigen::MatrixXd> basis(std::size_t(s.num_points()));
  for (int i = 0; i < s.num_points(); ++i) basis[i] = points_.Basis(i);
  // The deepest level holds an instance of every point; walking each such node's ancestors
  // visits, for every node, every point of its subtree.
  std::vector<double> rho(std::size_t(N) * r, 0.0);
  const int deepest = s.num_levels() - 1;
  for (int leaf = s.level_node_begin[deepest]; leaf < s.level_node_begin[deepest + 1]; ++leaf) {
    const Eigen::MatrixXd& Uq = basis[s.node_point[leaf]];
    for (int n = s.node_parent[leaf]; n >= 0; n = s.node_parent[n]) {
      const Eigen::MatrixXd& Uc = basis[s.node_point[n]];
      for (int j = 0; j < r; ++j) {
        const double d = (Uq.col(j) - Uc.col(j)).norm();
        double& m = rho[std::size_t(n) * r + j];
        if (d > m) m = d;
      }
    }
  }
  // Stored as float, rounded up so the bound stays conservative.
  const int stride = points_.basis_stride();
  rho_.assign(std::size_t(N) * stride, 0.f);
  for (int n = 0; n < N; ++n) {
    for (int j = 0; j < r; ++j) rho_[std::size_t(n) * stride + j] = std::nextafter(float(rho[std::size_t(n) * r + j]), INFINITY);
  }
  node_travel_.assign(std::size_t(N) * stride, 0.f);
  for (int n = 0; n < N; ++n) {
    const Eigen::MatrixXd& Uc = basis[s.node_point[n]];
    for (int j = 0; j < r; ++j) {
      node_travel_[std::size_t(n) * stride + j] =
          std::nextafter(float(rho[std::size_t(n) * r + j] + Uc.col(j).norm()), INFINITY);
    }
  }
  for (int j = 0; j < r; ++j) {
    double spread = 0, displacement = 0;
    for (int n = 0; n < N; ++n) spread = std::max(spread, rho[std::size_t(n) * r + j]);
    for (int i = 0; i < s.num_points(); ++i) displacement = std::max(displacement, basis[i].col(j).norm());
    travel_.push_back(std::nextafter(float(spread + displacement), INFINITY));
  }
}

}  // namespace contactlab
