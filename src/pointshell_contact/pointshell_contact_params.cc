#include "pointshell_contact/pointshell_contact_params.h"

namespace contactlab {

PointshellContactParams PointshellParamsOf(const ContactParams& shared, const PointshellOwnParams& own) {
  return {.penalty = shared.penalty,
          .level = own.level,
          .coherence = shared.coherence,
          .max_point_speed = shared.max_point_speed,
          .cycle_seconds = shared.cycle_seconds,
          .lipschitz = shared.lipschitz,
          .cold_fraction = own.cold_fraction,
          .gradient = own.gradient,
          .friction = shared.friction};
}

const ParamTable<PointshellOwnParams>& PointshellOwnParamTable() {
  using P = ParamRows<PointshellOwnParams>;
  static const ParamTable<PointshellOwnParams> table(
      "pointshell", "The paper's model (pointshell, pointshell-linear): its tree level, graceful degradation and "
      "contact gradient.",
      {
          P::Integer("level", PARAM_MEMBER(level), -1, 64,
                     "pointshell-linear: tree level rendered; pointshell: deepest level allowed (-1: the deepest)")
              .Sweepable().Example("2"),
          P::Number("cold_fraction", PARAM_MEMBER(cold_fraction), Above(0), AtMost(1),
                    "pointshell: graceful degradation, V_C = cold_fraction * V_W (sec. 3)")
              .Sweepable().Example("0.5"),
          P::Mapped("gradient", PARAM_MEMBER(gradient),
                    std::vector<std::pair<std::string, ContactGradient>>{{"halfspace", ContactGradient::kHalfspace},
                                                                         {"field", ContactGradient::kField}},
                    "pointshell: contact gradient, the sec. 5 halfspace rule or the field's gradient")
              .Sweepable().Example("field"),
      });
  return table;
}

}  // namespace contactlab
