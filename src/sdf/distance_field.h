// A signed distance field on a dense, uniform float grid (Barbič & James 2008, sec. 2.3).
// Negative inside the object. Trilinear interpolation inside the grid box; outside it the
// conservative bound d(p) >= d_box(p) + d_boundary_min of the paper's Fig. 5(c). A field is
// either dense (every grid sample stored) or sparse (a narrow band of fine samples over a coarse
// field, sdf/sparse_field.h); both answer every query below.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
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

struct SparseFieldStorage;
float SparseLookup(const SparseFieldStorage& s, float gx, float gy, float gz);
float SparseSample(const SparseFieldStorage& s, int i, int j, int k);

class DistanceField {
 public:
  DistanceField() = default;
  // Grid point (i, j, k) sits at ORIGIN + SPACING * (i, j, k); VALUES holds
  // DIMS.x * DIMS.y * DIMS.z samples, x fastest. Every dimension must be >= 2.
  // Throws Error when sizes disagree or a value is not finite.
  DistanceField(const Eigen::Vector3d& origin, double spacing, const Eigen::Vector3i& dims,
                std::vector<float> values, DistanceFieldInfo info = {});
  // A sparse field (sdf/sparse_field.h): the fine grid has 8 STORAGE.bricks + 1 points per
  // axis. Throws Error when STORAGE is inconsistent (SparseFieldStorage::Validate).
  DistanceField(const Eigen::Vector3d& origin, double spacing, SparseFieldStorage storage,
                DistanceFieldInfo info = {});

  const Eigen::Vector3d& origin() const { return origin_; }
  double spacing() const { return spacing_; }
  const Eigen::Vector3i& dims() const { return dims_; }  // grid points per axis
  // Every sample, x fastest; empty for a sparse field (use value()).
  const std::vector<float>& values() const { return values_; }
  // The sparse storage, or null for a dense field.
  const SparseFieldStorage* sparse() const { return sparse_.get(); }
  const DistanceFieldInfo& info() const { return info_; }
  DistanceFieldInfo& mutable_info() { return info_; }
  bool empty() const { return values_.empty() && !sparse_; }
  // Grid points (stored or not).
  std::int64_t num_samples() const {
    return empty() ? 0 : std::int64_t(dims_.x()) * dims_.y() * dims_.z();
  }
  // Bytes the samples occupy (dense: 4 a grid point; sparse: coarse grid, slots and bricks).
  std::int64_t memory_bytes() const;
  // Box spanned by the grid points.
  Aabb box() const;
  // Smallest sample on the grid's boundary faces (the paper's d_boundary).
  float boundary_min() const { return boundary_min_; }
  float min_value() const { return min_value_; }
  float max_value() const { return max_value_; }
  std::int64_t Index(int i, int j, int k) const {
    return i + std::int64_t(dims_.x()) * (j + std::int64_t(dims_.y()) * k);
  }
  float value(int i, int j, int k) const {
    return sparse_ ? SparseSample(*sparse_, i, j, k) : values_[Index(i, j, k)];
  }
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
  // VALUES is null for a sparse field, whose lookups go through SPARSE.
  struct FloatGrid {
    const float* values;
    const SparseFieldStorage* sparse;
    int nx, ny, nz;
    float ox, oy, oz, inv_h, ex, ey, ez, x1, y1, z1, boundary_min;
  };
  FloatGrid float_grid() const {
    return {sparse_ ? nullptr : values_.data(), sparse_.get(), dims_.x(), dims_.y(), dims_.z(), ox_, oy_, oz_, inv_h_, ex_, ey_, ez_,
            x1_, y1_, z1_, boundary_min_};
  }

  // True when P lies inside the grid box.
  bool Inside(const Eigen::Vector3d& p) const;

 private:
  // The float copies of origin, spacing and box the hot paths read.
  void SetHotPathConstants();
  // The conservative bound outside the box: distance to the box + boundary_min.
  inline float OutsideBound(float x, float y, float z) const;

  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  double spacing_ = 1;
  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  std::vector<float> values_;
  std::shared_ptr<const SparseFieldStorage> sparse_;
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
  if (sparse_) return SparseLookup(*sparse_, gx, gy, gz);
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
  if (empty() || !(std::abs(x) + std::abs(y) + std::abs(z) < std::numeric_limits<float>::infinity())) {
    return std::numeric_limits<float>::infinity();
  }
  const float dx = std::max(std::max(ox_ - x, x - x1_), 0.f);
  const float dy = std::max(std::max(oy_ - y, y - y1_), 0.f);
  const float dz = std::max(std::max(oz_ - z, z - z1_), 0.f);
  return std::sqrt(dx * dx + dy * dy + dz * dz) + boundary_min_;
}

}  // namespace contactlab
