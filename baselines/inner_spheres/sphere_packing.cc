#include "baselines/inner_spheres/sphere_packing.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <queue>

#include "geometry/aabb.h"

#include "util/binary_io.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr char kMagic[] = "CLSPHERE";
constexpr double kMaxCandidates = 1 << 21;
// A stale candidate is re-measured against the newest spheres one by one up to this many, else
// through the cells.
constexpr std::int32_t kIncremental = 32;
// Protosphere: at most this many moves of a prototype; a move is cut in half when it does not
// grow the free radius, down to this fraction of a cell.
constexpr int kMaxMoves = 16;
constexpr double kMinStepCells = 0.02;

double BallVolume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

// The free radius of a point against the body (its field) and the placed spheres, which are
// binned on a uniform grid of cells: each sphere in every cell its ball meets. Scanning rings
// of cells outward from the point's cell stops once the ring is farther than the nearest
// obstacle found (a sphere's nearest point to the point lies in a cell that holds it).
class FreeSpace {
 public:
  FreeSpace(const DistanceField& field, double cell) : field_(field), cell_(cell) {
    const Aabb box = field.box();
    lo_ = box.min;
    for (int a = 0; a < 3; ++a) n_[a] = std::max(1, int(std::ceil((box.max[a] - lo_[a]) / cell_)) + 1);
    cells_.resize(std::size_t(n_[0]) * n_[1] * n_[2]);
  }

  void Add(const Eigen::Vector3d& c, double r) {
    const std::int32_t id = std::int32_t(centers_.size());
    centers_.push_back(c);
    radii_.push_back(r);
    const Eigen::Vector3i a = CellOf(c - Eigen::Vector3d::Constant(r)), b = CellOf(c + Eigen::Vector3d::Constant(r));
    for (int k = a.z(); k <= b.z(); ++k) {
      for (int j = a.y(); j <= b.y(); ++j) {
        for (int i = a.x(); i <= b.x(); ++i) {
          // The cell's point nearest the centre: the ball meets the cell when it is within r.
          const Eigen::Vector3d cmin = lo_ + cell_ * Eigen::Vector3d(i, j, k);
          const Eigen::Vector3d q = c.cwiseMax(cmin).cwiseMin(cmin + Eigen::Vector3d::Constant(cell_));
          if ((q - c).squaredNorm() <= r * r) cells_[Cell(i, j, k)].push_back(id);
        }
      }
    }
  }

  std::int32_t size() const { return std::int32_t(centers_.size()); }
  const Eigen::Vector3d& center(std::int32_t s) const { return centers_[std::size_t(s)]; }
  double radius(std::int32_t s) const { return radii_[std::size_t(s)]; }

  // The free radius at X (negative inside a sphere or outside the body). AWAY (optional): the
  // sum of the unit directions away from every obstacle within SLACK of the nearest one, the
  // direction a Protosphere prototype moves.
  double FreeRadius(const Eigen::Vector3d& x, double slack = 0, Eigen::Vector3d* away = nullptr) {
    if (!field_.Inside(x)) return -1;
    Eigen::Vector3d g;
    double best = -field_.DistanceAndGradient(x, &g);
    near_.clear();
    if (away && g.squaredNorm() > 0) near_.push_back({best, -g.normalized()});
    if (best <= 0) return best;
    const Eigen::Vector3i c = CellOf(x);
    const int max_ring = std::max({n_[0], n_[1], n_[2]});
    for (int ring = 0; ring <= max_ring; ++ring) {
      for (int k = c.z() - ring; k <= c.z() + ring; ++k) {
        if (k < 0 || k >= n_[2]) continue;
        for (int j = c.y() - ring; j <= c.y() + ring; ++j) {
          if (j < 0 || j >= n_[1]) continue;
          const bool face = std::abs(k - c.z()) == ring || std::abs(j - c.y()) == ring;
          for (int i = c.x() - ring; i <= c.x() + ring; i += (face ? 1 : std::max(1, 2 * ring))) {
            if (i < 0 || i >= n_[0]) continue;
            for (const std::int32_t s : cells_[Cell(i, j, k)]) {
              const Eigen::Vector3d v = x - centers_[std::size_t(s)];
              const double len = v.norm();
              const double d = len - radii_[std::size_t(s)];
              if (d < best) best = d;
              if (away && d <= best + slack && len > 0) near_.push_back({d, v / len});
            }
          }
        }
      }
      if (best <= 0 && !away) return best;
      if (ring * cell_ >= best + slack) break;
    }
    if (away) {
      away->setZero();
      for (const Near& o : near_) {
        if (o.distance <= best + slack) *away += o.away;
      }
    }
    return best;
  }

 private:
  struct Near {
    double distance;
    Eigen::Vector3d away;
  };
  Eigen::Vector3i CellOf(const Eigen::Vector3d& p) const {
    Eigen::Vector3i c;
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(int(std::floor((p[a] - lo_[a]) / cell_)), 0, n_[a] - 1);
    return c;
  }
  std::size_t Cell(int i, int j, int k) const { return std::size_t(i) + std::size_t(n_[0]) * (j + std::size_t(n_[1]) * k); }

  const DistanceField& field_;
  double cell_;
  Eigen::Vector3d lo_;
  int n_[3];
  std::vector<std::vector<std::int32_t>> cells_;  // (cells) the spheres each cell meets
  std::vector<Eigen::Vector3d> centers_;
  std::vector<double> radii_;
  std::vector<Near> near_;  // scratch of FreeRadius
};

// The 14 unit directions to a cube's faces and corners: where a placed sphere seeds.
std::vector<Eigen::Vector3d> SeedDirections() {
  std::vector<Eigen::Vector3d> d;
  for (int k = -1; k <= 1; ++k) {
    for (int j = -1; j <= 1; ++j) {
      for (int i = -1; i <= 1; ++i) {
        const int nonzero = (i != 0) + (j != 0) + (k != 0);
        if (nonzero == 1 || nonzero == 3) d.push_back(Eigen::Vector3d(i, j, k).normalized());
      }
    }
  }
  return d;
}

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
  if (!(options.min_radius_cells > 0)) Fail(where, "the smallest sphere must have a positive radius");
  const Eigen::Vector3i dims = field.dims();
  const double h = field.spacing();
  const double min_radius = options.min_radius_cells * h;
  // A candidate centre: its free radius as last measured, its position, how many spheres it
  // has been measured against, and its number (ties: the lowest first, so the packing does not
  // depend on the queue's order).
  struct Candidate {
    double radius;
    float x, y, z;
    std::int32_t measured;
    std::int64_t id;
    bool operator<(const Candidate& o) const { return radius < o.radius || (radius == o.radius && id > o.id); }
    Eigen::Vector3d position() const { return {x, y, z}; }
  };
  // The first candidates: every grid point up to kMaxCandidates of them; a finer field offers
  // every STRIDE-th point per axis (the radii still come from the field's own samples).
  const double points = double(dims.x()) * dims.y() * dims.z();
  const int stride = std::max(1, int(std::ceil(std::cbrt(points / kMaxCandidates))));
  std::vector<Candidate> start;
  std::int64_t next_id = 0;
  for (int k = 0; k < dims.z(); k += stride) {
    for (int j = 0; j < dims.y(); j += stride) {
      for (int i = 0; i < dims.x(); i += stride) {
        const double d = field.value(i, j, k);
        const Eigen::Vector3d p = field.GridPoint(i, j, k);
        if (-d >= min_radius) start.push_back({-d, float(p.x()), float(p.y()), float(p.z()), 0, next_id});
        ++next_id;
      }
    }
  }
  if (start.empty()) Fail(where, "the field has no grid point deeper than the smallest sphere inside the body");
  std::priority_queue<Candidate> queue(std::less<Candidate>(), std::move(start));
  FreeSpace space(field, h * stride);
  const std::vector<Eigen::Vector3d> seeds = SeedDirections();
  SpherePacking p;
  p.body_volume = body_volume;
  double filled = 0;
  while (!queue.empty() && int(p.radii.size()) < options.max_spheres) {
    if (options.coverage > 0 && filled >= options.coverage * body_volume) break;
    Candidate c = queue.top();
    queue.pop();
    if (c.radius < min_radius) break;  // the largest free radius is below the floor
    Eigen::Vector3d x = c.position();
    const std::int32_t placed = space.size();
    // A stale candidate: measure it again and put it back.
    if (c.measured < placed) {
      if (placed - c.measured <= kIncremental) {
        for (std::int32_t s = c.measured; s < placed; ++s) {
          c.radius = std::min(c.radius, (x - space.center(s)).norm() - space.radius(s));
        }
      } else {
        c.radius = space.FreeRadius(x);
      }
      c.measured = placed;
      if (c.radius >= min_radius) queue.push(c);
      continue;
    }
    // The largest free radius: as a prototype, move it away from its nearest obstacles while
    // its free radius grows (Protosphere), then place its sphere.
    double r = c.radius;
    if (options.protosphere) {
      double step = 0.5 * r;
      Eigen::Vector3d away;
      space.FreeRadius(x, 0.5 * step, &away);
      for (int move = 0; move < kMaxMoves && step >= kMinStepCells * h; ++move) {
        if (away.squaredNorm() < 1e-12) break;  // balanced between its obstacles
        const Eigen::Vector3d y = x + step * away.normalized();
        Eigen::Vector3d away_y;
        const double ry = space.FreeRadius(y, 0.5 * step, &away_y);
        if (ry > r) {
          x = y;
          r = ry;
          away = away_y;
        } else {
          step *= 0.5;
        }
      }
    }
    space.Add(x, r);
    p.centers.push_back(x);
    p.radii.push_back(r);
    filled += BallVolume(r);
    if (!options.protosphere) continue;
    // Seeds just outside the new sphere: the voids next to it get candidates of their own.
    const double gap = std::max(min_radius, 0.25 * r);
    for (const Eigen::Vector3d& d : seeds) {
      const Eigen::Vector3d y = (x + (r + gap) * d).cast<float>().cast<double>();  // as the queue holds it
      const double ry = space.FreeRadius(y);
      if (ry >= min_radius) queue.push({ry, float(y.x()), float(y.y()), float(y.z()), space.size(), next_id++});
    }
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
