// Which pointshell points the viewer draws. A pointshell's points are sorted by repulsion
// level (Barbič & James 2008, sec. 2.4: level i adds the points that tree level i holds beyond
// level i-1), so a point's level is the first level whose prefix holds it. Large shells are
// thinned for display, level by level, so every level stays visible.
#pragma once

#include <cstdint>
#include <vector>

#include "pointshell/pointshell.h"

namespace contactlab {

struct DisplayPoints {
  std::vector<float> xyz;              // (#kept x 3) positions, body frame, metres
  std::vector<std::uint8_t> level;     // (#kept) repulsion level of each kept point
  std::vector<std::int32_t> index;     // (#kept) each kept point's index in the shell
  std::vector<std::int32_t> kept;      // (#levels) points kept per level
  std::vector<std::int32_t> total;     // (#levels) points of each level in the shell
  int num_kept() const { return static_cast<int>(level.size()); }
};

// Points added by each level: level_point_end[i] - level_point_end[i-1].
std::vector<std::int32_t> PointsPerLevel(const Pointshell& shell);

// Splits MAX_POINTS over levels holding COUNTS points each: a level with no more than its fair
// share keeps everything, what it leaves goes to the others in equal parts (max-min fair); a
// non-empty level keeps at least one point. Sum <= MAX_POINTS. Throws Error when MAX_POINTS is
// smaller than the number of non-empty levels.
std::vector<std::int32_t> DisplayBudget(const std::vector<std::int32_t>& counts, int max_points);

// The points of SHELL to draw: all of them when there are at most MAX_POINTS, else
// DisplayBudget(PointsPerLevel(SHELL), MAX_POINTS) per level, evenly spaced in each level's
// run of points (every k-th, k fractional). Throws Error as DisplayBudget.
DisplayPoints DecimatePointshell(const Pointshell& shell, int max_points);

}  // namespace contactlab
