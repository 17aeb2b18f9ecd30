// The pressure of each body and the gap between them, whose zero set is the contact surface
// (Elandt et al. 2019, sec. III: p_i = E_i e_i with the extent e_i = -phi_i / max(-phi_i)).
//
// Each body is a spring of compliance c_i = max(-phi_i) / E_i (metres of depth per pascal; 0
// for a rigid body), p_i = -phi_i / c_i. On the contact surface p_M = p_L = p, so the two
// depths add up to the local overlap, -(phi_M + phi_L) = (c_M + c_L) p: the surface carries
// the two springs in series. Written with the compliances, nothing is multiplied by a modulus:
// a body far stiffer than the other (1e40 against 1e5 Pa) is the rigid limit to rounding, where
// E_i phi_i would amplify the fields' rounding by E_i, and no modulus overflows a product.
#pragma once

#include <algorithm>

#include "baselines/pressure_field/polygon_clip.h"

namespace contactlab {

// The lattice body L's and the other body M's pressure laws, from their compliances.
struct PressureLaw {
  double w_M = 0.5, w_L = 0.5;  // the fields' weights in the gap: c_L, c_M over c_M + c_L (sum 1)
  double k = 0;                 // 1 / (c_M + c_L): pressure per metre of overlap, Pa/m

  // C_M, C_L: each body's compliance, max(-phi) / E in m/Pa, 0 for a rigid body (not both).
  static PressureLaw FromCompliances(double c_M, double c_L) {
    const double c = c_M + c_L;
    return {c_L / c, c_M / c, 1 / c};
  }

  // p_M - p_L times c_M c_L / (c_M + c_L), from the two fields at a point (metres): its zero
  // set is the contact surface. -phi_M for a rigid M, phi_L for a rigid L; at most as steep
  // as the steeper field.
  double Gap(double phi_M, double phi_L) const { return -w_M * phi_M + w_L * phi_L; }
  // The pressure on the contact surface at V (Pa): both bodies' there, never negative.
  double Pressure(const PolyVertex& v) const { return std::max(0.0, -k * (v.phi_M + v.phi_L)); }
};

}  // namespace contactlab
