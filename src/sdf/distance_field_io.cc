// Distance-field files ("CLSDF"; version 1 dense, version 2 sparse) and summaries (Barbič & James 2008, sec. 2.3).
#include <cmath>
#include <cstdio>
#include <sstream>

#include "geometry/triangle_mesh.h"
#include "sdf/build_distance_field.h"
#include "sdf/sparse_field.h"
#include "util/binary_io.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr char kMagic[] = "CLSDF";
constexpr std::uint32_t kVersion = 2;  // 1: dense samples; 2: sparse storage (sdf/sparse_field.h)
constexpr int kMaxDim = 1 << 14;

// The info block that ends both layouts, then the end of the file.
DistanceFieldInfo ReadInfoToEnd(BinaryReader& r) {
  DistanceFieldInfo info;
  info.source = r.GetString("source");
  info.mode = r.GetString("mode");
  info.offset = r.Get<double>("offset");
  info.build_seconds = r.Get<double>("build time");
  r.ExpectEnd();
  return info;
}

}  // namespace

void SaveDistanceField(const DistanceField& field, const std::filesystem::path& path) {
  if (field.empty()) Fail(path.string(), "cannot save an empty distance field");
  BinaryWriter w;
  for (int a = 0; a < 3; ++a) w.Put<double>(field.origin()[a]);
  w.Put<double>(field.spacing());
  if (const SparseFieldStorage* s = field.sparse()) {
    for (int a = 0; a < 3; ++a) w.Put<std::int32_t>(s->bricks[a]);
    w.Put<std::int32_t>(s->band_voxels);
    w.Put<float>(s->quantum);
    w.PutArray(s->coarse);
    w.PutArray(s->slot);
    w.PutArray(s->samples);
  } else {
    for (int a = 0; a < 3; ++a) w.Put<std::int32_t>(field.dims()[a]);
    w.PutArray(field.values());
  }
  w.PutString(field.info().source);
  w.PutString(field.info().mode);
  w.Put<double>(field.info().offset);
  w.Put<double>(field.info().build_seconds);
  // Dense fields keep version 1, so files written before sparse storage existed stay current.
  w.Save(path, kMagic, field.sparse() ? 2 : 1);
}

DistanceField LoadDistanceField(const std::filesystem::path& path) {
  BinaryReader r(path, kMagic, kVersion);
  Eigen::Vector3d origin;
  for (int a = 0; a < 3; ++a) origin[a] = r.Get<double>("origin");
  const double spacing = r.Get<double>("spacing");
  const bool sparse = r.version() == 2;
  Eigen::Vector3i dims;
  for (int a = 0; a < 3; ++a) {
    if (sparse) {
      const std::int32_t bricks = r.Get<std::int32_t>("bricks");
      if (bricks < 1 || bricks > kMaxDim / SparseFieldStorage::kBrick) {
        r.Corrupt("brick count " + std::to_string(bricks) + " is outside [1, " +
                  std::to_string(kMaxDim / SparseFieldStorage::kBrick) + "]");
      }
      dims[a] = SparseFieldStorage::kBrick * bricks + 1;
    } else {
      dims[a] = r.Get<std::int32_t>("dimensions");
    }
    if (dims[a] < 2 || dims[a] > kMaxDim) {
      r.Corrupt("grid dimension " + std::to_string(dims[a]) + " is outside [2, " + std::to_string(kMaxDim) + "]");
    }
  }
  if (!origin.allFinite()) r.Corrupt("origin is not finite");
  if (!(spacing > 0) || !std::isfinite(spacing)) r.Corrupt("spacing must be positive and finite");
  // A checksum-valid file may still describe a grid too large to evaluate in doubles.
  const double extent = spacing * (dims.maxCoeff() - 1);
  if (!(origin.cwiseAbs().maxCoeff() <= kMaxCoordinate) || !(origin.cwiseAbs().maxCoeff() + extent <= kMaxCoordinate)) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "origin or spacing out of range: spacing %.3g m, grid reaching %.3g m (the limit is %.0e m)",
                  spacing, origin.cwiseAbs().maxCoeff() + extent, kMaxCoordinate);
    r.Corrupt(buf);
  }
  if (sparse) {
    SparseFieldStorage s;
    s.bricks = (dims - Eigen::Vector3i::Ones()) / SparseFieldStorage::kBrick;
    s.band_voxels = r.Get<std::int32_t>("band");
    s.quantum = r.Get<float>("quantum");
    const std::uint64_t nb = std::uint64_t(s.bricks.x()) * s.bricks.y() * s.bricks.z();
    s.coarse = r.GetArray<float>("coarse samples", std::uint64_t(s.bricks.x() + 1) * (s.bricks.y() + 1) * (s.bricks.z() + 1));
    s.slot = r.GetArray<std::int32_t>("brick slots", nb);
    s.samples = r.GetArray<std::int16_t>("brick samples", nb * SparseFieldStorage::kBrickStride);
    DistanceFieldInfo info = ReadInfoToEnd(r);
    try {
      return DistanceField(origin, spacing, std::move(s), std::move(info));
    } catch (const Error& e) {
      r.Corrupt(e.what());
    }
  }
  const std::uint64_t n = std::uint64_t(dims.x()) * dims.y() * dims.z();
  std::vector<float> values = r.GetArray<float>("samples", n);
  if (values.size() != n) {
    r.Corrupt("holds " + std::to_string(values.size()) + " samples, dimensions need " + std::to_string(n));
  }
  DistanceFieldInfo info = ReadInfoToEnd(r);
  try {
    return DistanceField(origin, spacing, dims, std::move(values), std::move(info));
  } catch (const Error& e) {
    r.Corrupt(e.what());
  }
}

std::string DescribeDistanceField(const DistanceField& field) {
  char buf[512];
  std::ostringstream out;
  const DistanceFieldInfo& info = field.info();
  out << "distance field of " << (info.source.empty() ? "(unnamed)" : info.source) << "\n";
  if (info.mode == "soup") {
    std::snprintf(buf, sizeof(buf),
                  "  mode: soup; the zero level set is the offset surface at distance %.6g m (%.3g voxels) "
                  "from the input soup\n",
                  info.offset, info.offset / field.spacing());
    out << buf;
  } else {
    out << "  mode: " << (info.mode.empty() ? "unknown" : info.mode) << "\n";
  }
  const Eigen::Vector3i& d = field.dims();
  if (const SparseFieldStorage* s = field.sparse()) {
    const std::int64_t bricks = std::int64_t(s->bricks.x()) * s->bricks.y() * s->bricks.z();
    std::snprintf(buf, sizeof(buf),
                  "  grid: %d x %d x %d points, spacing %.6g m, sparse: %lld of %lld bricks of 8^3 cells stored "
                  "(band %d voxels, 16-bit samples, step %.3g voxels), coarse field %d x %d x %d (%.1f MB)\n",
                  d.x(), d.y(), d.z(), field.spacing(), static_cast<long long>(s->num_stored()),
                  static_cast<long long>(bricks), s->band_voxels, s->quantum / field.spacing(), s->bricks.x() + 1,
                  s->bricks.y() + 1, s->bricks.z() + 1, field.memory_bytes() / double(1 << 20));
  } else {
    std::snprintf(buf, sizeof(buf), "  grid: %d x %d x %d points, spacing %.6g m, %lld samples (%.1f MB)\n", d.x(),
                  d.y(), d.z(), field.spacing(), static_cast<long long>(field.num_samples()),
                  field.memory_bytes() / double(1 << 20));
  }
  out << buf;
  const Aabb box = field.box();
  std::snprintf(buf, sizeof(buf), "  box: [%.6g, %.6g, %.6g] .. [%.6g, %.6g, %.6g] m\n", box.min.x(), box.min.y(),
                box.min.z(), box.max.x(), box.max.y(), box.max.z());
  out << buf;
  std::snprintf(buf, sizeof(buf), "  values: [%.6g, %.6g] m, boundary minimum %.6g m\n", field.min_value(),
                field.max_value(), field.boundary_min());
  out << buf;
  std::snprintf(buf, sizeof(buf), "  build time: %.3f s\n", info.build_seconds);
  out << buf;
  return out.str();
}

}  // namespace contactlab
