// Embedding of detailed-surface points in the coarse simulation mesh (Barbič & James 2008,
// sec. 4.1).
#include "deform/embedded_points.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "util/error.h"

namespace contactlab {
namespace {

// Gradients of tet T's four shape functions (rows), constant over the tet.
Eigen::Matrix<double, 4, 3> ShapeGradients(const TetMesh& mesh, int t) {
  const Eigen::Vector4i& v = mesh.tets[t];
  Eigen::Matrix3d Dm;
  for (int c = 0; c < 3; ++c) Dm.col(c) = mesh.vertices[v[c + 1]] - mesh.vertices[v[0]];
  const Eigen::Matrix3d inv = Dm.inverse();
  Eigen::Matrix<double, 4, 3> grad;
  grad.row(1) = inv.row(0);
  grad.row(2) = inv.row(1);
  grad.row(3) = inv.row(2);
  grad.row(0) = -(inv.row(0) + inv.row(1) + inv.row(2));
  return grad;
}

// The gradient of mode J's displacement over tet T: sum_a U_a grad_a^T.
Eigen::Matrix3d TetGradientMode(const TetMesh& mesh, const Eigen::MatrixXd& U, int t,
                                const Eigen::Matrix<double, 4, 3>& grad, int j) {
  Eigen::Matrix3d Fj = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 4; ++a) Fj.noalias() += U.block<3, 1>(3 * mesh.tets[t][a], j) * grad.row(a);
  return Fj;
}

// Per-vertex gradient modes: the volume-weighted mean of the incident tets' gradient modes,
// #V x r matrices (vertex v, mode j at [v * r + j]).
std::vector<Eigen::Matrix3d> VertexGradientModes(const TetMesh& mesh, const Eigen::MatrixXd& U) {
  const int r = int(U.cols());
  std::vector<Eigen::Matrix3d> G(std::size_t(mesh.num_vertices()) * r, Eigen::Matrix3d::Zero());
  std::vector<double> weight(std::size_t(mesh.num_vertices()), 0.0);
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const double vol = std::abs(mesh.TetVolume(t));
    const Eigen::Matrix<double, 4, 3> grad = ShapeGradients(mesh, t);
    for (int j = 0; j < r; ++j) {
      const Eigen::Matrix3d Fj = vol * TetGradientMode(mesh, U, t, grad, j);
      for (int a = 0; a < 4; ++a) G[std::size_t(mesh.tets[t][a]) * r + j] += Fj;
    }
    for (int a = 0; a < 4; ++a) weight[mesh.tets[t][a]] += vol;
  }
  for (int v = 0; v < mesh.num_vertices(); ++v) {
    if (weight[v] > 0) {
      for (int j = 0; j < r; ++j) G[std::size_t(v) * r + j] /= weight[v];
    }
  }
  return G;
}

Eigen::Vector4d Barycentric(const TetMesh& mesh, int t, const Eigen::Vector3d& p) {
  const Eigen::Vector4i& v = mesh.tets[t];
  Eigen::Matrix3d Dm;
  for (int c = 0; c < 3; ++c) Dm.col(c) = mesh.vertices[v[c + 1]] - mesh.vertices[v[0]];
  const Eigen::Vector3d l = Dm.inverse() * (p - mesh.vertices[v[0]]);
  return Eigen::Vector4d(1 - l.sum(), l[0], l[1], l[2]);
}

// Uniform grid of tet bounding boxes for point location.
class TetGrid {
 public:
  explicit TetGrid(const TetMesh& mesh) : mesh_(mesh) {
    box_ = mesh.Bounds();
    const double h0 = mesh.cell_size > 0 ? mesh.cell_size : std::cbrt(std::abs(mesh.Volume()) / mesh.num_tets()) * 2;
    h_ = std::max(h0, 1e-12);
    n_ = ((box_.size() / h_).array().ceil().cast<int>()).cwiseMax(1);
    start_.assign(std::size_t(n_.prod()) + 1, 0);
    std::vector<std::pair<int, int>> entries;  // (cell, tet)
    for (int t = 0; t < mesh.num_tets(); ++t) {
      Aabb b;
      for (int a = 0; a < 4; ++a) b.Extend(mesh.vertices[mesh.tets[t][a]]);
      const Eigen::Vector3i lo = Cell(b.min), hi = Cell(b.max);
      for (int k = lo.z(); k <= hi.z(); ++k)
        for (int j = lo.y(); j <= hi.y(); ++j)
          for (int i = lo.x(); i <= hi.x(); ++i) entries.emplace_back(Id(i, j, k), t);
    }
    std::sort(entries.begin(), entries.end());
    for (const auto& e : entries) ++start_[e.first + 1];
    for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
    tets_.resize(entries.size());
    for (std::size_t e = 0; e < entries.size(); ++e) tets_[e] = entries[e].second;
  }

  // Tet containing P (min barycentric >= -eps) from P's cell, else -1.
  int FindContaining(const Eigen::Vector3d& p, Eigen::Vector4d* bary) const {
    if (!box_.Inflated(1e-9 * h_).Contains(p)) return -1;
    const Eigen::Vector3i c = Cell(p);
    const int id = Id(c.x(), c.y(), c.z());
    int best = -1;
    double best_min = -std::numeric_limits<double>::infinity();
    for (int e = start_[id]; e < start_[id + 1]; ++e) {
      const Eigen::Vector4d b = Barycentric(mesh_, tets_[e], p);
      if (b.minCoeff() > best_min) {
        best_min = b.minCoeff();
        best = tets_[e];
        *bary = b;
      }
    }
    return best_min >= -1e-9 ? best : -1;
  }

 private:
  Eigen::Vector3i Cell(const Eigen::Vector3d& p) const {
    Eigen::Vector3i c = ((p - box_.min) / h_).array().floor().cast<int>();
    return c.cwiseMax(0).cwiseMin(n_ - Eigen::Vector3i::Ones());
  }
  int Id(int i, int j, int k) const { return i + n_.x() * (j + n_.y() * k); }

  const TetMesh& mesh_;
  Aabb box_;
  double h_ = 1;
  Eigen::Vector3i n_;
  std::vector<int> start_;
  std::vector<int> tets_;
};

}  // namespace

int LocateInTetMesh(const TetMesh& mesh, const Eigen::Vector3d& p, Eigen::Vector4d* bary) {
  int best = -1;
  double best_min = -std::numeric_limits<double>::infinity();
  for (int t = 0; t < mesh.num_tets(); ++t) {
    const Eigen::Vector4d b = Barycentric(mesh, t, p);
    if (b.minCoeff() > best_min) {
      best_min = b.minCoeff();
      best = t;
      *bary = b;
    }
  }
  return best;
}

EmbeddedPoints::EmbeddedPoints(const TetMesh& mesh, const Eigen::MatrixXd& U,
                               const std::vector<Eigen::Vector3d>& points,
                               const std::vector<Eigen::Vector3d>& normals, GradientScheme scheme) {
  if (mesh.tets.empty()) Fail("embedded points", "the simulation mesh has no tets");
  if (U.rows() != 3 * mesh.num_vertices()) Fail("embedded points", "the basis row count is not 3 x #vertices");
  if (!normals.empty() && normals.size() != points.size()) Fail("embedded points", "normals and points differ in count");
  r_ = int(U.cols());
  stride_ = (r_ + kBasisLanes - 1) / kBasisLanes * kBasisLanes;
  scheme_ = scheme;
  const std::size_t np = points.size();
  tet_.resize(np);
  bary_.resize(4 * np);
  rest_.resize(3 * np);
  normal_.assign(3 * np, 0.f);
  u_.assign(np * 3 * std::size_t(stride_), 0.f);
  f_.resize(np * 9 * r_);
  nc_.assign(np * 3 * std::size_t(stride_), 0.f);
  const std::vector<Eigen::Matrix3d> vertex_modes =
      scheme == GradientScheme::kSmooth ? VertexGradientModes(mesh, U) : std::vector<Eigen::Matrix3d>();
  const TetGrid grid(mesh);
  for (std::size_t i = 0; i < np; ++i) {
    const Eigen::Vector3d& p = points[i];
    Eigen::Vector4d b;
    int t = grid.FindContaining(p, &b);
    if (t < 0) t = LocateInTetMesh(mesh, p, &b);
    tet_[i] = t;
    const Eigen::Vector3d n = normals.empty() ? Eigen::Vector3d::Zero() : normals[i];
    for (int a = 0; a < 4; ++a) bary_[4 * i + a] = b[a];
    for (int c = 0; c < 3; ++c) {
      rest_[3 * i + c] = float(p[c]);
      normal_[3 * i + c] = float(n[c]);
    }
    const Eigen::Vector4i& v = mesh.tets[t];
    const Eigen::Matrix<double, 4, 3> grad = ShapeGradients(mesh, t);
    for (int j = 0; j < r_; ++j) {
      // Displacement mode and gradient mode at the point.
      Eigen::Vector3d uj = Eigen::Vector3d::Zero();
      for (int a = 0; a < 4; ++a) uj += b[a] * U.block<3, 1>(3 * v[a], j);
      Eigen::Matrix3d Fj = Eigen::Matrix3d::Zero();
      if (scheme == GradientScheme::kSmooth) {
        for (int a = 0; a < 4; ++a) Fj += b[a] * vertex_modes[std::size_t(v[a]) * r_ + j];
      } else {
        Fj = TetGradientMode(mesh, U, t, grad, j);
      }
      const Eigen::Vector3d nj = -Fj.transpose() * n;  // column j of the normal correction
      for (int c = 0; c < 3; ++c) {
        u_[(3 * i + c) * stride_ + j] = float(uj[c]);
        nc_[(3 * i + c) * stride_ + j] = float(nj[c]);
      }
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) f_[(9 * i + 3 * a + c) * r_ + j] = float(Fj(a, c));
    }
  }
}

Eigen::MatrixXd EmbeddedPoints::Basis(int i) const {
  Eigen::MatrixXd B(3, r_);
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < r_; ++j) B(c, j) = u_[(3 * std::size_t(i) + c) * stride_ + j];
  return B;
}

// The rows' sums are formed side by side, each in the order j = 0, 1, ...: independent chains
// of additions instead of one after another, the same values.
Eigen::Vector3d EmbeddedPoints::Displacement(int i, const double* q) const {
  const float* rows = &u_[3 * std::size_t(i) * stride_];
  double s[3] = {0, 0, 0};
  for (int j = 0; j < r_; ++j) {
    const double qj = q[j];
    for (int c = 0; c < 3; ++c) s[c] += double(rows[c * stride_ + j]) * qj;
  }
  return Eigen::Vector3d(s[0], s[1], s[2]);
}

Eigen::Matrix3d EmbeddedPoints::DeformationGradient(int i, const double* q) const {
  const float* rows = &f_[9 * std::size_t(i) * r_];
  double s[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  for (int j = 0; j < r_; ++j) {
    const double qj = q[j];
    for (int e = 0; e < 9; ++e) s[e] += double(rows[e * r_ + j]) * qj;
  }
  Eigen::Matrix3d F;
  for (int e = 0; e < 9; ++e) F(e / 3, e % 3) = s[e] + (e / 3 == e % 3 ? 1.0 : 0.0);
  return F;
}

Eigen::Vector3d EmbeddedPoints::Normal(int i, const double* q) const {
  const Eigen::Matrix3d F = DeformationGradient(i, q);
  // F^{-T} n is parallel to cof(F) n; cof(F) = [f1 x f2, f2 x f0, f0 x f1] (columns).
  const Eigen::Vector3d n(normal_[3 * i], normal_[3 * i + 1], normal_[3 * i + 2]);
  const Eigen::Vector3d m = n[0] * F.col(1).cross(F.col(2)) + n[1] * F.col(2).cross(F.col(0)) +
                            n[2] * F.col(0).cross(F.col(1));
  // cof(F) = det(F) F^{-T}: flip for an inverted element so the result is along F^{-T} n.
  const double det = F.col(0).dot(F.col(1).cross(F.col(2)));
  const double len = m.norm();
  return len > 0 ? Eigen::Vector3d(m * ((det < 0 ? -1.0 : 1.0) / len)) : m;
}

Eigen::Vector3d EmbeddedPoints::CorrectedNormal(int i, const double* q) const {
  Eigen::Vector3d m;
  for (int c = 0; c < 3; ++c) {
    const float* row = &nc_[(3 * std::size_t(i) + c) * stride_];
    double s = normal_[3 * i + c];
    for (int j = 0; j < r_; ++j) s += double(row[j]) * q[j];
    m[c] = s;
  }
  const double len = m.norm();
  return len > 0 ? Eigen::Vector3d(m / len) : m;
}

void EmbeddedPoints::AddPointForce(int i, const Eigen::Vector3d& force, double* f_q) const {
  for (int c = 0; c < 3; ++c) {
    const float* row = &u_[(3 * std::size_t(i) + c) * stride_];
    for (int j = 0; j < r_; ++j) f_q[j] += double(row[j]) * force[c];
  }
}

}  // namespace contactlab
