// Axis-aligned bounding boxes.
#pragma once

#include <Eigen/Core>
#include <limits>

namespace contactlab {

struct Aabb {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return (min.array() > max.array()).any(); }
  void Extend(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void Extend(const Aabb& b) {
    min = min.cwiseMin(b.min);
    max = max.cwiseMax(b.max);
  }
  Eigen::Vector3d size() const { return max - min; }
  Eigen::Vector3d center() const { return 0.5 * (min + max); }
  // Euclidean distance from P to the box (0 inside).
  double Distance(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d d = (min - p).cwiseMax(p - max).cwiseMax(0.0);
    return d.norm();
  }
  bool Contains(const Eigen::Vector3d& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
  Aabb Inflated(double margin) const {
    Aabb b = *this;
    b.min.array() -= margin;
    b.max.array() += margin;
    return b;
  }
};

}  // namespace contactlab
