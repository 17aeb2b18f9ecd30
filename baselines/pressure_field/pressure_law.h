// The pressure of each body and the gap between them, whose zero set is the contact surface
// (Elandt et al. 2019, sec. III: p_i = E_i e_i with the extent e_i = -phi_i / max(-phi_i)).
#pragma once

#include <algorithm>

#include "baselines/pressure_field/polygon_clip.h"

namespace contactlab {

// The lattice body L's and the other body M's pressure laws: K = E / depth, pressure per metre
// of depth (0 for a rigid side, whose pressure counts as infinite inside it).
struct PressureLaw {
  bool rigid_M = false, rigid_L = false;
  double k_M = 0, k_L = 0;

  // p_M - p_L up to a positive factor, from the two fields at a point (metres): its zero set is
  // the contact surface.
  double Gap(double phi_M, double phi_L) const {
    return rigid_M ? -phi_M : rigid_L ? phi_L : -k_M * phi_M + k_L * phi_L;
  }
  // The pressure on the contact surface at V (Pa): the mean of the two bodies' when both are
  // compliant, the compliant one's when the other is rigid; never negative.
  double Pressure(const PolyVertex& v) const {
    const double pM = -k_M * v.phi_M, pL = -k_L * v.phi_L;
    const double p = rigid_M ? pL : rigid_L ? pM : 0.5 * (pM + pL);
    return std::max(0.0, p);
  }
};

}  // namespace contactlab
