// Nested point tree: parents, child ranges and bounding radii (Barbič & James 2008, sec. 2.4).
#include "pointshell/point_tree.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <limits>

#include "pointshell/nearest_point_index.h"
#include "util/error.h"

namespace contactlab {

void BuildPointTree(Pointshell* shell) {
  Pointshell& s = *shell;
  const int levels = s.num_levels();
  const std::int32_t num_points = s.num_points();
  if (levels < 1) Fail("pointshell tree", "the pointshell has no levels");
  for (int i = 0; i < levels; ++i) {
    const std::int32_t lo = i == 0 ? 0 : s.level_point_end[i - 1];
    if (s.level_point_end[i] <= lo) Fail("pointshell tree", "level point counts are not increasing");
  }
  if (s.level_point_end.back() != num_points) Fail("pointshell tree", "the last level does not hold every point");

  // Node ranges: level i has level_point_end[i] nodes.
  s.level_node_begin.assign(levels + 1, 0);
  for (int i = 0; i < levels; ++i) s.level_node_begin[i + 1] = s.level_node_begin[i] + s.level_point_end[i];
  const std::int32_t num_nodes = s.level_node_begin[levels];
  s.node_point.assign(num_nodes, -1);
  s.node_parent.assign(num_nodes, -1);
  s.child_begin.assign(num_nodes + 1, num_nodes);
  s.node_radius.assign(num_nodes, 0.f);

  // Level 0: points in index order, no parents.
  std::vector<std::int32_t> node_of_point(num_points, -1);  // node of each point on the current level
  for (std::int32_t p = 0; p < s.level_point_end[0]; ++p) {
    s.node_point[p] = p;
    node_of_point[p] = p;
  }

  // Each next level: parent node per point, then a stable counting sort by parent.
  std::vector<std::int32_t> parent_of_point(num_points);
  for (int i = 0; i + 1 < levels; ++i) {
    const std::int32_t coarse = s.level_point_end[i], fine = s.level_point_end[i + 1];
    const std::int32_t begin = s.level_node_begin[i], next_begin = s.level_node_begin[i + 1];
    for (std::int32_t p = 0; p < coarse; ++p) parent_of_point[p] = node_of_point[p];
    const NearestPointIndex index(s.x.data(), s.y.data(), s.z.data(), coarse);
    tbb::parallel_for(coarse, fine, [&](std::int32_t p) {
      const float q[3] = {s.x[p], s.y[p], s.z[p]};
      std::int32_t nearest = 0;
      float d2 = 0;
      index.Nearest(q, 1, &nearest, &d2);
      parent_of_point[p] = node_of_point[nearest];
    });
    // Counting sort by parent (points visited in increasing order: stable).
    std::vector<std::int32_t> count(coarse + 1, 0);
    for (std::int32_t p = 0; p < fine; ++p) ++count[parent_of_point[p] - begin + 1];
    for (std::int32_t c = 0; c < coarse; ++c) count[c + 1] += count[c];
    for (std::int32_t c = 0; c < coarse; ++c) s.child_begin[begin + c] = next_begin + count[c];
    for (std::int32_t p = 0; p < fine; ++p) {
      const std::int32_t node = next_begin + count[parent_of_point[p] - begin]++;
      s.node_point[node] = p;
      s.node_parent[node] = parent_of_point[p];
      node_of_point[p] = node;
    }
  }
  // Children of the deepest level: empty ranges ending at num_nodes (already set).
  // Nodes of the level before the deepest: child_begin filled above; the deepest level and the
  // sentinel keep num_nodes.

  // Radii: each leaf updates every ancestor with its distance (exact subtree bound).
  std::vector<double> radius(num_nodes, 0.0);
  for (std::int32_t leaf = s.level_node_begin[levels - 1]; leaf < num_nodes; ++leaf) {
    const std::int32_t p = s.node_point[leaf];
    for (std::int32_t a = s.node_parent[leaf]; a >= 0; a = s.node_parent[a]) {
      const std::int32_t q = s.node_point[a];
      const double dx = double(s.x[p]) - s.x[q], dy = double(s.y[p]) - s.y[q], dz = double(s.z[p]) - s.z[q];
      radius[a] = std::max(radius[a], std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  }
  for (std::int32_t n = 0; n < num_nodes; ++n) {
    float r = float(radius[n]);
    if (double(r) < radius[n]) r = std::nextafter(r, std::numeric_limits<float>::infinity());
    s.node_radius[n] = r;
  }
}

std::int32_t NodeWithoutOwnFirstChild(const Pointshell& s) {
  const int levels = s.num_levels();
  if (levels < 2) return -1;
  for (std::int32_t n = 0; n < s.level_node_begin[levels - 1]; ++n) {
    const std::int32_t c = s.child_begin[n];
    if (c >= s.child_begin[n + 1] || s.node_point[c] != s.node_point[n]) return n;
  }
  return -1;
}

}  // namespace contactlab
