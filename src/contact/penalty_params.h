// The penalty law every contact model shares (Barbič & James 2008, sec. 2.1): a point (or
// contact) at depth -d pushes with k_C |d|, and when l >= L points touch at once k_C becomes
// k_C L / l so the total stays that of about L points. The paper's model, VPS, FCL, Bullet and
// the references all embed this one type; its defaults are written here and nowhere else.
#pragma once

#include <string_view>

namespace contactlab {

struct PenaltyParams {
  static constexpr double kDefaultStiffness = 1000;  // k_C, N/m
  static constexpr int kDefaultManyPointThreshold = 10;  // L

  double k_C = kDefaultStiffness;       // contact penalty stiffness, N/m (per point, before L/l)
  int L = kDefaultManyPointThreshold;   // k_C -> k_C L / l when l >= L points touch; 0 disables it

  // The stiffness applied to each of COUNT touching points: k_C, or k_C L / COUNT when
  // COUNT >= L > 0. Sets *SCALE (may be null) to the factor applied.
  double StiffnessFor(int count, double* scale = nullptr) const {
    double s = 1;
    if (L > 0 && count >= L) s = double(L) / double(count);
    if (scale != nullptr) *scale = s;
    return k_C * s;
  }
};

// Throws Error("WHERE: ...") unless k_C is finite and positive and L is not negative.
void CheckPenaltyParams(const PenaltyParams& params, std::string_view where);

}  // namespace contactlab
