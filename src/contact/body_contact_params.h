// Per-body parameters of the volumetric contact models, read from a scene body's blocks
// `pressure_field:` and `inner_spheres:` (experiment/scene.h). They describe the body, not the
// pair: a body's pressure modulus and its sphere packing are the same whatever it touches.
#pragma once

#include "util/param_table.h"

namespace contactlab {

// The body's pressure field of "pressure-field" (baselines/pressure_field): p(x) = E e(x), e the
// field's extent (0 on the surface, 1 at the deepest point), E the modulus. A rigid body has
// infinite modulus: the contact surface is its boundary inside the other body.
struct PressureFieldSpec {
  double modulus = 1.0e5;  // E, Pa
  bool rigid = false;
};

// The body's inner-sphere packing of "inner-spheres" (baselines/inner_spheres): greedy largest
// empty spheres inside its field until SPHERES are placed or their volume reaches COVERAGE of
// the body's.
struct InnerSphereSpec {
  int spheres = 2000;    // at most this many spheres
  double coverage = 0;   // stop once this fraction of the volume is covered (0: no target)
};

inline constexpr int kMaxInnerSpheres = 1 << 20;

struct BodyContactParams {
  PressureFieldSpec pressure_field;
  InnerSphereSpec inner_spheres;
};

// The blocks' tables (util/param_table.h): parsing, range checks, the packing's cache key and
// the scene reference.
const ParamTable<PressureFieldSpec>& PressureFieldParams();
const ParamTable<InnerSphereSpec>& InnerSphereParams();

}  // namespace contactlab
