#include "contact/contact_params.h"

namespace contactlab {

const ParamTable<ContactParams>& ContactParamTable() {
  using P = ParamRows<ContactParams>;
  static const ParamTable<ContactParams> table(
      "model", "The parameters every contact model shares: the paper's penalty law (Barbič & James 2008), the "
      "coherence bound and the haptic cycle.",
      {
          P::Number("k_C", PARAM_MEMBER(penalty.k_C), Above(0), AtMost(1e9),
                    "contact stiffness of one point, N/m (sec. 2.1); at most 1e9, some 10^5 times what a haptic "
                    "device renders stably, so that no force reaches magnitudes no report can state (9.2e18 gave "
                    "2e17 N)")
              .Unit("N/m").Sweepable().Example("3000"),
          P::Integer("L", PARAM_MEMBER(penalty.L), 0, 1000000,
                     "contacts at which the stiffness is scaled by L / l (0: no scaling; sec. 2.1)")
              .Sweepable().Example("20"),
          P::Boolean("coherence", PARAM_MEMBER(coherence),
                     "temporal coherence (sec. 3) in the models that keep it (pointshell's tree variant, vps); "
                     "refused against a deformed field")
              .Sweepable().Example("true"),
          P::Number("max_point_speed", PARAM_MEMBER(max_point_speed), Above(0), NoUpperBound(),
                    "largest speed of any pointshell point relative to B, which coherence assumes")
              .Unit("m/s").Sweepable().Example("0.5"),
          P::Number("cycle_seconds", PARAM_MEMBER(cycle_seconds), AtLeast(kMinCycleSeconds), AtMost(kMaxCycleSeconds),
                    "one haptic cycle (a loop of 10 Hz to 100 kHz)")
              .Unit("s").Sweepable().Example("0.002"),
          P::Number("lipschitz", PARAM_MEMBER(lipschitz), AtLeast(1), NoUpperBound(),
                    "bound on |grad d| assumed by culling and coherence (paper: 1)")
              .Sweepable().Example("1.5"),
          P::Mapped("stiffness", PARAM_MEMBER(stiffness),
                    std::vector<std::pair<std::string, StiffnessRule>>{{"own", StiffnessRule::kOwn},
                                                                       {"matched", StiffnessRule::kMatched}},
                    "own: each model's stiffness keys as given; matched: every model other than the paper's "
                    "pointshell has its wrench (force, torque, gradient) scaled by the one factor that makes it "
                    "push back like the paper's model on a reference press (A moved toward B's origin to where "
                    "its mesh first touches B, then match_depth further; one pose), the same as scaling the "
                    "model's own stiffness keys, since every model's wrench is linear in them")
              .Sweepable().Example("matched"),
          P::Number("match_depth", PARAM_MEMBER(match_depth), Above(0), AtMost(1),
                    "stiffness: matched: how far past the meshes' first touch the reference press goes")
              .Unit("m").Sweepable().Example("0.002"),
          P::Block("friction", PARAM_MEMBER(friction), FrictionParamTable(),
                   "Coulomb friction {static, dynamic, stiffness} in the models that carry it (off by default)"),
      });
  return table;
}

}  // namespace contactlab
