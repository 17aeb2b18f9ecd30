// The penalty law every contact model shares (Barbič & James 2008, sec. 2.1): a point (or
// contact) at depth -d pushes with k_C |d|, and when l >= L points touch at once k_C becomes
// k_C L / l so the total stays that of about L points. The paper's model, VPS, FCL, Bullet and
// the references all embed this one type; its defaults are written here and nowhere else.
#pragma once

#include <cmath>
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

  // The volume law's stiffness k_V (force -k_V grad V, N/m^2) for a first body of surface area
  // AREA_A (m^2): k_C L / sqrt(AREA_A). A flat face of area A_c pressed in feels k_V A_c at
  // every depth, and scaling the whole scene by s scales the force by s, as in the penalty
  // laws. L = 0 counts as the default L. The volume reference and inner-spheres both use it, so
  // their forces compare directly.
  double VolumeStiffness(double area_A) const {
    const int l = L > 0 ? L : kDefaultManyPointThreshold;
    return k_C * l / std::sqrt(area_A);
  }
};

// Throws Error("WHERE: ...") unless k_C is finite and positive and L is not negative.
void CheckPenaltyParams(const PenaltyParams& params, std::string_view where);

}  // namespace contactlab
