#include "contact/body_contact_params.h"

namespace contactlab {

const ParamTable<PressureFieldSpec>& PressureFieldParams() {
  using P = ParamRows<PressureFieldSpec>;
  static const ParamTable<PressureFieldSpec> table(
      "bodies[].pressure_field",
      "The body's pressure field in the pressure-field (hydroelastic) model: p = E e, e = -phi / max(-phi).",
      {
          P::Number("modulus", PARAM_MEMBER(modulus), Above(0), NoUpperBound(),
                    "hydroelastic modulus E: the pressure at the body's deepest point")
              .Unit("Pa").Sweepable().Example("250000"),
          P::Boolean("rigid", PARAM_MEMBER(rigid),
                     "infinite modulus: the contact surface is this body's boundary inside the other")
              .Example("true"),
      });
  return table;
}

const ParamTable<InnerSphereSpec>& InnerSphereParams() {
  using P = ParamRows<InnerSphereSpec>;
  static const ParamTable<InnerSphereSpec> table(
      "bodies[].inner_spheres",
      "The body's inner-sphere packing in the inner-spheres model: greedy largest empty spheres inside its field.",
      {
          P::Integer("spheres", PARAM_MEMBER(spheres), 1, kMaxInnerSpheres, "at most this many spheres")
              .Sweepable().Example("500"),
          P::Number("coverage", PARAM_MEMBER(coverage), AtLeast(0), AtMost(1),
                    "stop once the spheres fill this fraction of the body's volume (0: no target)")
              .Sweepable().Example("0.8"),
      });
  return table;
}

}  // namespace contactlab
