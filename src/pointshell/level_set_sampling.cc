// Offset level sets of a distance field: checks, crossing cells, projection and random
// sampling (Barbič & James 2008, sec. 2.2 and 2.4).
#include "pointshell/level_set_sampling.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <sstream>

#include "pointshell/random_stream.h"
#include "util/error.h"

namespace contactlab {

double DefaultPointshellOffset(const DistanceField& field) { return 0.5 * field.spacing(); }

void CheckLevelSetOffset(const DistanceField& field, double delta, const std::string& where) {
  if (field.empty()) Fail(where, "the distance field is empty");
  std::ostringstream range;
  range << "[" << field.min_value() << ", " << field.max_value() << "]";
  if (!(field.min_value() < 0 && field.max_value() > 0)) {
    Fail(where, "the distance field has no zero crossing (values in " + range.str() +
                    "): it does not describe a surface");
  }
  if (!std::isfinite(delta)) Fail(where, "the level-set offset is not finite");
  if (!(delta > field.min_value())) {
    std::ostringstream s;
    s << "offset " << delta << " m is at or below the smallest field value " << field.min_value()
      << " m: the level set d = offset is empty";
    Fail(where, s.str());
  }
  if (!(delta < field.boundary_min())) {
    std::ostringstream s;
    s << "offset " << delta << " m is not below the smallest value on the field box boundary ("
      << field.boundary_min()
      << " m): the level set d = offset reaches the box and is not closed; use a smaller offset or "
         "a field with more padding";
    Fail(where, s.str());
  }
}

LevelSetCells FindLevelSetCells(const DistanceField& field, double delta, const std::string& where) {
  CheckLevelSetOffset(field, delta, where);
  const Eigen::Vector3i dims = field.dims();
  const int cx = dims.x() - 1, cy = dims.y() - 1, cz = dims.z() - 1;
  const double h = field.spacing();
  // Per z-slab lists (parallel), joined in slab order so the result is deterministic.
  std::vector<std::vector<Eigen::Vector3i>> slab_cells(cz);
  std::vector<std::vector<double>> slab_area(cz);
  tbb::parallel_for(0, cz, [&](int k) {
    for (int j = 0; j < cy; ++j) {
      for (int i = 0; i < cx; ++i) {
        float lo = field.value(i, j, k), hi = lo;
        for (int c = 1; c < 8; ++c) {
          const float v = field.value(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
          lo = std::min(lo, v);
          hi = std::max(hi, v);
        }
        if (!(lo <= delta && delta <= hi) || lo == hi) continue;
        Eigen::Vector3d g;
        field.DistanceAndGradient(field.GridPoint(i, j, k) + Eigen::Vector3d::Constant(0.5 * h), &g);
        const double gn = g.norm();
        double area = h * h;  // fallback for a vanishing gradient
        if (gn > 0) area = h * h / (g.cwiseAbs().sum() / gn);
        slab_cells[k].emplace_back(i, j, k);
        slab_area[k].push_back(area);
      }
    }
  });
  LevelSetCells cells;
  cells.delta = delta;
  double sum = 0;
  for (int k = 0; k < cz; ++k) {
    for (std::size_t c = 0; c < slab_cells[k].size(); ++c) {
      sum += slab_area[k][c];
      cells.cell.push_back(slab_cells[k][c]);
      cells.cumulative_area.push_back(sum);
    }
  }
  if (cells.cell.empty()) {
    std::ostringstream s;
    s << "no grid cell crosses the level set d = " << delta << " m";
    Fail(where, s.str());
  }
  return cells;
}

bool ProjectOntoLevelSet(const DistanceField& field, double delta, double tolerance, int max_steps,
                         Eigen::Vector3d* p, Eigen::Vector3d* gradient) {
  Eigen::Vector3d g;
  for (int step = 0; step <= max_steps; ++step) {
    const double d = field.DistanceAndGradient(*p, &g) - delta;
    if (!std::isfinite(d)) return false;
    if (std::abs(d) <= tolerance) {
      if (gradient) *gradient = g;
      return g.squaredNorm() > 0;
    }
    if (step == max_steps) break;
    const double g2 = g.squaredNorm();
    if (!(g2 > 1e-12)) return false;
    *p -= (d / g2) * g;
  }
  return false;
}

void SampleLevelSet(const DistanceField& field, const LevelSetCells& cells, std::uint64_t seed,
                    std::int64_t first_index, std::int64_t count, Eigen::Vector3d* out,
                    const std::string& where) {
  if (count <= 0) return;
  const double h = field.spacing();
  const double total = cells.area();
  const double tolerance = LevelSetTolerance(field);
  constexpr int kMaxAttempts = 256;
  std::atomic<bool> failed{false};
  tbb::parallel_for(std::int64_t(0), count, [&](std::int64_t i) {
    RandomStream rng(seed, std::uint64_t(first_index + i));
    for (int attempt = 0; attempt < kMaxAttempts; ++attempt) {
      // Cell by area, then a uniform point in it.
      const double u = rng.Uniform() * total;
      const auto it = std::upper_bound(cells.cumulative_area.begin(), cells.cumulative_area.end(), u);
      const std::size_t c = std::min<std::size_t>(it - cells.cumulative_area.begin(), cells.cell.size() - 1);
      const Eigen::Vector3d corner = field.GridPoint(cells.cell[c].x(), cells.cell[c].y(), cells.cell[c].z());
      const Eigen::Vector3d start = corner + h * Eigen::Vector3d(rng.Uniform(), rng.Uniform(), rng.Uniform());
      Eigen::Vector3d p = start;
      if (!ProjectOntoLevelSet(field, cells.delta, tolerance, 20, &p, nullptr)) continue;
      // Reject points that ran far from the cell (projection onto another sheet).
      if ((p - start).norm() > 2 * h) continue;
      out[i] = p;
      return;
    }
    failed = true;
    out[i] = Eigen::Vector3d::Constant(std::nan(""));
  });
  if (failed) Fail(where, "could not place random points on the level set (degenerate field?)");
}

}  // namespace contactlab
