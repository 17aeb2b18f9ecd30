// Marching cubes with a generated, crack-free case table (Barbič & James 2008, sec. 2.3).
#include "sdf/marching_cubes.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace contactlab {
namespace {

int EdgeOf(int c0, int c1) {
  for (int e = 0; e < 12; ++e) {
    if ((kCubeEdgeCorners[e][0] == c0 && kCubeEdgeCorners[e][1] == c1) ||
        (kCubeEdgeCorners[e][0] == c1 && kCubeEdgeCorners[e][1] == c0)) {
      return e;
    }
  }
  return -1;
}

// Polygons (cycles of crossed edges) of one case, from the face rule in the header.
std::vector<std::vector<int>> CasePolygons(int mask) {
  int next[12];
  std::fill(next, next + 12, -1);
  for (int a = 0; a < 3; ++a) {
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      // Face corners counter-clockwise seen from outside the cube.
      int cyc[4];
      const int uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
      for (int m = 0; m < 4; ++m) cyc[m] = (side << a) | (uv[m][0] << u) | (uv[m][1] << v);
      if (side == 0) std::reverse(cyc, cyc + 4);
      // Crossings in that order; each outside->inside crossing joins the next crossing.
      int edge[4], out_in[4], n = 0;
      for (int m = 0; m < 4; ++m) {
        const int c0 = cyc[m], c1 = cyc[(m + 1) % 4];
        const bool in0 = (mask >> c0) & 1, in1 = (mask >> c1) & 1;
        if (in0 == in1) continue;
        edge[n] = EdgeOf(c0, c1);
        out_in[n] = !in0 && in1;
        ++n;
      }
      for (int m = 0; m < n; ++m) {
        if (out_in[m]) next[edge[m]] = edge[(m + 1) % n];
      }
    }
  }
  std::vector<std::vector<int>> polygons;
  bool used[12] = {};
  for (int e = 0; e < 12; ++e) {
    if (next[e] < 0 || used[e]) continue;
    std::vector<int> poly;
    for (int x = e; !used[x]; x = next[x]) {
      used[x] = true;
      poly.push_back(x);
    }
    polygons.push_back(poly);
  }
  return polygons;
}

// True when cube edges E and F lie on a common cube face.
bool ShareFace(int e, int f) {
  for (int bit = 1; bit <= 4; bit <<= 1) {
    const int ce = kCubeEdgeCorners[e][0], cf = kCubeEdgeCorners[f][0];
    const bool e_spans = (kCubeEdgeCorners[e][1] ^ ce) == bit, f_spans = (kCubeEdgeCorners[f][1] ^ cf) == bit;
    if (!e_spans && !f_spans && (ce & bit) == (cf & bit)) return true;
  }
  return false;
}

std::array<std::array<std::int8_t, kMarchingCubesRow>, 256> GenerateTable() {
  std::array<std::array<std::int8_t, kMarchingCubesRow>, 256> table;
  for (auto& row : table) row.fill(-1);
  // Orientation: the polygon of case 1 (corner 0 inside) must face away from corner 0.
  auto edge_mid = [](int e) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int s = 0; s < 2; ++s) {
      const int c = kCubeEdgeCorners[e][s];
      p += 0.5 * Eigen::Vector3d(c & 1, (c >> 1) & 1, (c >> 2) & 1);
    }
    return p;
  };
  const auto probe = CasePolygons(1)[0];
  const Eigen::Vector3d n = (edge_mid(probe[1]) - edge_mid(probe[0])).cross(edge_mid(probe[2]) - edge_mid(probe[0]));
  const bool flip = n.dot(edge_mid(probe[0])) < 0;
  for (int mask = 0; mask < 256; ++mask) {
    int w = 0;
    for (auto poly : CasePolygons(mask)) {
      if (flip) std::reverse(poly.begin(), poly.end());
      const int size = int(poly.size());
      int fan = -1;
      for (int s = 0; s < size && fan < 0; ++s) {
        bool ok = true;
        for (int t = 2; t + 1 < size; ++t) ok = ok && !ShareFace(poly[s], poly[(s + t) % size]);
        if (ok) fan = s;
      }
      table[mask][w++] = std::int8_t(size);
      table[mask][w++] = std::int8_t(fan);
      for (int e : poly) table[mask][w++] = std::int8_t(e);
    }
  }
  return table;
}

}  // namespace

const std::array<std::array<std::int8_t, kMarchingCubesRow>, 256>& MarchingCubesTable() {
  static const auto table = GenerateTable();
  return table;
}

TriangleMesh ExtractIsosurface(const std::vector<float>& values_in, const FieldGrid& grid_in, double iso,
                               bool close_at_boundary, const std::string& name) {
  // Optionally surround the grid with one layer of "outside" samples.
  const std::vector<float>* values = &values_in;
  FieldGrid grid = grid_in;
  std::vector<float> bordered;
  if (close_at_boundary) {
    grid.origin = grid_in.origin.array() - grid_in.spacing;
    grid.dims = grid_in.dims.array() + 2;
    bordered.assign(grid.num_points(), float(iso + grid.spacing));
    for (int k = 0; k < grid_in.dims.z(); ++k)
      for (int j = 0; j < grid_in.dims.y(); ++j)
        std::copy_n(values_in.data() + grid_in.Index(0, j, k), grid_in.dims.x(),
                    bordered.data() + grid.Index(1, j + 1, k + 1));
    values = &bordered;
  }
  const auto& table = MarchingCubesTable();
  const int nx = grid.dims.x(), ny = grid.dims.y(), nz = grid.dims.z();
  const float fiso = float(iso);
  const float* v = values->data();

  TriangleMesh mesh;
  mesh.name = name;
  // Vertex ids of crossed grid edges: x- and y-edges of two z-layers, z-edges of one cell layer.
  std::vector<int> xs[2], ys[2], zs;
  for (int l = 0; l < 2; ++l) {
    xs[l].assign(std::size_t(nx) * ny, -1);
    ys[l].assign(std::size_t(nx) * ny, -1);
  }
  zs.assign(std::size_t(nx) * ny, -1);
  auto vertex_on = [&](int i, int j, int k, int axis) {
    int* slot;
    if (axis == 0) slot = &xs[k & 1][i + std::size_t(nx) * j];
    else if (axis == 1) slot = &ys[k & 1][i + std::size_t(nx) * j];
    else slot = &zs[i + std::size_t(nx) * j];
    if (*slot >= 0) return *slot;
    const float a = v[grid.Index(i, j, k)];
    const float b = v[grid.Index(i + (axis == 0), j + (axis == 1), k + (axis == 2))];
    const double t = std::clamp((double(iso) - a) / (double(b) - a), 0.0, 1.0);
    Eigen::Vector3d p = grid.Point(i, j, k);
    p[axis] += t * grid.spacing;
    mesh.vertices.push_back(p);
    *slot = mesh.num_vertices() - 1;
    return *slot;
  };
  for (int k = 0; k + 1 < nz; ++k) {
    // Layer k+1 and the z-edges of this cell layer start empty.
    std::fill(xs[(k + 1) & 1].begin(), xs[(k + 1) & 1].end(), -1);
    std::fill(ys[(k + 1) & 1].begin(), ys[(k + 1) & 1].end(), -1);
    std::fill(zs.begin(), zs.end(), -1);
    for (int j = 0; j + 1 < ny; ++j) {
      for (int i = 0; i + 1 < nx; ++i) {
        int mask = 0;
        for (int c = 0; c < 8; ++c) {
          if (v[grid.Index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))] < fiso) mask |= 1 << c;
        }
        if (mask == 0 || mask == 255) continue;
        const auto& row = table[mask];
        for (int n = 0; row[n] >= 0;) {
          const int size = row[n], fan = row[n + 1];
          int ids[12];
          for (int s = 0; s < size; ++s) {
            const int e = row[n + 2 + s];
            const int c0 = kCubeEdgeCorners[e][0];
            const int bit = kCubeEdgeCorners[e][1] ^ c0;
            const int axis = bit == 1 ? 0 : bit == 2 ? 1 : 2;
            ids[s] = vertex_on(i + (c0 & 1), j + ((c0 >> 1) & 1), k + ((c0 >> 2) & 1), axis);
          }
          if (fan >= 0) {
            for (int m = 1; m + 1 < size; ++m) {
              mesh.triangles.emplace_back(ids[fan], ids[(fan + m) % size], ids[(fan + m + 1) % size]);
            }
          } else {
            Eigen::Vector3d centre = Eigen::Vector3d::Zero();
            for (int s = 0; s < size; ++s) centre += mesh.vertices[ids[s]];
            mesh.vertices.push_back(centre / size);
            const int c = mesh.num_vertices() - 1;
            for (int s = 0; s < size; ++s) mesh.triangles.emplace_back(c, ids[s], ids[(s + 1) % size]);
          }
          n += 2 + size;
        }
      }
    }
  }
  return mesh;
}

}  // namespace contactlab
