#include "sdf/distance_field.h"

#include <limits>

#include "sdf/sparse_field.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Smallest sample on the boundary faces of a grid of DIMS points (x fastest).
float BoundaryMinimum(const std::vector<float>& values, const Eigen::Vector3i& dims) {
  float m = std::numeric_limits<float>::infinity();
  auto at = [&](int i, int j, int k) { return values[i + std::int64_t(dims.x()) * (j + std::int64_t(dims.y()) * k)]; };
  for (int k = 0; k < dims.z(); ++k) {
    for (int j = 0; j < dims.y(); ++j) {
      const bool face = (k == 0 || k == dims.z() - 1 || j == 0 || j == dims.y() - 1);
      for (int i = 0; i < dims.x(); i += (face ? 1 : dims.x() - 1)) m = std::min(m, at(i, j, k));
    }
  }
  return m;
}

}  // namespace

DistanceField::DistanceField(const Eigen::Vector3d& origin, double spacing, const Eigen::Vector3i& dims,
                             std::vector<float> values, DistanceFieldInfo info)
    : origin_(origin), spacing_(spacing), dims_(dims), values_(std::move(values)), info_(std::move(info)) {
  const std::string where = "distance field" + (info_.source.empty() ? "" : " of " + info_.source);
  if (!(spacing > 0) || !std::isfinite(spacing)) Fail(where, "spacing must be positive and finite");
  if ((dims.array() < 2).any()) Fail(where, "every grid dimension must be at least 2");
  if (!origin.allFinite()) Fail(where, "origin is not finite");
  const std::int64_t n = std::int64_t(dims.x()) * dims.y() * dims.z();
  if (n >= (std::int64_t(1) << 31)) {  // 32-bit sample indices in the vectorised lookups
    Fail(where, "has " + std::to_string(n) + " samples, more than 2^31 - 1");
  }
  if (std::int64_t(values_.size()) != n) {
    Fail(where, "holds " + std::to_string(values_.size()) + " samples, dimensions need " + std::to_string(n));
  }
  min_value_ = std::numeric_limits<float>::infinity();
  max_value_ = -min_value_;
  for (float v : values_) {
    if (!std::isfinite(v)) Fail(where, "a sample is not finite");
    min_value_ = std::min(min_value_, v);
    max_value_ = std::max(max_value_, v);
  }
  boundary_min_ = BoundaryMinimum(values_, dims);
  SetHotPathConstants();
}

DistanceField::DistanceField(const Eigen::Vector3d& origin, double spacing, SparseFieldStorage storage,
                             DistanceFieldInfo info)
    : origin_(origin), spacing_(spacing), info_(std::move(info)) {
  const std::string where = "sparse distance field" + (info_.source.empty() ? "" : " of " + info_.source);
  if (!(spacing > 0) || !std::isfinite(spacing)) Fail(where, "spacing must be positive and finite");
  if (!origin.allFinite()) Fail(where, "origin is not finite");
  storage.Validate(where);
  dims_ = SparseFieldStorage::kBrick * storage.bricks + Eigen::Vector3i::Ones();
  if (std::int64_t(dims_.x()) * dims_.y() * dims_.z() >= (std::int64_t(1) << 31)) {
    Fail(where, "has more than 2^31 - 1 grid points");
  }
  min_value_ = std::numeric_limits<float>::infinity();
  max_value_ = -min_value_;
  for (float v : storage.coarse) {
    min_value_ = std::min(min_value_, v);
    max_value_ = std::max(max_value_, v);
  }
  for (std::int16_t q : storage.samples) {
    min_value_ = std::min(min_value_, q * storage.quantum);
    max_value_ = std::max(max_value_, q * storage.quantum);
  }
  // The grid box is the coarse grid's, whose boundary samples bound the distance on its faces.
  boundary_min_ = BoundaryMinimum(storage.coarse, storage.bricks + Eigen::Vector3i::Ones());
  storage.SetSpacing(spacing);
  sparse_ = std::make_shared<const SparseFieldStorage>(std::move(storage));
  SetHotPathConstants();
}

std::int64_t DistanceField::memory_bytes() const {
  return sparse_ ? sparse_->memory_bytes() : std::int64_t(values_.size() * sizeof(float));
}

void DistanceField::SetHotPathConstants() {
  ox_ = float(origin_.x());
  oy_ = float(origin_.y());
  oz_ = float(origin_.z());
  inv_h_ = float(1.0 / spacing_);
  ex_ = float(dims_.x() - 1);
  ey_ = float(dims_.y() - 1);
  ez_ = float(dims_.z() - 1);
  const Eigen::Vector3d upper = box().max;
  x1_ = float(upper.x());
  y1_ = float(upper.y());
  z1_ = float(upper.z());
}

Aabb DistanceField::box() const {
  Aabb b;
  b.min = origin_;
  b.max = origin_ + spacing_ * (dims_ - Eigen::Vector3i::Ones()).cast<double>();
  return b;
}

bool DistanceField::Inside(const Eigen::Vector3d& p) const { return box().Contains(p); }

double DistanceField::DistanceAndGradient(const Eigen::Vector3d& p, Eigen::Vector3d* gradient) const {
  const Aabb b = box();
  if (!b.Contains(p)) {
    const Eigen::Vector3d q = p.cwiseMax(b.min).cwiseMin(b.max);
    const Eigen::Vector3d d = p - q;
    const double len = d.norm();
    if (gradient) *gradient = len > 0 ? Eigen::Vector3d(d / len) : Eigen::Vector3d::Zero();
    return len + boundary_min_;
  }
  const Eigen::Vector3d g = (p - origin_) / spacing_;
  if (sparse_) {
    const double value = sparse_->Lookup(g, gradient);
    if (gradient) *gradient /= spacing_;
    return value;
  }
  const int i = std::clamp(int(g.x()), 0, dims_.x() - 2);
  const int j = std::clamp(int(g.y()), 0, dims_.y() - 2);
  const int k = std::clamp(int(g.z()), 0, dims_.z() - 2);
  const double tx = g.x() - i, ty = g.y() - j, tz = g.z() - k;
  double c[2][2][2];
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) c[dx][dy][dz] = value(i + dx, j + dy, k + dz);
  auto lerp = [](double a, double b, double t) { return a + t * (b - a); };
  // Value.
  const double c00 = lerp(c[0][0][0], c[1][0][0], tx), c10 = lerp(c[0][1][0], c[1][1][0], tx);
  const double c01 = lerp(c[0][0][1], c[1][0][1], tx), c11 = lerp(c[0][1][1], c[1][1][1], tx);
  const double c0 = lerp(c00, c10, ty), c1 = lerp(c01, c11, ty);
  const double value = lerp(c0, c1, tz);
  if (gradient) {
    // Partial derivatives of the trilinear interpolant, per unit length.
    const double dx00 = c[1][0][0] - c[0][0][0], dx10 = c[1][1][0] - c[0][1][0];
    const double dx01 = c[1][0][1] - c[0][0][1], dx11 = c[1][1][1] - c[0][1][1];
    const double ddx = lerp(lerp(dx00, dx10, ty), lerp(dx01, dx11, ty), tz);
    const double ddy = lerp(c10 - c00, c11 - c01, tz);
    const double ddz = c1 - c0;
    *gradient = Eigen::Vector3d(ddx, ddy, ddz) / spacing_;
  }
  return value;
}

}  // namespace contactlab
