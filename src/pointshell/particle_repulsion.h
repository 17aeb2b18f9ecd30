// Particle repulsion constrained to an offset level set of a distance field (Barbič & James
// 2008, sec. 2.4, after Witkin & Heckbert 1994 and Turk 1992): free points push each other
// (and are pushed by frozen points of coarser levels) with a compact kernel, move only
// tangentially, and are projected back onto the level set after every step.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "sdf/distance_field.h"
#include "util/progress.h"

namespace contactlab {

// Repulsion parameters, dimensionless: lengths are in units of the level's expected point
// spacing s = sqrt(area / n), n the points of the level (frozen + free). With branching
// factor 4, s halves per level, so the kernel width and the force strength in metres halve
// per level exactly as in the paper.
struct RepulsionOptions {
  double kernel_width = 2.0;  // sigma / s: points farther apart than sigma do not interact
  double strength = 0.25;     // displacement per unit force per iteration / s
  double max_step = 0.3;      // largest displacement of one point in one iteration / s
  double tolerance = 2e-3;    // converged when the mean displacement < tolerance * s
  int max_iterations = 250;   // per level
};

struct RepulsionLevelStats {
  std::int32_t frozen_points = 0;
  std::int32_t free_points = 0;
  double expected_spacing = 0;  // s, metres
  double kernel_width = 0;      // sigma, metres
  int iterations = 0;
  double last_mean_step = 0;    // mean displacement of the last iteration / s
  bool converged = false;
  double seconds = 0;
};

// Relaxes POSITIONS[FROZEN, #P) by repulsion; POSITIONS[0, FROZEN) stay fixed but push.
// Every position must lie on the level set d = DELTA (metres) of FIELD on entry; so do the
// free ones on exit. EXPECTED_SPACING is s in metres (> 0). Force of j on i:
// (1 - r/sigma)^3 (p_i - p_j)/r for r < sigma; step = strength * s * force, made tangential
// (the component along the field gradient removed), clamped to max_step * s, then projected
// back by Newton steps (a step whose projection fails is dropped). Jacobi iteration (new
// positions in a second buffer) with TBB: the result does not depend on the thread count.
// Stops when the mean displacement of the free points falls below tolerance * s, or after
// max_iterations. Advances PROGRESS (may be null) once per iteration, and by the unused
// iterations at convergence.
RepulsionLevelStats RepelOnLevelSet(const DistanceField& field, double delta, double expected_spacing,
                                    const RepulsionOptions& options, std::int32_t frozen,
                                    std::vector<Eigen::Vector3d>* positions, Progress* progress);

}  // namespace contactlab
