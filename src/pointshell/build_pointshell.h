// Building nested multiresolution pointshells (Barbič & James 2008, sec. 2.2 and 2.4): the
// paper's particle repulsion on an offset level set, and three alternatives with the same data
// type for comparison (VPS-style voxel centres, mesh vertices, uniform random samples).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "geometry/triangle_mesh.h"
#include "pointshell/particle_repulsion.h"
#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab {

enum class PointshellMethod { kRepulsion, kVoxel, kVertices, kRandom };

struct PointshellOptions {
  PointshellMethod method = PointshellMethod::kRepulsion;
  std::int32_t num_points = 4096;  // points of the deepest level (repulsion, random, vertices)
  int num_levels = 4;              // tree levels
  int branching = 4;               // growth of the cumulative point count per level
  // Level-set offset delta (metres); unset: DefaultPointshellOffset = 0.5 field spacings.
  std::optional<double> offset;
  std::uint64_t seed = 1;
  RepulsionOptions repulsion;
  // Voxel method: voxel side (metres); <= 0 picks it so about num_points voxels are crossed
  // (side = sqrt(1.5 * area / num_points)).
  double voxel_size = 0;
  bool show_progress = true;  // progress on a terminal (util/progress.h)
};

// Per-level record of a repulsion build.
struct PointshellBuildReport {
  std::vector<RepulsionLevelStats> levels;  // repulsion only
  double area = 0;                          // estimated level-set area, m^2
  double seconds = 0;                       // wall time of the whole build
};

// Cumulative point counts of NUM_LEVELS nested levels ending at NUM_POINTS:
// end[i] = floor(NUM_POINTS / BRANCHING^(NUM_LEVELS-1-i)), strictly increasing. Throws
// Error("WHERE: ...") for NUM_POINTS < 1, NUM_LEVELS < 1, BRANCHING < 2, or when level 0
// would be empty (NUM_POINTS < BRANCHING^(NUM_LEVELS-1)).
std::vector<std::int32_t> NestedLevelEnds(std::int32_t num_points, int num_levels, int branching,
                                          const std::string& where);

// Builds a pointshell of FIELD's level set d = delta: positions (float, body frame = field
// frame, metres) sorted by level, inward unit normals -grad d / |grad d| at each point, the
// nested tree (point_tree.h), method, source (FIELD's info().source), offset and seed.
//  - repulsion: level 0 gets end[0] random level-set points, relaxed by repulsion; each next
//    level injects end[i] - end[i-1] random points and relaxes only them (earlier levels
//    frozen but pushing), with kernel width and strength proportional to sqrt(area / end[i]).
//  - voxel: centres of the voxels (side voxel_size) whose corners bracket delta (VPS); not on
//    the level set. num_points is ignored: every crossed voxel gives one point.
//  - vertices: the vertices of MESH used by triangles (duplicates removed), projected onto the
//    level set; a random subset of num_points if there are more.
//  - random: uniform random samples on the level set (area-weighted cells, projected).
// Levels of the non-repulsion methods are nested random subsets (a seeded shuffle), with the
// same cumulative counts as NestedLevelEnds of the total. Deterministic for a given seed,
// independent of the thread count. REPORT (may be null) receives timings and per-level stats.
// Throws Error naming the field's source for: bad counts (NestedLevelEnds), an offset the
// field cannot represent or a field with no zero crossing (CheckLevelSetOffset), the
// vertices method without MESH, or a vanishing gradient at a point.
Pointshell BuildPointshell(const DistanceField& field, const PointshellOptions& options,
                           const TriangleMesh* mesh = nullptr, PointshellBuildReport* report = nullptr);

// The version of what BuildPointshell produces. Raise it with any change that alters the output for
// the same inputs: cached results (scene/scene_assets.h) of an older version are then no
// longer found.
inline constexpr int kPointshellBuilderVersion = 1;

// "repulsion" | "voxel" | "vertices" | "random"; Parse throws Error naming WHERE.
PointshellMethod ParsePointshellMethod(const std::string& text, const std::string& where);
std::string PointshellMethodName(PointshellMethod method);

}  // namespace contactlab
