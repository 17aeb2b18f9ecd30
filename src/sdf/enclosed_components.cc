// Enclosed-component removal for the soup pipeline (Barbič & James 2008, sec. 2.3).
#include "sdf/enclosed_components.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <numeric>

#include "sdf/winding_number.h"

namespace contactlab {

std::vector<TriangleMesh> SplitComponents(const TriangleMesh& mesh) {
  // Union-find over vertices joined by triangles.
  std::vector<int> parent(mesh.num_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& t : mesh.triangles) {
    for (int s = 1; s < 3; ++s) {
      const int a = find(t[0]), b = find(t[s]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  std::vector<int> component_of_root(mesh.num_vertices(), -1);
  std::vector<int> local(mesh.num_vertices(), -1);
  std::vector<TriangleMesh> components;
  for (const auto& t : mesh.triangles) {
    const int root = find(t[0]);
    if (component_of_root[root] < 0) {
      component_of_root[root] = int(components.size());
      components.emplace_back();
      components.back().name = mesh.name + " component " + std::to_string(components.size());
    }
    TriangleMesh& c = components[component_of_root[root]];
    Eigen::Vector3i f;
    for (int s = 0; s < 3; ++s) {
      if (local[t[s]] < 0) {
        local[t[s]] = c.num_vertices();
        c.vertices.push_back(mesh.vertices[t[s]]);
      }
      f[s] = local[t[s]];
    }
    c.triangles.push_back(f);
  }
  return components;
}

TriangleMesh RemoveEnclosedComponents(const TriangleMesh& mesh, int* removed) {
  const std::vector<TriangleMesh> parts = SplitComponents(mesh);
  const int n = int(parts.size());
  std::vector<Aabb> boxes(n);
  for (int c = 0; c < n; ++c) boxes[c] = parts[c].Bounds();
  std::vector<char> enclosed(n, 0);
  tbb::parallel_for(0, n, [&](int c) {
    for (int d = 0; d < n && !enclosed[c]; ++d) {
      if (d == c) continue;
      const bool box_inside = (boxes[c].min.array() >= boxes[d].min.array()).all() &&
                              (boxes[c].max.array() <= boxes[d].max.array()).all();
      if (!box_inside) continue;
      if (std::abs(WindingNumber(parts[d], parts[c].vertices[0])) > 0.5) enclosed[c] = 1;
    }
  });
  TriangleMesh kept;
  kept.name = mesh.name;
  int dropped = 0;
  for (int c = 0; c < n; ++c) {
    if (enclosed[c]) {
      ++dropped;
    } else {
      kept.Append(parts[c]);
    }
  }
  if (removed) *removed = dropped;
  return kept;
}

}  // namespace contactlab
