// Per-level sampling quality of a pointshell (Barbič & James 2008, sec. 2.2 and 2.4).
#include "pointshell/pointshell_quality.h"

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "pointshell/level_set_sampling.h"
#include "pointshell/nearest_point_index.h"

namespace contactlab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kDegrees = 180.0 / 3.14159265358979323846;

nlohmann::json Number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

}  // namespace

PointshellQuality AssessPointshell(const Pointshell& s, const DistanceField* field, const QualityOptions& options) {
  PointshellQuality q;
  q.method = s.method;
  q.source = s.source;
  q.offset = s.offset;
  q.field_spacing = field ? field->spacing() : kNaN;
  q.area = kNaN;
  const std::int32_t np = s.num_points();

  // Per-point field measures (deepest level holds every point; levels are prefixes).
  std::vector<double> normal_error(np, kNaN), level_distance(np, kNaN);
  std::vector<Eigen::Vector3d> samples;
  if (field) {
    tbb::parallel_for(std::int32_t(0), np, [&](std::int32_t i) {
      Eigen::Vector3d g;
      const double d = field->DistanceAndGradient(Eigen::Vector3d(s.x[i], s.y[i], s.z[i]), &g);
      level_distance[i] = std::abs(d - s.offset);
      const Eigen::Vector3d n(s.nx[i], s.ny[i], s.nz[i]);
      normal_error[i] = std::atan2(g.cross(n).norm(), -g.dot(n)) * kDegrees;  // accurate near 0
    });
    const LevelSetCells cells = FindLevelSetCells(*field, s.offset, "quality of pointshell of " + s.source);
    q.area = cells.area();
    q.coverage_samples = options.coverage_samples;
    samples.resize(options.coverage_samples);
    SampleLevelSet(*field, cells, options.seed, 0, options.coverage_samples, samples.data(),
                   "quality of pointshell of " + s.source);
  }

  for (int level = 0; level < s.num_levels(); ++level) {
    PointshellLevelQuality lq;
    lq.level = level;
    const std::int32_t n = s.level_point_end[level];
    lq.points = n;
    const NearestPointIndex index(s.x.data(), s.y.data(), s.z.data(), n);
    // Nearest-neighbour spacing within the level.
    std::vector<double> nn(n, 0.0);
    if (n >= 2) {
      tbb::parallel_for(std::int32_t(0), n, [&](std::int32_t i) {
        const float p[3] = {s.x[i], s.y[i], s.z[i]};
        std::int32_t idx[2];
        float d2[2];
        const int found = index.Nearest(p, 2, idx, d2);
        // The first hit is the point itself (or a coincident twin: then distance 0 either way).
        nn[i] = found == 2 ? std::sqrt(double(d2[1])) : 0.0;
      });
      double sum = 0, sum2 = 0;
      lq.spacing_min = INFINITY;
      for (double d : nn) {
        sum += d;
        lq.spacing_min = std::min(lq.spacing_min, d);
        lq.spacing_max = std::max(lq.spacing_max, d);
      }
      lq.spacing_mean = sum / n;
      for (double d : nn) sum2 += (d - lq.spacing_mean) * (d - lq.spacing_mean);
      lq.spacing_cv = lq.spacing_mean > 0 ? std::sqrt(sum2 / n) / lq.spacing_mean : kNaN;
    } else {
      lq.spacing_mean = lq.spacing_cv = lq.spacing_min = lq.spacing_max = kNaN;
    }
    lq.spacing_to_voxel = lq.spacing_mean / q.field_spacing;
    // Covering radius from the dense samples.
    if (field && !samples.empty()) {
      std::vector<double> cover(samples.size());
      tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t k) {
        const float p[3] = {float(samples[k].x()), float(samples[k].y()), float(samples[k].z())};
        std::int32_t idx;
        float d2;
        index.Nearest(p, 1, &idx, &d2);
        cover[k] = std::sqrt(double(d2));
      });
      double sum = 0;
      lq.covering_radius = 0;
      for (double c : cover) {
        sum += c;
        lq.covering_radius = std::max(lq.covering_radius, c);
      }
      lq.covering_mean = sum / cover.size();
      double emax = 0, esum = 0, dmax = 0;
      for (std::int32_t i = 0; i < n; ++i) {
        emax = std::max(emax, normal_error[i]);
        esum += normal_error[i];
        dmax = std::max(dmax, level_distance[i]);
      }
      lq.normal_error_max_deg = emax;
      lq.normal_error_mean_deg = esum / n;
      lq.level_set_distance_max = dmax;
    } else {
      lq.covering_radius = lq.covering_mean = kNaN;
      lq.normal_error_max_deg = lq.normal_error_mean_deg = lq.level_set_distance_max = kNaN;
    }
    // Largest bounding radius of the level.
    for (std::int32_t node = s.level_node_begin[level]; node < s.level_node_begin[level + 1]; ++node) {
      lq.radius_max = std::max(lq.radius_max, double(s.node_radius[node]));
    }
    q.levels.push_back(lq);
  }
  return q;
}

std::string QualityToText(const PointshellQuality& q) {
  std::ostringstream out;
  out << "pointshell quality: method " << q.method << ", source " << (q.source.empty() ? "-" : q.source)
      << ", offset " << q.offset << " m";
  if (std::isfinite(q.field_spacing)) out << ", field spacing " << q.field_spacing << " m";
  if (std::isfinite(q.area)) out << ", level-set area " << q.area << " m^2";
  if (q.coverage_samples > 0) out << ", covering radius from " << q.coverage_samples << " samples";
  out << "\n";
  char line[512];
  std::snprintf(line, sizeof line, "%5s %9s %11s %7s %11s %11s %11s %11s %10s %10s %11s %11s\n", "level",
                "points", "spacing_m", "cv", "min_m", "max_m", "cover_max_m", "cover_mean", "nrm_max°",
                "spc/voxel", "|d-off|max", "radius_max");
  out << line;
  for (const auto& l : q.levels) {
    std::snprintf(line, sizeof line,
                  "%5d %9d %11.4g %7.4f %11.4g %11.4g %11.4g %11.4g %10.3g %10.3g %11.3g %11.4g\n", l.level,
                  l.points, l.spacing_mean, l.spacing_cv, l.spacing_min, l.spacing_max, l.covering_radius,
                  l.covering_mean, l.normal_error_max_deg, l.spacing_to_voxel, l.level_set_distance_max,
                  l.radius_max);
    out << line;
  }
  return out.str();
}

nlohmann::json QualityToJson(const PointshellQuality& q) {
  nlohmann::json j;
  j["method"] = q.method;
  j["source"] = q.source;
  j["offset_m"] = q.offset;
  j["field_spacing_m"] = Number(q.field_spacing);
  j["area_m2"] = Number(q.area);
  j["coverage_samples"] = q.coverage_samples;
  j["levels"] = nlohmann::json::array();
  for (const auto& l : q.levels) {
    j["levels"].push_back({{"level", l.level},
                           {"points", l.points},
                           {"spacing_mean_m", Number(l.spacing_mean)},
                           {"spacing_cv", Number(l.spacing_cv)},
                           {"spacing_min_m", Number(l.spacing_min)},
                           {"spacing_max_m", Number(l.spacing_max)},
                           {"spacing_to_voxel", Number(l.spacing_to_voxel)},
                           {"covering_radius_m", Number(l.covering_radius)},
                           {"covering_mean_m", Number(l.covering_mean)},
                           {"normal_error_max_deg", Number(l.normal_error_max_deg)},
                           {"normal_error_mean_deg", Number(l.normal_error_mean_deg)},
                           {"level_set_distance_max_m", Number(l.level_set_distance_max)},
                           {"radius_max_m", Number(l.radius_max)}});
  }
  return j;
}

}  // namespace contactlab
