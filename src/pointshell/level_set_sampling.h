// Points on an offset level set d(x) = delta of a distance field (Barbič & James 2008, sec.
// 2.2 and 2.4): checking that the level set is a closed surface inside the field box, the
// grid cells it crosses with an area estimate, Newton projection onto it, and random
// (area-weighted) sampling, used to seed particle repulsion and as the "random" pointshell.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "sdf/distance_field.h"

namespace contactlab {

// Default level-set offset of a pointshell: half a grid spacing of FIELD (metres), so the
// points sit just outside the zero level set, on a surface the trilinear field resolves.
double DefaultPointshellOffset(const DistanceField& field);

// Throws Error("WHERE: ...") unless the level set d = DELTA is a closed surface strictly
// inside FIELD's box: FIELD must be non-empty and have a zero crossing (min < 0 < max),
// DELTA must be finite, above the smallest sample (else the level set is empty) and below
// the smallest sample on the box boundary (else it reaches the box and is not closed).
void CheckLevelSetOffset(const DistanceField& field, double delta, const std::string& where);

// The grid cells whose eight corner samples bracket DELTA, with the cumulative area estimate
// used to sample them. A plane of unit normal n crosses a cube of side h with expected area
// h^2 / (|n_x| + |n_y| + |n_z|) (averaged over the plane's offset); n is the field gradient
// at the cell centre. The sum over cells estimates the level set's area.
struct LevelSetCells {
  double delta = 0;                  // metres
  std::vector<Eigen::Vector3i> cell;  // (#C) lower-corner grid indices
  std::vector<double> cumulative_area;  // (#C) sum of the area estimates of cells 0..c, m^2
  double area() const { return cumulative_area.empty() ? 0.0 : cumulative_area.back(); }
};

// Finds the crossing cells (parallel, deterministic order). Throws Error("WHERE: ...") as
// CheckLevelSetOffset does, or when no cell crosses DELTA.
LevelSetCells FindLevelSetCells(const DistanceField& field, double delta, const std::string& where);

// Moves P onto d = DELTA by Newton steps p -= (d(p) - delta) g / |g|^2 (at most MAX_STEPS),
// stopping when |d(p) - delta| <= TOLERANCE (metres). On success stores the gradient at the
// final P in GRADIENT (may be null) and returns true; returns false (P unspecified) when the
// gradient vanishes or the iteration does not converge. Never throws or allocates.
bool ProjectOntoLevelSet(const DistanceField& field, double delta, double tolerance, int max_steps,
                         Eigen::Vector3d* p, Eigen::Vector3d* gradient);

// Tolerance used for level-set projections: 1e-6 grid spacings.
inline double LevelSetTolerance(const DistanceField& field) { return 1e-6 * field.spacing(); }

// Draws COUNT random points on the level set: a cell chosen with probability proportional to
// its area estimate, a uniform point in it, projected by Newton steps; retried with the next
// draws of the same stream when the projection fails or leaves the cell's neighbourhood.
// Point i uses the stream RandomStream(SEED, FIRST_INDEX + i), so the result does not depend
// on thread count. Writes (COUNT) positions to OUT. Throws Error("WHERE: ...") when a point
// cannot be placed after many attempts (a degenerate field).
void SampleLevelSet(const DistanceField& field, const LevelSetCells& cells, std::uint64_t seed,
                    std::int64_t first_index, std::int64_t count, Eigen::Vector3d* out,
                    const std::string& where);

}  // namespace contactlab
