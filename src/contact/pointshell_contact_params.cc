#include "contact/pointshell_contact_params.h"

#include "util/config_node.h"

namespace contactlab {

PointshellContactParams ParsePointshellContactParams(const ConfigNode& n) {
  PointshellContactParams p;
  p.penalty = ParsePenaltyParams(n, p.penalty);
  if (auto c = n.Find("level")) {
    const long long level = c->AsInt();
    if (level < -1 || level > 64) c->Fail("must be -1 (deepest) or a level index");
    p.level = int(level);
  }
  p.coherence = n.Bool("coherence", p.coherence);
  p.max_point_speed = n.Positive("max_point_speed", p.max_point_speed);
  p.cycle_seconds = n.Positive("cycle_seconds", p.cycle_seconds);
  p.lipschitz = n.Positive("lipschitz", p.lipschitz);
  if (p.lipschitz < 1) n.Get("lipschitz").Fail("must be at least 1");
  p.cold_fraction = n.Positive("cold_fraction", p.cold_fraction);
  if (p.cold_fraction > 1) n.Get("cold_fraction").Fail("must be at most 1");
  p.gradient = n.OneOf("gradient", "halfspace", {"halfspace", "field"}) == "field" ? ContactGradient::kField
                                                                                   : ContactGradient::kHalfspace;
  return p;
}

}  // namespace contactlab
