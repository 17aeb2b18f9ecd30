// The parameters every contact model shares, read from a scene's "model:" section: the penalty
// law (Barbič & James 2008, sec. 2.1), the coherence bound (sec. 3), the haptic cycle and friction. A
// model's own keys live in its own folder, in the table its registry entry carries
// (model_registry.h, ContactModelEntry::pair_params).
#pragma once

#include "contact/friction.h"
#include "contact/penalty_params.h"
#include "util/param_table.h"

namespace contactlab {

// How a model's stiffness is set in a scene (scene/stiffness_match.h).
enum class StiffnessRule {
  kOwn,      // each model's own stiffness keys as given
  kMatched,  // every model's wrench scaled so a reference press gives the paper's model's force
};

// The haptic cycles a scene may ask for (model.cycle_seconds): 1e-5 s to 0.1 s, a loop of
// 100 kHz down to 10 Hz (haptics/haptic_loop.h derives its rates from these).
inline constexpr double kMinCycleSeconds = 1e-5;
inline constexpr double kMaxCycleSeconds = 0.1;

struct ContactParams {
  PenaltyParams penalty;         // k_C and L (sec. 2.1)
  bool coherence = false;        // temporal coherence (sec. 3), in the models that keep it
  double max_point_speed = 1.0;  // m/s, largest speed of any point of A relative to B
  double cycle_seconds = 1e-3;   // duration of one haptic cycle, seconds
  double lipschitz = 1.0;        // bound on |grad d| assumed by culling and coherence (paper: 1)
  StiffnessRule stiffness = StiffnessRule::kOwn;
  double match_depth = 1e-3;     // metres past first touch of the reference press (kMatched)
  FrictionParams friction;       // off unless friction.static > 0 (contact/friction.h)
};

// The parameters above as a table (util/param_table.h): the scene's model section reads them
// through it, each value checked, the error naming file, line and key.
const ParamTable<ContactParams>& ContactParamTable();

}  // namespace contactlab
