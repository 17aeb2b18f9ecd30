// Test fixtures for the contact model: analytic fields sampled on grids and sphere/box
// pointshells with a nested tree, independent of the repulsion builder.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <numeric>
#include <random>
#include <vector>

#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab::testing {

// Samples PHI on a grid over BOX_MIN..BOX_MAX with spacing H.
inline std::shared_ptr<DistanceField> SampleField(const std::function<double(const Eigen::Vector3d&)>& phi,
                                                  const Eigen::Vector3d& box_min, const Eigen::Vector3d& box_max,
                                                  double h) {
  const Eigen::Vector3i dims = (((box_max - box_min) / h).array().ceil().cast<int>() + 1).matrix();
  std::vector<float> v;
  v.reserve(std::size_t(dims.prod()));
  for (int k = 0; k < dims.z(); ++k)
    for (int j = 0; j < dims.y(); ++j)
      for (int i = 0; i < dims.x(); ++i) v.push_back(float(phi(box_min + h * Eigen::Vector3d(i, j, k))));
  return std::make_shared<DistanceField>(box_min, h, dims, std::move(v), DistanceFieldInfo{"analytic", "analytic", 0, 0});
}

// Points with inward normals -> a Pointshell whose level i holds the first COUNTS[i] points;
// parents are the nearest nodes of the previous level and radii cover each subtree.
inline std::shared_ptr<Pointshell> MakeNestedShell(const std::vector<Eigen::Vector3d>& p,
                                                   const std::vector<Eigen::Vector3d>& n,
                                                   const std::vector<int>& counts) {
  auto s = std::make_shared<Pointshell>();
  for (std::size_t i = 0; i < p.size(); ++i) {
    s->x.push_back(float(p[i].x()));
    s->y.push_back(float(p[i].y()));
    s->z.push_back(float(p[i].z()));
    s->nx.push_back(float(n[i].x()));
    s->ny.push_back(float(n[i].y()));
    s->nz.push_back(float(n[i].z()));
  }
  s->level_point_end = counts;
  const int levels = int(counts.size());
  // Nodes per level: the level's points ordered by parent node.
  std::vector<std::vector<int>> level_points(levels), level_parent(levels);
  for (int i = 0; i < counts[0]; ++i) {
    level_points[0].push_back(i);
    level_parent[0].push_back(-1);
  }
  s->level_node_begin = {0};
  s->level_node_begin.push_back(counts[0]);
  for (int L = 1; L < levels; ++L) {
    const auto& prev = level_points[L - 1];
    std::vector<std::pair<int, int>> pairs;  // (parent slot in prev level, point)
    for (int i = 0; i < counts[L]; ++i) {
      int best = 0;
      double best_d = 1e300;
      for (int slot = 0; slot < int(prev.size()); ++slot) {
        const double d = (p[i] - p[prev[slot]]).squaredNorm();
        if (d < best_d) best_d = d, best = slot;
      }
      pairs.emplace_back(best, i);
    }
    std::stable_sort(pairs.begin(), pairs.end(), [](auto a, auto b) { return a.first < b.first; });
    for (auto [slot, i] : pairs) {
      level_points[L].push_back(i);
      level_parent[L].push_back(s->level_node_begin[L - 1] + slot);
    }
    s->level_node_begin.push_back(s->level_node_begin.back() + counts[L]);
  }
  const int nodes = s->level_node_begin.back();
  s->node_point.resize(nodes);
  s->node_parent.resize(nodes);
  s->node_radius.assign(nodes, 0.f);
  s->child_begin.assign(nodes + 1, 0);
  for (int L = 0; L < levels; ++L) {
    for (int k = 0; k < counts[L]; ++k) {
      s->node_point[s->level_node_begin[L] + k] = level_points[L][k];
      s->node_parent[s->level_node_begin[L] + k] = level_parent[L][k];
    }
  }
  // child_begin: children of level-L nodes are contiguous in level L+1 (sorted by parent).
  for (int node = 0; node < nodes; ++node) s->child_begin[node + 1] = s->child_begin[node];
  std::vector<int> child_count(nodes, 0);
  for (int node = 0; node < nodes; ++node)
    if (s->node_parent[node] >= 0) child_count[s->node_parent[node]]++;
  int cursor = counts[0];
  for (int node = 0; node < nodes; ++node) {
    s->child_begin[node] = cursor;
    cursor += child_count[node];
  }
  s->child_begin[nodes] = cursor;
  // Radii bottom-up.
  for (int node = nodes - 1; node >= 0; --node) {
    const int parent = s->node_parent[node];
    if (parent < 0) continue;
    const double dist = (p[s->node_point[node]] - p[s->node_point[parent]]).norm();
    s->node_radius[parent] = std::max(s->node_radius[parent], float(dist + s->node_radius[node]) * 1.0001f);
  }
  s->method = "test";
  return s;
}

// N near-uniform points on a sphere (Fibonacci lattice), inward normals, in random order.
inline void FibonacciSphere(double radius, int n, std::uint32_t seed, std::vector<Eigen::Vector3d>* p,
                            std::vector<Eigen::Vector3d>* normals, bool shuffle = true) {
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  if (shuffle) std::shuffle(order.begin(), order.end(), std::mt19937(seed));
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int k : order) {
    const double z = 1 - (k + 0.5) * 2.0 / n;
    const double r = std::sqrt(1 - z * z);
    const Eigen::Vector3d u(r * std::cos(golden * k), r * std::sin(golden * k), z);
    p->push_back(radius * u);
    normals->push_back(-u);
  }
}

// A nested sphere pointshell: LEVELS levels, level i has N0 * 4^i points.
inline std::shared_ptr<Pointshell> SphereShell(double radius, int n0, int levels, std::uint32_t seed = 1) {
  std::vector<int> counts;
  for (int i = 0, c = n0; i < levels; ++i, c *= 4) counts.push_back(c);
  std::vector<Eigen::Vector3d> p, n;
  FibonacciSphere(radius, counts.back(), seed, &p, &n);
  return MakeNestedShell(p, n, counts);
}

}  // namespace contactlab::testing
