#include "contact/friction.h"

#include <string>
#include <utility>

namespace contactlab {

const ParamTable<FrictionParams>& FrictionParamTable() {
  using P = ParamRows<FrictionParams>;
  static const ParamTable<FrictionParams> table(
      "friction",
      "Coulomb friction on a stick anchor per contact (docs/models.md, \"Friction\"): a contact sticks while its "
      "tangential force stays within static * F_n and slides at dynamic * F_n beyond, F_n its normal force. Off "
      "(static 0) by default; the models that carry it are marked in `contactlab models`.",
      {
          P::Number("static", PARAM_MEMBER(mu_static), AtLeast(0), AtMost(10),
                    "static coefficient mu_s: the largest tangential force a sticking contact holds, per newton of "
                    "normal force (0: no friction)")
              .Sweepable()
              .Example("0.5"),
          P::Number("dynamic", PARAM_MEMBER(mu_dynamic), AtLeast(0), AtMost(10),
                    "dynamic coefficient mu_d <= mu_s: the tangential force of a sliding contact per newton of normal "
                    "force (default: the static coefficient)")
              .Sweepable()
              .Default("static")
              .Example("0.4"),
          P::Number("stiffness", PARAM_MEMBER(tangential_stiffness), Above(0), AtMost(1e9),
                    "tangential stiffness kappa of a sticking contact per newton of its normal force (N/m per N): "
                    "it slips after mu_s / kappa of tangential travel")
              .Unit("1/m")
              .Sweepable()
              .Example("2000"),
          P::Number("match_radius", PARAM_MEMBER(match_radius), Above(0), AtMost(1),
                    "models whose contacts are new each query (fcl, bullet): a contact takes over the anchor of "
                    "the previous query's contact nearest to it on A within this distance")
              .Unit("m")
              .Sweepable()
              .Example("0.002"),
      },
      [](const ConfigNode& n, FrictionParams* f) {
        if (!n.Has("dynamic")) f->mu_dynamic = f->mu_static;
        if (f->mu_dynamic > f->mu_static) {
          n.Fail("dynamic (" + std::to_string(f->mu_dynamic) + ") must not exceed static (" +
                 std::to_string(f->mu_static) + "): a contact that slides holds no more than one that sticks");
        }
      });
  return table;
}

}  // namespace contactlab
