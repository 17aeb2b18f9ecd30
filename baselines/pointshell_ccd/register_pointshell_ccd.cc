// Registers "pointshell-ccd" (pointshell_ccd_model.h) with the contact-model registry, with its
// own keys under the scene's model section (proxy_*). k_C and L, which every model shares, set
// the proxy's default coupling stiffness (the largest the paper's model renders, k_C L);
// proxy_offset is in cells of B's field.
#include <algorithm>
#include <memory>

#include "baselines/pointshell_ccd/pointshell_ccd_model.h"
#include "contact/model_registry.h"
#include "geometry/aabb.h"

namespace contactlab {
namespace {

// The proxy's coupling to B, how far from B's surface its points stop, and its constrained
// steps per cycle, as the scene gives them.
struct ProxySpec {
  double stiffness = 0;      // N/m; 0: k_C L (k_C when L = 0)
  double rot_stiffness = 0;  // N m/rad; 0: stiffness R_B^2 (R_B: B's field box radius)
  double offset = 0.25;      // field cells of B: a point stops at this distance from B's surface
  int iterations = 4;        // constrained steps (active set, solve, time of impact) per cycle
};

const ParamTable<ProxySpec>& ProxyParams() {
  using P = ParamRows<ProxySpec>;
  static const ParamTable<ProxySpec> table(
      "pointshell-ccd", "The proxy of pointshell-ccd: its coupling to B, its stopping distance and its steps.",
      {
          P::Number("proxy_stiffness", PARAM_MEMBER(stiffness), AtLeast(0), NoUpperBound(),
                    "pointshell-ccd: spring between its proxy and B (0: k_C L, k_C when L = 0)")
              .Unit("N/m").Sweepable().Example("5000"),
          P::Number("proxy_rot_stiffness", PARAM_MEMBER(rot_stiffness), AtLeast(0), NoUpperBound(),
                    "pointshell-ccd: rotational spring (0: proxy_stiffness times the squared radius of B's field box)")
              .Unit("N m/rad").Sweepable().Example("2"),
          P::Number("proxy_offset", PARAM_MEMBER(offset), AtLeast(kMinProxyOffsetCells), AtMost(4),
                    "pointshell-ccd: distance from B's surface at which a point of the proxy stops, in cells of B's "
                    "field. At least 0.01: a point in contact advances by at least half the offset a step, so a "
                    "smaller offset lets the proxy slide only a few micrometres a cycle and it lags or stalls")
              .Sweepable().Example("0.1"),
          P::Integer("proxy_iterations", PARAM_MEMBER(iterations), 1, 64,
                     "pointshell-ccd: constrained steps (active set, solve, time of impact) per cycle")
              .Sweepable().Example("8"),
      });
  return table;
}

std::unique_ptr<ContactModel> MakePointshellCcd(const ContactModelInputs& in) {
  const ProxySpec& proxy = in.Params(ProxyParams());
  const PenaltyParams& penalty = in.params.penalty;
  CheckPenaltyParams(penalty, "pointshell-ccd");
  auto field = in.B.field();
  PointshellCcdParams p;
  p.stiffness = proxy.stiffness > 0 ? proxy.stiffness : penalty.k_C * std::max(1, penalty.L);
  // B's field box, its farthest corner from B's origin (per axis the farther face).
  const Aabb box = field->box();
  const double radius = box.min.cwiseAbs().cwiseMax(box.max.cwiseAbs()).norm();
  p.rot_stiffness = proxy.rot_stiffness > 0 ? proxy.rot_stiffness : p.stiffness * radius * radius;
  p.offset = proxy.offset * field->spacing();
  p.iterations = proxy.iterations;
  p.lipschitz = in.params.lipschitz;
  return std::make_unique<PointshellCcdModel>(in.A.pointshell(), std::move(field), p);
}

}  // namespace

void RegisterPointshellCcdContactModels() {
  RegisterContactModel({
      .name = "pointshell-ccd",
      .description = "proxy that never passes through: continuous collision of A's pointshell against B's field "
                     "(Xu & Barbic 2017)",
      .needs = {.pointshell_A = true, .field_B = true},
      .make = MakePointshellCcd,
      .pair_params = ParamBlock(ProxyParams()),
  });
}

}  // namespace contactlab
