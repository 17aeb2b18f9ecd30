// A signed distance field on a dense, uniform float grid (Barbič & James 2008, sec. 2.3).
// Negative inside the object. Trilinear interpolation inside the grid box; outside it the
// conservative bound d(p) >= d_box(p) + d_boundary_min of the paper's Fig. 5(c).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "geometry/aabb.h"

namespace contactlab {

// How a field was made; stored in field files and printed in summaries.
struct DistanceFieldInfo {
  std::string source;        // mesh file or description
  std::string mode;          // "closed", "soup" or "analytic"
  double offset = 0;         // soup pipeline: iso-offset of the closed surface (metres), else 0
  double build_seconds = 0;  // wall time of the build
};

class DistanceField {
 public:
  DistanceField() = default;
  // Grid point (i, j, k) sits at ORIGIN + SPACING * (i, j, k); VALUES holds
  // DIMS.x * DIMS.y * DIMS.z samples, x fastest. Every dimension must be >= 2.
  // Throws Error when sizes disagree or a value is not finite.
  DistanceField(const Eigen::Vector3d& origin, double spacing, const Eigen::Vector3i& dims,
                std::vector<float> values, DistanceFieldInfo info = {});

  const Eigen::Vector3d& origin() const { return origin_; }
  double spacing() const { return spacing_; }
  const Eigen::Vector3i& dims() const { return dims_; }  // grid points per axis
  const std::vector<float>& values() const { return values_; }
  const DistanceFieldInfo& info() const { return info_; }
  DistanceFieldInfo& mutable_info() { return info_; }
  bool empty() const { return values_.empty(); }
  std::int64_t num_samples() const { return std::int64_t(values_.size()); }
  // Box spanned by the grid points.
  Aabb box() const;
  // Smallest sample on the grid's boundary faces (the paper's d_boundary).
  float boundary_min() const { return boundary_min_; }
  float min_value() const { return min_value_; }
  float max_value() const { return max_value_; }
  std::int64_t Index(int i, int j, int k) const {
    return i + std::int64_t(dims_.x()) * (j + std::int64_t(dims_.y()) * k);
  }
  float value(int i, int j, int k) const { return values_[Index(i, j, k)]; }
  Eigen::Vector3d GridPoint(int i, int j, int k) const {
    return origin_ + spacing_ * Eigen::Vector3d(i, j, k);
  }

  // Signed distance at P (field frame, metres). Inside the box: trilinear interpolation;
  // outside: the conservative lower bound. Never allocates, never throws.
  inline float Distance(float x, float y, float z) const;
  double Distance(const Eigen::Vector3d& p) const { return Distance(float(p.x()), float(p.y()), float(p.z())); }

  // Signed distance and the gradient of the trilinear interpolant at P (outside the box:
  // the bound and the gradient of d_box). Double precision throughout.
  double DistanceAndGradient(const Eigen::Vector3d& p, Eigen::Vector3d* gradient) const;

  // The hot-path constants of Distance, for the vectorised lookups (sdf/batch_distance.h).
  struct FloatGrid {
    const float* values;
    int nx, ny, nz;
    float ox, oy, oz, inv_h, ex, ey, ez, x1, y1, z1, boundary_min;
  };
  FloatGrid float_grid() const {
    return {values_.data(), dims_.x(), dims_.y(), dims_.z(), ox_, oy_, oz_, inv_h_, ex_, ey_, ez_,
            x1_, y1_, z1_, boundary_min_};
  }

  // True when P lies inside the grid box.
  bool Inside(const Eigen::Vector3d& p) const;

 private:
  // The conservative bound outside the box: distance to the box + boundary_min.
  inline float OutsideBound(float x, float y, float z) const;

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double spacing_ = 1;
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  std::vector<float> values_;
  DistanceFieldInfo info_;
  float boundary_min_ = 0, min_value_ = 0, max_value_ = 0;
  // Hot-path copies in float.
  float ox_ = 0, oy_ = 0, oz_ = 0, inv_h_ = 1, ex_ = 0, ey_ = 0, ez_ = 0;  // e*: last grid coordinate
  float x1_ = 0, y1_ = 0, z1_ = 0;  // the box's upper corner
};

inline float DistanceField::Distance(float x, float y, float z) const {
  const float gx = (x - ox_) * inv_h_, gy = (y - oy_) * inv_h_, gz = (z - oz_) * inv_h_;
  if (!(gx >= 0.f && gy >= 0.f && gz >= 0.f && gx <= ex_ && gy <= ey_ && gz <= ez_)) {
    return OutsideBound(x, y, z);
  }
  // Cell index clamped so the last grid point uses the last cell with t = 1.
  const int i = std::min(int(gx), dims_.x() - 2);
  const int j = std::min(int(gy), dims_.y() - 2);
  const int k = std::min(int(gz), dims_.z() - 2);
  const float tx = gx - float(i), ty = gy - float(j), tz = gz - float(k);
  const std::int64_t sx = 1, sy = dims_.x(), sz = std::int64_t(dims_.x()) * dims_.y();
  const float* v = values_.data() + i + sy * j + sz * k;
  const float c00 = v[0] + tx * (v[sx] - v[0]);
  const float c10 = v[sy] + tx * (v[sy + sx] - v[sy]);
  const float c01 = v[sz] + tx * (v[sz + sx] - v[sz]);
  const float c11 = v[sz + sy] + tx * (v[sz + sy + sx] - v[sz + sy]);
  const float c0 = c00 + ty * (c10 - c00);
  const float c1 = c01 + ty * (c11 - c01);
  return c0 + tz * (c1 - c0);
}

inline float DistanceField::OutsideBound(float x, float y, float z) const {
  // NaN or infinite input, or an empty field: never in contact.
  if (values_.empty() || !(std::abs(x) + std::abs(y) + std::abs(z) < std::numeric_limits<float>::infinity())) {
    return std::numeric_limits<float>::infinity();
  }
  const float dx = std::max(std::max(ox_ - x, x - x1_), 0.f);
  const float dy = std::max(std::max(oy_ - y, y - y1_), 0.f);
  const float dz = std::max(std::max(oz_ - z, z - z1_), 0.f);
  return std::sqrt(dx * dx + dy * dy + dz * dz) + boundary_min_;
}

}  // namespace contactlab
