#include "geometry/procedural_shapes.h"

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "util/error.h"

namespace contactlab {
namespace {

constexpr double kPi = std::numbers::pi;

// Grid of (nu x nv) vertices wrapped into a closed surface by the caller's index map.
void AddQuad(TriangleMesh& m, int a, int b, int c, int d) {
  // a-b-c-d counter-clockwise seen from outside.
  m.triangles.emplace_back(a, b, c);
  m.triangles.emplace_back(a, c, d);
}

}  // namespace

TriangleMesh MakeSphere(double radius, int subdivisions) {
  if (!(radius > 0) || subdivisions < 0 || subdivisions > 8) {
    Fail("MakeSphere", "needs radius > 0 and 0 <= subdivisions <= 8");
  }
  TriangleMesh m;
  m.name = "sphere";
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double base[12][3] = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0},
                              {0, -1, t}, {0, 1, t},  {0, -1, -t}, {0, 1, -t},
                              {t, 0, -1}, {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (const auto& v : base) m.vertices.push_back(Eigen::Vector3d(v[0], v[1], v[2]).normalized());
  const int faces[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                            {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                            {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                            {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (const auto& f : faces) m.triangles.emplace_back(f[0], f[1], f[2]);
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      const int id = m.num_vertices() - 1;
      midpoint.emplace(key, id);
      return id;
    };
    std::vector<Eigen::Vector3i> next;
    next.reserve(m.triangles.size() * 4);
    for (const auto& f : m.triangles) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      next.emplace_back(f[0], ab, ca);
      next.emplace_back(f[1], bc, ab);
      next.emplace_back(f[2], ca, bc);
      next.emplace_back(ab, bc, ca);
    }
    m.triangles = std::move(next);
  }
  for (auto& v : m.vertices) v *= radius;
  return m;
}

TriangleMesh MakeBox(const Eigen::Vector3d& half, int cuts_per_edge) {
  if (!(half.array() > 0).all() || cuts_per_edge < 1) {
    Fail("MakeBox", "needs positive half extents and cuts_per_edge >= 1");
  }
  TriangleMesh m;
  m.name = "box";
  const int n = cuts_per_edge;
  std::map<std::tuple<int, int, int>, int> index;  // lattice point -> vertex id (shared edges)
  auto vertex = [&](int i, int j, int k) {
    const auto key = std::make_tuple(i, j, k);
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    m.vertices.emplace_back(half.x() * (2.0 * i / n - 1), half.y() * (2.0 * j / n - 1),
                            half.z() * (2.0 * k / n - 1));
    index.emplace(key, m.num_vertices() - 1);
    return m.num_vertices() - 1;
  };
  // Each face: fixed axis `a` at side s (0 or n); (u, v) axes chosen so u x v points outward.
  for (int a = 0; a < 3; ++a) {
    for (int side = 0; side < 2; ++side) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          auto lattice = [&](int di, int dj) {
            int c[3];
            c[a] = side * n;
            c[u] = i + di;
            c[v] = j + dj;
            return vertex(c[0], c[1], c[2]);
          };
          const int p00 = lattice(0, 0), p10 = lattice(1, 0), p11 = lattice(1, 1), p01 = lattice(0, 1);
          if (side == 1) AddQuad(m, p00, p10, p11, p01);
          else AddQuad(m, p00, p01, p11, p10);
        }
      }
    }
  }
  return m;
}

TriangleMesh MakeTorus(double major, double minor, int major_segments, int minor_segments) {
  if (!(major > minor && minor > 0) || major_segments < 3 || minor_segments < 3) {
    Fail("MakeTorus", "needs major > minor > 0 and at least 3 segments each way");
  }
  TriangleMesh m;
  m.name = "torus";
  for (int i = 0; i < major_segments; ++i) {
    const double u = 2 * kPi * i / major_segments;
    for (int j = 0; j < minor_segments; ++j) {
      const double v = 2 * kPi * j / minor_segments;
      const double r = major + minor * std::cos(v);
      m.vertices.emplace_back(r * std::cos(u), r * std::sin(u), minor * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return (i % major_segments) * minor_segments + (j % minor_segments); };
  for (int i = 0; i < major_segments; ++i) {
    for (int j = 0; j < minor_segments; ++j) {
      AddQuad(m, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
  return m;
}

TriangleMesh MakeCapsule(double radius, double half_length, int segments, int rings) {
  if (!(radius > 0) || !(half_length >= 0) || segments < 3 || rings < 1) {
    Fail("MakeCapsule", "needs radius > 0, half_length >= 0, segments >= 3, rings >= 1");
  }
  TriangleMesh m;
  m.name = "capsule";
  // Latitude rows from the top pole to the bottom pole; the two equator rows are the cylinder.
  std::vector<std::pair<double, double>> rows;  // (ring radius, z)
  for (int r = 1; r <= rings; ++r) {
    const double phi = 0.5 * kPi * r / rings;  // from the pole
    rows.emplace_back(radius * std::sin(phi), half_length + radius * std::cos(phi));
  }
  for (int r = rings; r >= 1; --r) {
    const double phi = 0.5 * kPi * r / rings;
    rows.emplace_back(radius * std::sin(phi), -half_length - radius * std::cos(phi));
  }
  m.vertices.emplace_back(0, 0, half_length + radius);
  for (const auto& [rr, z] : rows) {
    for (int s = 0; s < segments; ++s) {
      const double u = 2 * kPi * s / segments;
      m.vertices.emplace_back(rr * std::cos(u), rr * std::sin(u), z);
    }
  }
  m.vertices.emplace_back(0, 0, -half_length - radius);
  const int top = 0, bottom = m.num_vertices() - 1;
  auto id = [&](int row, int s) { return 1 + row * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) m.triangles.emplace_back(top, id(0, s), id(0, s + 1));
  for (int row = 0; row + 1 < static_cast<int>(rows.size()); ++row) {
    for (int s = 0; s < segments; ++s) AddQuad(m, id(row, s), id(row + 1, s), id(row + 1, s + 1), id(row, s + 1));
  }
  const int last = static_cast<int>(rows.size()) - 1;
  for (int s = 0; s < segments; ++s) m.triangles.emplace_back(bottom, id(last, s + 1), id(last, s));
  return m;
}

TriangleMesh MakeTube(double outer, double inner, double half_length, int segments) {
  if (!(outer > inner && inner > 0) || !(half_length > 0) || segments < 3) {
    Fail("MakeTube", "needs outer > inner > 0, half_length > 0 and at least 3 segments");
  }
  TriangleMesh m;
  m.name = "tube";
  // Four rings: outer top, outer bottom, inner bottom, inner top; quads between consecutive
  // rings (and from the last back to the first) wind outward: the outer wall, the bottom
  // annulus, the inner wall (facing the axis) and the top annulus.
  const double radius[4] = {outer, outer, inner, inner};
  const double z[4] = {half_length, -half_length, -half_length, half_length};
  for (int k = 0; k < 4; ++k) {
    for (int s = 0; s < segments; ++s) {
      const double u = 2 * kPi * s / segments;
      m.vertices.emplace_back(radius[k] * std::cos(u), radius[k] * std::sin(u), z[k]);
    }
  }
  auto id = [&](int ring, int s) { return (ring % 4) * segments + (s % segments); };
  for (int k = 0; k < 4; ++k) {
    for (int s = 0; s < segments; ++s) AddQuad(m, id(k, s), id(k + 1, s), id(k + 1, s + 1), id(k, s + 1));
  }
  return m;
}

TriangleMesh MakeBumpyPlate(double size, double thickness, int bumps, double height, int resolution) {
  if (!(size > 0) || !(thickness > 0) || bumps < 0 || resolution < 2) {
    Fail("MakeBumpyPlate", "needs size > 0, thickness > 0, bumps >= 0, resolution >= 2");
  }
  TriangleMesh m;
  m.name = "bumpy-plate";
  const int n = resolution;
  auto top_z = [&](double x, double y) {
    if (bumps == 0) return 0.0;
    const double fx = std::sin(kPi * bumps * (x / size + 0.5));
    const double fy = std::sin(kPi * bumps * (y / size + 0.5));
    return height * fx * fx * fy * fy;
  };
  // Top grid (n+1)^2, bottom grid (n+1)^2, sharing nothing; sides stitch the borders.
  auto coord = [&](int i) { return size * (double(i) / n - 0.5); };
  for (int layer = 0; layer < 2; ++layer) {
    for (int j = 0; j <= n; ++j) {
      for (int i = 0; i <= n; ++i) {
        const double x = coord(i), y = coord(j);
        m.vertices.emplace_back(x, y, layer == 0 ? top_z(x, y) : -thickness);
      }
    }
  }
  auto top = [&](int i, int j) { return j * (n + 1) + i; };
  auto bot = [&](int i, int j) { return (n + 1) * (n + 1) + j * (n + 1) + i; };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      AddQuad(m, top(i, j), top(i + 1, j), top(i + 1, j + 1), top(i, j + 1));
      AddQuad(m, bot(i, j), bot(i, j + 1), bot(i + 1, j + 1), bot(i + 1, j));
    }
  }
  for (int i = 0; i < n; ++i) {
    AddQuad(m, top(i, 0), bot(i, 0), bot(i + 1, 0), top(i + 1, 0));          // y = -size/2
    AddQuad(m, top(i + 1, n), bot(i + 1, n), bot(i, n), top(i, n));          // y = +size/2
    AddQuad(m, top(0, i + 1), bot(0, i + 1), bot(0, i), top(0, i));          // x = -size/2
    AddQuad(m, top(n, i), bot(n, i), bot(n, i + 1), top(n, i + 1));          // x = +size/2
  }
  return m;
}

}  // namespace contactlab
