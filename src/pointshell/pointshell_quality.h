// Sampling-quality report of a nested pointshell, per tree level (Barbič & James 2008, sec.
// 2.2 and 2.4: near-uniform spacing, no gaps, normals orthogonal to the surface, resolution
// equal to or finer than the distance field's).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab {

struct PointshellLevelQuality {
  int level = 0;
  std::int32_t points = 0;
  // Nearest-neighbour distance within the level (metres): mean, coefficient of variation
  // (standard deviation / mean), min, max.
  double spacing_mean = 0, spacing_cv = 0, spacing_min = 0, spacing_max = 0;
  double spacing_to_voxel = 0;  // spacing_mean / field spacing (NaN without a field)
  // Largest and mean distance from dense random level-set samples to the nearest point of the
  // level (metres): an estimate (from below) of the covering radius. NaN without a field.
  double covering_radius = 0, covering_mean = 0;
  // Angle between the stored normal and -grad d / |grad d| at the point, degrees. NaN
  // without a field.
  double normal_error_max_deg = 0, normal_error_mean_deg = 0;
  // |d(p) - offset| over the level's points, metres. NaN without a field.
  double level_set_distance_max = 0;
  double radius_max = 0;  // largest bounding radius of the level's nodes, metres
};

struct PointshellQuality {
  std::string method, source;
  double offset = 0;
  double field_spacing = 0;     // metres, NaN without a field
  double area = 0;              // estimated level-set area, m^2 (NaN without a field)
  std::int32_t coverage_samples = 0;  // level-set samples used for the covering radius
  std::vector<PointshellLevelQuality> levels;
};

struct QualityOptions {
  std::int32_t coverage_samples = 100000;  // dense level-set samples for the covering radius
  std::uint64_t seed = 0x51ab1e;           // their random stream
};

// Measures SHELL level by level. FIELD (may be null) must be the field SHELL was built on;
// without it only counts, spacing and radii are reported (the rest NaN). Parallel,
// deterministic. Throws Error (as FindLevelSetCells) when the field cannot be sampled at
// SHELL's offset.
PointshellQuality AssessPointshell(const Pointshell& shell, const DistanceField* field,
                                   const QualityOptions& options = {});

// A table, one line per level.
std::string QualityToText(const PointshellQuality& quality);
// NaN values become null.
nlohmann::json QualityToJson(const PointshellQuality& quality);

}  // namespace contactlab
