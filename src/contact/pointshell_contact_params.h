// Parameters of the paper's contact model (Barbič & James 2008, sec. 2.1, 3, 5), read from a
// scene's "model:" section. The scene holds this struct itself; the baselines take what they
// share with it (the penalty law, the coherence bound) from it.
#pragma once

#include "contact/contact_accumulator.h"
#include "contact/penalty_params.h"
#include "util/param_table.h"

namespace contactlab {

struct PointshellContactParams {
  PenaltyParams penalty;         // k_C and L (sec. 2.1)
  int level = -1;                // linear variant: tree level rendered (-1: deepest); tree: deepest level allowed
  bool coherence = false;        // tree variant: temporal coherence (sec. 3)
  double max_point_speed = 1.0;  // m/s, largest speed of any pointshell point relative to B
  double cycle_seconds = 1e-3;   // duration of one haptic cycle, seconds
  double lipschitz = 1.0;        // bound on |grad d| assumed by culling and coherence (paper: 1)
  double cold_fraction = 0.8;    // V_C = cold_fraction * V_W (sec. 3, graceful degradation)
  ContactGradient gradient = ContactGradient::kHalfspace;  // sec. 5 halfspace rule, or the field's gradient
  // The proxy of pointshell-ccd (baselines/pointshell_ccd): the coupling between its proxy and
  // B, how far from B's surface its points stop, and its constrained steps per cycle.
  double proxy_stiffness = 0;      // N/m; 0: k_C L (k_C when L = 0)
  double proxy_rot_stiffness = 0;  // N m/rad; 0: proxy_stiffness R_B^2 (R_B: B's field box radius)
  double proxy_offset = 0.25;      // field cells of B: a point stops at this distance from B's surface
  int proxy_iterations = 4;        // constrained steps (active set, solve, time of impact) per cycle
  // pressure-field (baselines/pressure_field): the spacing of the lattice its contact surface is
  // extracted on, in cells of the finer of the two fields.
  int pressure_lattice = 1;
};

// The parameters above as a table (util/param_table.h): the scene's model section reads them
// through it, each value checked, the error naming file, line and key.
const ParamTable<PointshellContactParams>& PointshellContactParamTable();

}  // namespace contactlab
