// Parameters of the paper's contact model (Barbič & James 2008, sec. 2.1, 3, 5): the keys every
// model shares (contact/contact_params.h) and the paper's own, its tree level, its graceful
// degradation's cold threshold and its contact gradient, read from a scene's "model:" section.
#pragma once

#include "contact/contact_accumulator.h"
#include "contact/contact_params.h"
#include "contact/penalty_params.h"
#include "util/param_table.h"

namespace contactlab {

// The paper's own keys.
struct PointshellOwnParams {
  int level = -1;                // linear variant: tree level rendered (-1: deepest); tree: deepest level allowed
  double cold_fraction = 0.8;    // V_C = cold_fraction * V_W (sec. 3, graceful degradation)
  ContactGradient gradient = ContactGradient::kHalfspace;  // sec. 5 halfspace rule, or the field's gradient
};

// Everything the paper's model reads.
struct PointshellContactParams {
  PenaltyParams penalty;         // k_C and L (sec. 2.1)
  int level = -1;                // linear variant: tree level rendered (-1: deepest); tree: deepest level allowed
  bool coherence = false;        // tree variant: temporal coherence (sec. 3)
  double max_point_speed = 1.0;  // m/s, largest speed of any pointshell point relative to B
  double cycle_seconds = 1e-3;   // duration of one haptic cycle, seconds
  double lipschitz = 1.0;        // bound on |grad d| assumed by culling and coherence (paper: 1)
  double cold_fraction = 0.8;    // V_C = cold_fraction * V_W (sec. 3, graceful degradation)
  ContactGradient gradient = ContactGradient::kHalfspace;  // sec. 5 halfspace rule, or the field's gradient
  FrictionParams friction;       // off by default (contact/friction.h)
};

// The shared keys SHARED with the paper's own OWN.
PointshellContactParams PointshellParamsOf(const ContactParams& shared, const PointshellOwnParams& own);

// The paper's own keys as a table (util/param_table.h), carried by its registry entries.
const ParamTable<PointshellOwnParams>& PointshellOwnParamTable();

}  // namespace contactlab
