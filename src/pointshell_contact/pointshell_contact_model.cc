// Barbič & James 2008, sec. 2.1, 3 and 5: the checks every instance of the paper's model
// makes, and its rigid x grid instance.
#include "pointshell_contact/pointshell_contact_model.h"

#include "pointshell/point_tree.h"
#include "util/error.h"

namespace contactlab {

int ValidatePointshellModelInputs(const Pointshell* shell, const DistanceField* field,
                                  const PointshellContactParams& params, const std::string& where) {
  if (!shell || shell->num_points() == 0 || shell->num_levels() == 0) Fail(where, "needs a non-empty pointshell");
  if (!field || field->empty()) Fail(where, "needs a distance field");
  if (const std::int32_t n = NodeWithoutOwnFirstChild(*shell); n >= 0) {
    Fail(where, "pointshell node " + std::to_string(n) + ": its first child is not its own point one level down");
  }
  CheckPenaltyParams(params.penalty, where);
  if (params.level >= shell->num_levels() || params.level < -1) {
    Fail(where, "level " + std::to_string(params.level) + " is out of range (the pointshell has " +
                    std::to_string(shell->num_levels()) + " levels)");
  }
  if (!(params.max_point_speed > 0) || !(params.cycle_seconds > 0) || !(params.lipschitz >= 1)) {
    Fail(where, "max_point_speed and cycle_seconds must be positive and lipschitz >= 1");
  }
  if (!(params.cold_fraction > 0 && params.cold_fraction <= 1)) Fail(where, "cold_fraction must be in (0, 1]");
  return params.level < 0 ? shell->num_levels() - 1 : params.level;
}

void CheckPointshellCoherence(const PointshellContactParams& params, PointshellVariant variant, bool field_deforms,
                              std::string_view where) {
  if (field_deforms && params.coherence && variant == PointshellVariant::kTree) {
    Fail(where, "temporal coherence is not conservative against a deformed distance field (a point's distance "
                "can drop faster than the proxies move, through the pull-backs and the shifting proxy weights); "
                "set the model's coherence: false");
  }
}

template class PointshellFieldModel<RigidShell, GridField>;

}  // namespace contactlab
