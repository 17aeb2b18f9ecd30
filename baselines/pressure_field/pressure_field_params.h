// The pressure-field model's parameters (Elandt et al. 2019): per body its pressure field (scene
// block `bodies[].pressure_field`), per pair the lattice its contact surface is extracted on (a
// key of the scene's model section). Registered with the model (register_pressure_field.cc).
#pragma once

#include "util/param_table.h"

namespace contactlab {

// The range of a body's modulus (Pa), and why, in the table row (pressure_field_params.cc).
constexpr double kMinPressureModulus = 1;
constexpr double kMaxPressureModulus = 1e15;

// The body's pressure field: p(x) = E e(x), e the field's extent (0 on the surface, 1 at the
// deepest point), E the modulus. A rigid body has infinite modulus: the contact surface is its
// boundary inside the other body.
struct PressureFieldSpec {
  double modulus = 1.0e5;  // E, Pa
  bool rigid = false;
};

// The pair's keys: the lattice the contact surface is extracted on.
struct PressureLatticeSpec {
  int lattice = 1;  // in cells of the finer of the two fields
};

const ParamTable<PressureFieldSpec>& PressureFieldParams();
const ParamTable<PressureLatticeSpec>& PressureLatticeParams();

}  // namespace contactlab
