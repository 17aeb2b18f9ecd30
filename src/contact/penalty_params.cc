#include "contact/penalty_params.h"

#include <cmath>
#include <string>

#include "util/error.h"

namespace contactlab {

void CheckPenaltyParams(const PenaltyParams& params, std::string_view where) {
  // k_C = 0 gives no force at any depth: the body would fall through silently.
  if (!(params.k_C > 0) || !std::isfinite(params.k_C)) Fail(where, "k_C must be a finite positive stiffness (N/m)");
  if (params.L < 0) Fail(where, "L must not be negative (0 disables the L / l scaling)");
}

}  // namespace contactlab
