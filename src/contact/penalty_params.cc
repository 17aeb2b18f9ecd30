#include "contact/penalty_params.h"

#include <cmath>
#include <string>

#include "util/config_node.h"
#include "util/error.h"

namespace contactlab {

void CheckPenaltyParams(const PenaltyParams& params, std::string_view where) {
  // k_C = 0 gives no force at any depth: the body would fall through silently.
  if (!(params.k_C > 0) || !std::isfinite(params.k_C)) Fail(where, "k_C must be a finite positive stiffness (N/m)");
  if (params.L < 0) Fail(where, "L must not be negative (0 disables the L / l scaling)");
}

PenaltyParams ParsePenaltyParams(const ConfigNode& section, PenaltyParams base) {
  PenaltyParams p = base;
  p.k_C = section.Positive("k_C", p.k_C);
  if (auto c = section.Find("L")) {
    const long long L = c->AsInt();
    if (L < 0 || L > 1000000) c->Fail("must be between 0 (no L / l scaling) and 1000000, got " + c->AsString());
    p.L = int(L);
  }
  return p;
}

}  // namespace contactlab
