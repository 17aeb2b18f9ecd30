// A bounding-volume hierarchy over a body's inner spheres (sphere_packing.h): a binary tree,
// split at the median along the longest axis of the centres, each node bounded by a sphere
// around its leaves' spheres. Each node also carries a proxy: the sphere at its leaves'
// volume-weighted centroid with their total volume, which stands for the subtree when a
// time-critical traversal stops above it (Weller & Zachmann 2009, time-critical queries).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "baselines/inner_spheres/sphere_packing.h"

namespace contactlab {

struct SphereTreeNode {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // bounding sphere, body frame
  double radius = 0;
  Eigen::Vector3d proxy_center = Eigen::Vector3d::Zero();
  double proxy_radius = 0;
  std::int32_t child[2] = {-1, -1};  // both -1 at a leaf
  std::int32_t sphere = -1;          // a leaf's sphere
  bool leaf() const { return child[0] < 0; }
};

struct SphereTree {
  std::vector<SphereTreeNode> nodes;  // root first
  int depth = 0;                      // levels below the root
};

// Throws Error when PACKING holds no sphere.
SphereTree BuildSphereTree(const SpherePacking& packing);

}  // namespace contactlab
