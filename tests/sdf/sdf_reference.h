// Brute-force references for the distance-field tests: exact distance to every triangle and
// the winding-number sign (Barbič & James 2008, sec. 2.3).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>

#include "geometry/triangle_mesh.h"
#include "sdf/point_triangle_distance.h"
#include "sdf/winding_number.h"

namespace contactlab::testing {

// Exact unsigned distance from P to MESH (all triangles).
inline double BruteForceDistance(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles) {
    best = std::min(best, PointTriangleDistanceSquared(p.data(), mesh.vertices[t[0]].data(),
                                                       mesh.vertices[t[1]].data(), mesh.vertices[t[2]].data()));
  }
  return std::sqrt(best);
}

// Exact signed distance to a closed MESH: negative where |winding number| > 1/2.
inline double BruteForceSignedDistance(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  const double d = BruteForceDistance(mesh, p);
  return std::abs(WindingNumber(mesh, p)) > 0.5 ? -d : d;
}

}  // namespace contactlab::testing

#include <map>
#include <utility>

namespace contactlab::testing {

// Edge census of a triangle mesh by vertex index: a closed, consistently oriented surface has
// no boundary, non-manifold or doubly used directed edges.
struct EdgeCensus {
  int boundary = 0;      // undirected edges used by one triangle
  int nonmanifold = 0;   // used by more than two
  int inconsistent = 0;  // a directed edge used twice
};
inline EdgeCensus CountEdges(const TriangleMesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles)
    for (int s = 0; s < 3; ++s) ++directed[{t[s], t[(s + 1) % 3]}];
  EdgeCensus c;
  for (const auto& [e, n] : directed) {
    if (n > 1) ++c.inconsistent;
    const auto it = directed.find({e.second, e.first});
    const int back = it == directed.end() ? 0 : it->second;
    if (e.first < e.second || back == 0) {
      if (n + back == 1) ++c.boundary;
      if (n + back > 2) ++c.nonmanifold;
    }
  }
  return c;
}

}  // namespace contactlab::testing
