#include "baselines/inner_spheres/sphere_tree.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "util/error.h"

namespace contactlab {
namespace {

struct Builder {
  const SpherePacking& packing;
  SphereTree& tree;

  // Builds the node over SPHERES [first, last) at DEPTH; returns its index.
  std::int32_t Build(std::vector<std::int32_t>& spheres, std::size_t first, std::size_t last, int depth) {
    const std::int32_t id = std::int32_t(tree.nodes.size());
    tree.nodes.emplace_back();
    tree.depth = std::max(tree.depth, depth);
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = -lo, weighted = Eigen::Vector3d::Zero();
    double volume = 0;
    for (std::size_t i = first; i < last; ++i) {
      const Eigen::Vector3d& c = packing.centers[std::size_t(spheres[i])];
      const double r = packing.radii[std::size_t(spheres[i])];
      lo = lo.cwiseMin(c - Eigen::Vector3d::Constant(r));
      hi = hi.cwiseMax(c + Eigen::Vector3d::Constant(r));
      const double v = r * r * r;
      weighted += v * c;
      volume += v;
    }
    SphereTreeNode node;
    node.center = 0.5 * (lo + hi);
    for (std::size_t i = first; i < last; ++i) {
      const std::size_t s = std::size_t(spheres[i]);
      node.radius = std::max(node.radius, (packing.centers[s] - node.center).norm() + packing.radii[s]);
    }
    node.proxy_center = weighted / volume;
    node.proxy_radius = std::cbrt(volume);
    if (last - first == 1) {
      node.sphere = spheres[first];
    } else {
      Eigen::Vector3d clo = Eigen::Vector3d::Constant(INFINITY), chi = -clo;
      for (std::size_t i = first; i < last; ++i) {
        clo = clo.cwiseMin(packing.centers[std::size_t(spheres[i])]);
        chi = chi.cwiseMax(packing.centers[std::size_t(spheres[i])]);
      }
      int axis;
      (chi - clo).maxCoeff(&axis);
      const std::size_t mid = first + (last - first) / 2;
      std::nth_element(spheres.begin() + std::ptrdiff_t(first), spheres.begin() + std::ptrdiff_t(mid),
                       spheres.begin() + std::ptrdiff_t(last), [&](std::int32_t a, std::int32_t b) {
                         const double ca = packing.centers[std::size_t(a)][axis], cb = packing.centers[std::size_t(b)][axis];
                         return ca < cb || (ca == cb && a < b);
                       });
      node.child[0] = Build(spheres, first, mid, depth + 1);
      node.child[1] = Build(spheres, mid, last, depth + 1);
    }
    tree.nodes[std::size_t(id)] = node;
    return id;
  }
};

}  // namespace

SphereTree BuildSphereTree(const SpherePacking& packing) {
  if (packing.radii.empty()) Fail("sphere tree", "the packing holds no sphere");
  SphereTree tree;
  tree.nodes.reserve(2 * packing.radii.size());
  std::vector<std::int32_t> spheres(packing.radii.size());
  std::iota(spheres.begin(), spheres.end(), 0);
  Builder{packing, tree}.Build(spheres, 0, spheres.size(), 0);
  return tree;
}

}  // namespace contactlab
