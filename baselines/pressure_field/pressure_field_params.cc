#include "baselines/pressure_field/pressure_field_params.h"

namespace contactlab {

const ParamTable<PressureFieldSpec>& PressureFieldParams() {
  using P = ParamRows<PressureFieldSpec>;
  static const ParamTable<PressureFieldSpec> table(
      "bodies[].pressure_field",
      "The body's pressure field in the pressure-field (hydroelastic) model: p = E e, e = -phi / max(-phi).",
      {
          P::Number("modulus", PARAM_MEMBER(modulus), AtLeast(kMinPressureModulus), AtMost(kMaxPressureModulus),
                    "hydroelastic modulus E: the pressure at the body's deepest point. Bounded to physical values: "
                    "softer than any gel to a thousand times diamond (1.1e12 Pa); a stiffer body is `rigid`, which "
                    "1e15 Pa against a 1e5 Pa body already renders to six digits, and moduli toward the double "
                    "range overflow the pressure, its integral and K_B")
              .Unit("Pa").Sweepable().Example("250000"),
          P::Boolean("rigid", PARAM_MEMBER(rigid),
                     "infinite modulus: the contact surface is this body's boundary inside the other")
              .Example("true"),
      });
  return table;
}

const ParamTable<PressureLatticeSpec>& PressureLatticeParams() {
  using P = ParamRows<PressureLatticeSpec>;
  static const ParamTable<PressureLatticeSpec> table(
      "pressure-field", "The lattice the pressure field's contact surface is extracted on.",
      {
          P::Integer("pressure_lattice", PARAM_MEMBER(lattice), 1, 16,
                     "pressure-field: spacing of the lattice the contact surface is extracted on, in cells of the "
                     "finer field (1: its grid)")
              .Sweepable().Example("2"),
      });
  return table;
}

}  // namespace contactlab
