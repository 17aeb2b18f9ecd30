// K_B of the pressure-field model (pressure_field_model.h): the exact derivative of its
// discretised wrench (Elandt et al. 2019 on sampled fields) in B's pose, from the sums'
// derivatives taken in reverse mode through the integration, the clip and the cut
// (pressure_adjoints.h).
#pragma once

#include "contact/contact_model.h"
#include "geometry/pose.h"

namespace contactlab {

// d(wrench on B)/d(B's world twist) (translation, then rotation about B's origin), from D, the
// derivative of the lattice body L's sums (force, torque about L's origin, L's frame) along B's
// twist in L's frame. ON_B: the wrench on B (world, about B's origin). LATTICE_IS_A: L is A (the
// sums are the wrench on A, which does not move), else L is B (its sums turn with it).
Matrix6d PressureStiffnessOnB(const Matrix6d& D, const Wrench& on_B, bool lattice_is_A, const Pose& X_WA,
                              const Pose& X_WB);

}  // namespace contactlab
