// Flat-array BVH over triangles with exact closest-triangle queries (Barbič & James 2008, sec. 2.3).
#include "sdf/triangle_bvh.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "sdf/point_triangle_distance.h"

namespace contactlab {
namespace {

constexpr int kLeafSize = 4;
constexpr int kMaxDepth = 64;

}  // namespace

TriangleBvh::TriangleBvh(const std::vector<double>& corners) {
  const int n = int(corners.size() / 9);
  std::vector<std::int32_t> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  nodes_.reserve(std::size_t(2 * n / kLeafSize + 2));
  if (n > 0) Build(ids, corners, 0, n);
  ids_ = ids;
  tri_.resize(corners.size());
  for (int s = 0; s < n; ++s) std::copy_n(&corners[std::size_t(ids[s]) * 9], 9, &tri_[std::size_t(s) * 9]);
}

int TriangleBvh::Build(std::vector<std::int32_t>& ids, const std::vector<double>& corners, int begin, int end) {
  const int index = int(nodes_.size());
  nodes_.push_back({});
  Node node;
  double clo[3], chi[3];  // centroid bounds
  for (int a = 0; a < 3; ++a) {
    node.lo[a] = clo[a] = std::numeric_limits<double>::infinity();
    node.hi[a] = chi[a] = -std::numeric_limits<double>::infinity();
  }
  for (int s = begin; s < end; ++s) {
    const double* c = &corners[std::size_t(ids[s]) * 9];
    for (int a = 0; a < 3; ++a) {
      node.lo[a] = std::min({node.lo[a], c[a], c[3 + a], c[6 + a]});
      node.hi[a] = std::max({node.hi[a], c[a], c[3 + a], c[6 + a]});
      const double m = (c[a] + c[3 + a] + c[6 + a]) / 3;
      clo[a] = std::min(clo[a], m);
      chi[a] = std::max(chi[a], m);
    }
  }
  if (end - begin <= kLeafSize) {
    node.first = begin;
    node.count = end - begin;
    nodes_[index] = node;
    return index;
  }
  // Median split along the longest centroid extent.
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (chi[a] - clo[a] > chi[axis] - clo[axis]) axis = a;
  const int mid = (begin + end) / 2;
  std::nth_element(ids.begin() + begin, ids.begin() + mid, ids.begin() + end, [&](std::int32_t l, std::int32_t r) {
    const double* cl = &corners[std::size_t(l) * 9];
    const double* cr = &corners[std::size_t(r) * 9];
    return cl[axis] + cl[3 + axis] + cl[6 + axis] < cr[axis] + cr[3 + axis] + cr[6 + axis];
  });
  Build(ids, corners, begin, mid);
  node.first = Build(ids, corners, mid, end);
  node.count = 0;
  nodes_[index] = node;
  return index;
}

double TriangleBvh::ClosestSquared(const double* p, double bound2, std::int32_t* triangle) const {
  if (nodes_.empty()) return bound2;
  auto box_distance2 = [p](const Node& n) {
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const double d = std::max({n.lo[a] - p[a], p[a] - n.hi[a], 0.0});
      d2 += d * d;
    }
    return d2;
  };
  double best = bound2;
  std::int32_t stack[kMaxDepth * 2];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (box_distance2(node) >= best) continue;
    if (node.count > 0) {
      for (int s = node.first; s < node.first + node.count; ++s) {
        const double* c = &tri_[std::size_t(s) * 9];
        const double d2 = PointTriangleDistanceSquared(p, c, c + 3, c + 6);
        if (d2 < best) {
          best = d2;
          *triangle = ids_[s];
        }
      }
      continue;
    }
    // Visit the nearer child first (pushed last).
    const std::int32_t left = std::int32_t(&node - nodes_.data()) + 1, right = node.first;
    const double dl = box_distance2(nodes_[left]), dr = box_distance2(nodes_[right]);
    if (dl < dr) {
      if (dr < best) stack[top++] = right;
      if (dl < best) stack[top++] = left;
    } else {
      if (dl < best) stack[top++] = left;
      if (dr < best) stack[top++] = right;
    }
  }
  return best;
}

}  // namespace contactlab
