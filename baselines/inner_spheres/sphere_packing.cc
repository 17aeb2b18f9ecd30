#include "baselines/inner_spheres/sphere_packing.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>

#include "util/binary_io.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr char kMagic[] = "CLSPHERE";
constexpr double kMaxCandidates = 1 << 21;

double BallVolume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

}  // namespace

double SpherePacking::SphereVolume() const {
  double v = 0;
  for (const double r : radii) v += BallVolume(r);
  return v;
}

double SpherePacking::Coverage() const { return body_volume > 0 ? SphereVolume() / body_volume : 0; }

SpherePacking BuildSpherePacking(const DistanceField& field, double body_volume, const SpherePackingOptions& options,
                                 const std::string& where) {
  if (options.max_spheres < 1) Fail(where, "needs at least one sphere");
  if (!(options.coverage >= 0 && options.coverage <= 1)) Fail(where, "coverage must be in [0, 1]");
  if (!(body_volume > 0)) Fail(where, "the body has no volume to fill");
  const Eigen::Vector3i dims = field.dims();
  const double h = field.spacing();
  const double min_radius = options.min_radius_cells * h;
  // A candidate centre: its free radius as last measured, its grid index, and how many spheres
  // it has been measured against.
  struct Candidate {
    double radius;
    std::int64_t index;
    std::int32_t measured;
    bool operator<(const Candidate& o) const {
      return radius < o.radius || (radius == o.radius && index > o.index);  // ties: lowest index first
    }
  };
  // Centres on every grid point up to kMaxCandidates of them; a finer field offers every
  // STRIDE-th point per axis (the radii still come from the field's own samples).
  const double points = double(dims.x()) * dims.y() * dims.z();
  const int stride = std::max(1, int(std::ceil(std::cbrt(points / kMaxCandidates))));
  std::vector<Candidate> start;
  for (int k = 0; k < dims.z(); k += stride) {
    for (int j = 0; j < dims.y(); j += stride) {
      for (int i = 0; i < dims.x(); i += stride) {
        const double d = field.value(i, j, k);
        if (-d >= min_radius) start.push_back({-d, field.Index(i, j, k), 0});
      }
    }
  }
  if (start.empty()) Fail(where, "the field has no grid point deeper than half a cell inside the body");
  std::priority_queue<Candidate> queue(std::less<Candidate>(), std::move(start));
  auto position = [&](std::int64_t index) {
    const std::int64_t nx = dims.x(), nxy = nx * dims.y();
    return field.GridPoint(int(index % nx), int((index / nx) % dims.y()), int(index / nxy));
  };
  SpherePacking p;
  p.body_volume = body_volume;
  double filled = 0;
  while (!queue.empty() && int(p.radii.size()) < options.max_spheres) {
    if (options.coverage > 0 && filled >= options.coverage * body_volume) break;
    Candidate c = queue.top();
    queue.pop();
    if (c.radius < min_radius) break;  // the largest free radius is below the floor
    const Eigen::Vector3d x = position(c.index);
    const std::int32_t placed = std::int32_t(p.radii.size());
    if (c.measured < placed) {
      for (std::int32_t s = c.measured; s < placed; ++s) {
        c.radius = std::min(c.radius, (x - p.centers[std::size_t(s)]).norm() - p.radii[std::size_t(s)]);
      }
      c.measured = placed;
      if (c.radius >= min_radius) queue.push(c);
      continue;
    }
    p.centers.push_back(x);
    p.radii.push_back(c.radius);
    filled += BallVolume(c.radius);
  }
  return p;
}

void SaveSpherePacking(const SpherePacking& packing, const std::filesystem::path& path) {
  BinaryWriter w;
  w.Put<double>(packing.body_volume);
  std::vector<double> xyz;
  xyz.reserve(3 * packing.centers.size());
  for (const Eigen::Vector3d& c : packing.centers) xyz.insert(xyz.end(), {c.x(), c.y(), c.z()});
  w.PutArray(xyz);
  w.PutArray(packing.radii);
  w.Save(path, kMagic, 1);
}

SpherePacking LoadSpherePacking(const std::filesystem::path& path) {
  BinaryReader r(path, kMagic, 1);
  SpherePacking p;
  p.body_volume = r.Get<double>("body volume");
  const std::vector<double> xyz = r.GetArray<double>("centres");
  p.radii = r.GetArray<double>("radii", xyz.size() / 3);
  if (xyz.size() != 3 * p.radii.size()) Fail(path.string(), "a sphere packing needs three coordinates per radius");
  for (std::size_t i = 0; i < p.radii.size(); ++i) p.centers.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  r.ExpectEnd();
  if (p.radii.size() != p.centers.size() || p.centers.empty() || !(p.body_volume > 0)) {
    Fail(path.string(), "a sphere packing needs as many radii as centres, at least one, and a volume");
  }
  for (std::size_t i = 0; i < p.radii.size(); ++i) {
    if (!(p.radii[i] > 0) || !p.centers[i].allFinite()) Fail(path.string(), "sphere " + std::to_string(i) + " is not valid");
  }
  return p;
}

}  // namespace contactlab
