#include "contact/pointshell_contact_params.h"

namespace contactlab {

const ParamTable<PointshellContactParams>& PointshellContactParamTable() {
  using P = ParamRows<PointshellContactParams>;
  static const ParamTable<PointshellContactParams> table(
      "model", "The paper's contact model (Barbič & James 2008), whose penalty law and coherence bound every "
      "registered model shares.",
      {
          P::Number("k_C", PARAM_MEMBER(penalty.k_C), Above(0), NoUpperBound(),
                    "contact stiffness of one point, N/m (sec. 2.1)")
              .Unit("N/m").Sweepable().Example("3000"),
          P::Integer("L", PARAM_MEMBER(penalty.L), 0, 1000000,
                     "contacts at which the stiffness is scaled by L / l (0: no scaling; sec. 2.1)")
              .Sweepable().Example("20"),
          P::Integer("level", PARAM_MEMBER(level), -1, 64,
                     "linear variant: tree level rendered; tree: deepest level allowed (-1: the deepest)")
              .Sweepable().Example("2"),
          P::Boolean("coherence", PARAM_MEMBER(coherence),
                     "tree variant: temporal coherence (sec. 3); refused against a deformed field")
              .Sweepable().Example("true"),
          P::Number("max_point_speed", PARAM_MEMBER(max_point_speed), Above(0), NoUpperBound(),
                    "largest speed of any pointshell point relative to B, which coherence assumes")
              .Unit("m/s").Sweepable().Example("0.5"),
          P::Number("cycle_seconds", PARAM_MEMBER(cycle_seconds), Above(0), NoUpperBound(), "one haptic cycle")
              .Unit("s").Sweepable().Example("0.002"),
          P::Number("lipschitz", PARAM_MEMBER(lipschitz), AtLeast(1), NoUpperBound(),
                    "bound on |grad d| assumed by culling and coherence (paper: 1)")
              .Sweepable().Example("1.5"),
          P::Number("cold_fraction", PARAM_MEMBER(cold_fraction), Above(0), AtMost(1),
                    "graceful degradation: V_C = cold_fraction * V_W (sec. 3)")
              .Sweepable().Example("0.5"),
          P::Mapped("gradient", PARAM_MEMBER(gradient),
                    std::vector<std::pair<std::string, ContactGradient>>{{"halfspace", ContactGradient::kHalfspace},
                                                                         {"field", ContactGradient::kField}},
                    "contact gradient: the sec. 5 halfspace rule, or the field's gradient")
              .Sweepable().Example("field"),
          P::Number("proxy_stiffness", PARAM_MEMBER(proxy_stiffness), AtLeast(0), NoUpperBound(),
                    "pointshell-ccd: spring between its proxy and B (0: k_C L, k_C when L = 0)")
              .Unit("N/m").Sweepable().Example("5000"),
          P::Number("proxy_rot_stiffness", PARAM_MEMBER(proxy_rot_stiffness), AtLeast(0), NoUpperBound(),
                    "pointshell-ccd: rotational spring (0: proxy_stiffness times the squared radius of B's field box)")
              .Unit("N m/rad").Sweepable().Example("2"),
          P::Number("proxy_offset", PARAM_MEMBER(proxy_offset), Above(0), AtMost(4),
                    "pointshell-ccd: distance from B's surface at which a point of the proxy stops, in cells of B's field")
              .Sweepable().Example("0.1"),
          P::Integer("proxy_iterations", PARAM_MEMBER(proxy_iterations), 1, 64,
                     "pointshell-ccd: constrained steps (active set, solve, time of impact) per cycle")
              .Sweepable().Example("8"),
          P::Integer("pressure_lattice", PARAM_MEMBER(pressure_lattice), 1, 16,
                     "pressure-field: spacing of the lattice the contact surface is extracted on, in cells of the "
                     "finer field (1: its grid)")
              .Sweepable().Example("2"),
      });
  return table;
}

}  // namespace contactlab
