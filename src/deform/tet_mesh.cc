// Voxel tetrahedral meshes from distance-field interiors (Barbič & James 2008, sec. 4.1).
#include "deform/tet_mesh.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>

#include "util/error.h"

namespace contactlab {
namespace {

// Cube corner index a + 2b + 4c for the corner at offset (a, b, c).
constexpr int Corner(int a, int b, int c) { return a + 2 * b + 4 * c; }

// Six tets sharing the main diagonal 0-7 (Kuhn split); conforming without parity.
constexpr std::array<std::array<int, 4>, 6> kSixTets = {{
    {Corner(0, 0, 0), Corner(1, 0, 0), Corner(1, 1, 0), Corner(1, 1, 1)},
    {Corner(0, 0, 0), Corner(1, 0, 0), Corner(1, 0, 1), Corner(1, 1, 1)},
    {Corner(0, 0, 0), Corner(0, 1, 0), Corner(1, 1, 0), Corner(1, 1, 1)},
    {Corner(0, 0, 0), Corner(0, 1, 0), Corner(0, 1, 1), Corner(1, 1, 1)},
    {Corner(0, 0, 0), Corner(0, 0, 1), Corner(1, 0, 1), Corner(1, 1, 1)},
    {Corner(0, 0, 0), Corner(0, 0, 1), Corner(0, 1, 1), Corner(1, 1, 1)},
}};

// Five tets (even parity); odd-parity cells use the mirror image in x, so faces conform.
constexpr std::array<std::array<int, 4>, 5> kFiveTets = {{
    {Corner(1, 0, 0), Corner(0, 1, 0), Corner(0, 0, 1), Corner(1, 1, 1)},
    {Corner(0, 0, 0), Corner(1, 0, 0), Corner(0, 1, 0), Corner(0, 0, 1)},
    {Corner(1, 1, 0), Corner(1, 0, 0), Corner(0, 1, 0), Corner(1, 1, 1)},
    {Corner(1, 0, 1), Corner(1, 0, 0), Corner(0, 0, 1), Corner(1, 1, 1)},
    {Corner(0, 1, 1), Corner(0, 1, 0), Corner(0, 0, 1), Corner(1, 1, 1)},
}};

double SignedVolume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& d) {
  return (b - a).dot((c - a).cross(d - a)) / 6.0;
}

// Builds the tet mesh of the kept cells of an NX x NY x NZ lattice with origin O and cell H.
TetMesh TetsOfCells(const std::vector<std::uint8_t>& keep, int nx, int ny, int nz,
                    const Eigen::Vector3d& o, double h, TetSplit split) {
  TetMesh mesh;
  mesh.cell_size = h;
  const auto vid = [&](int i, int j, int k) {
    return std::int64_t(i) + std::int64_t(nx + 1) * (j + std::int64_t(ny + 1) * k);
  };
  std::vector<int> vertex_of(std::size_t(nx + 1) * (ny + 1) * (nz + 1), -1);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        if (!keep[i + std::size_t(nx) * (j + std::size_t(ny) * k)]) continue;
        std::array<int, 8> c;
        for (int corner = 0; corner < 8; ++corner) {
          const int a = corner & 1, b = (corner >> 1) & 1, cc = (corner >> 2) & 1;
          int& v = vertex_of[vid(i + a, j + b, k + cc)];
          if (v < 0) {
            v = int(mesh.vertices.size());
            mesh.vertices.push_back(o + h * Eigen::Vector3d(i + a, j + b, k + cc));
          }
          c[corner] = v;
        }
        const auto add = [&](std::array<int, 4> t) {
          Eigen::Vector4i tet(t[0], t[1], t[2], t[3]);
          if (SignedVolume(mesh.vertices[tet[0]], mesh.vertices[tet[1]], mesh.vertices[tet[2]],
                           mesh.vertices[tet[3]]) < 0) {
            std::swap(tet[2], tet[3]);
          }
          mesh.tets.push_back(tet);
        };
        if (split == TetSplit::kSix) {
          for (const auto& t : kSixTets) add({c[t[0]], c[t[1]], c[t[2]], c[t[3]]});
        } else {
          const bool odd = ((i + j + k) & 1) != 0;
          for (const auto& t : kFiveTets) {
            std::array<int, 4> m;
            for (int q = 0; q < 4; ++q) m[q] = odd ? (t[q] ^ 1) : t[q];  // mirror in x
            add({c[m[0]], c[m[1]], c[m[2]], c[m[3]]});
          }
        }
      }
  return mesh;
}

}  // namespace

double TetMesh::TetVolume(int t) const {
  const Eigen::Vector4i& v = tets[t];
  return SignedVolume(vertices[v[0]], vertices[v[1]], vertices[v[2]], vertices[v[3]]);
}

double TetMesh::Volume() const {
  double s = 0;
  for (int t = 0; t < num_tets(); ++t) s += TetVolume(t);
  return s;
}

Aabb TetMesh::Bounds() const {
  Aabb b;
  for (const auto& p : vertices) b.Extend(p);
  return b;
}

double TetMesh::DeformedVolume(const Eigen::VectorXd& u) const {
  double s = 0;
  const auto x = [&](int i) -> Eigen::Vector3d { return vertices[i] + u.segment<3>(3 * i); };
  for (const auto& v : tets) s += SignedVolume(x(v[0]), x(v[1]), x(v[2]), x(v[3]));
  return s;
}

TetMesh MakeBoxTetMesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, int nx, int ny,
                       int nz, TetSplit split) {
  if (nx < 1 || ny < 1 || nz < 1) Fail("MakeBoxTetMesh", "cell counts must be >= 1");
  if (!((hi - lo).array() > 0).all()) Fail("MakeBoxTetMesh", "the box is empty");
  const Eigen::Vector3d size = hi - lo;
  const double h = size.x() / nx;
  if (std::abs(size.y() / ny - h) > 1e-9 * h || std::abs(size.z() / nz - h) > 1e-9 * h) {
    Fail("MakeBoxTetMesh", "cells must be cubes: size / count must agree on all axes");
  }
  std::vector<std::uint8_t> keep(std::size_t(nx) * ny * nz, 1);
  return TetsOfCells(keep, nx, ny, nz, lo, h, split);
}

TetMesh BuildVoxelTetMesh(const DistanceField& field, const VoxelMeshOptions& options) {
  const std::string where = "voxel mesh of " + (field.info().source.empty() ? std::string("field") : field.info().source);
  if (field.empty()) Fail(where, "the distance field is empty");
  if (options.cells < 1 || options.cells > 256) Fail(where, "cells must be in [1, 256], got " + std::to_string(options.cells));

  // Box of the interior samples, padded by one field spacing.
  Aabb inner;
  const Eigen::Vector3i d = field.dims();
  for (int k = 0; k < d.z(); ++k)
    for (int j = 0; j < d.y(); ++j)
      for (int i = 0; i < d.x(); ++i)
        if (field.value(i, j, k) < 0) inner.Extend(field.GridPoint(i, j, k));
  if (inner.empty()) Fail(where, "the field has no interior (no negative sample)");
  inner = inner.Inflated(field.spacing());
  const double h = inner.size().maxCoeff() / options.cells;
  const Eigen::Vector3i n = (inner.size() / h).array().ceil().cast<int>().cwiseMax(1);
  const Eigen::Vector3d o = inner.center() - 0.5 * h * n.cast<double>();

  // Keep cells whose centre is within (threshold x half diagonal) of the interior.
  const double limit = options.threshold * 0.5 * std::sqrt(3.0) * h;
  const std::size_t ncell = std::size_t(n.x()) * n.y() * n.z();
  std::vector<std::uint8_t> keep(ncell, 0);
  const auto cid = [&](int i, int j, int k) { return i + std::size_t(n.x()) * (j + std::size_t(n.y()) * k); };
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const Eigen::Vector3d c = o + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
        keep[cid(i, j, k)] = field.Distance(c) < limit ? 1 : 0;
      }

  // Face-connected components; keep the largest unless all are wanted.
  if (options.largest_component) {
    std::vector<int> label(ncell, -1);
    std::vector<std::size_t> stack;
    int best = -1;
    std::size_t best_size = 0;
    int next = 0;
    for (std::size_t s = 0; s < ncell; ++s) {
      if (!keep[s] || label[s] >= 0) continue;
      std::size_t count = 0;
      stack.assign(1, s);
      label[s] = next;
      while (!stack.empty()) {
        const std::size_t c = stack.back();
        stack.pop_back();
        ++count;
        const int i = int(c % n.x()), j = int((c / n.x()) % n.y()), k = int(c / (std::size_t(n.x()) * n.y()));
        const int nb[6][3] = {{i - 1, j, k}, {i + 1, j, k}, {i, j - 1, k}, {i, j + 1, k}, {i, j, k - 1}, {i, j, k + 1}};
        for (const auto& q : nb) {
          if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= n.x() || q[1] >= n.y() || q[2] >= n.z()) continue;
          const std::size_t e = cid(q[0], q[1], q[2]);
          if (keep[e] && label[e] < 0) {
            label[e] = next;
            stack.push_back(e);
          }
        }
      }
      if (count > best_size) {
        best_size = count;
        best = next;
      }
      ++next;
    }
    for (std::size_t s = 0; s < ncell; ++s) keep[s] = (keep[s] && label[s] == best) ? 1 : 0;
  }
  TetMesh mesh = TetsOfCells(keep, n.x(), n.y(), n.z(), o, h, options.split);
  if (mesh.tets.empty()) Fail(where, "no cell was kept; the interior is thinner than the cells");
  return mesh;
}

}  // namespace contactlab
