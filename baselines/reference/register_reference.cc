// Registers "reference" (QuadratureReference: the eq. (2) limit by dense quadrature with exact
// distances to B's closed mesh) with the contact-model registry, and the reference-only
// "volume" (VolumeReference: the volume law on the exact overlap volume) and
// "eq2-halfspace" (HalfspaceLimitReference: the eq. (2) limit in closed form against a box's
// top face). The limit needs L > 0: a
// scene that turns the L / l scaling off (L = 0) gets the default L for its reference.
#include <memory>

#include "baselines/reference/halfspace_limit_reference.h"
#include "baselines/reference/surface_quadrature_reference.h"
#include "baselines/reference/volume_reference.h"
#include "contact/model_registry.h"

namespace contactlab {

void RegisterReferenceContactModels() {
  RegisterContactModel({
      .name = "reference",
      .description = "eq. (2) limit of the pointshell model: dense quadrature on A, exact CGAL distances to B (offline)",
      .needs = {.mesh_A = true, .mesh_B = true, .closed_mesh_B = true},
      .make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
        QuadratureReferenceParams p;
        p.penalty = in.params.penalty;
        if (p.penalty.L <= 0) p.penalty.L = PenaltyParams::kDefaultManyPointThreshold;
        return std::make_unique<QuadratureReference>(in.A.mesh(), in.B.mesh(), p);
      },
      .allocates = true,  // CGAL's distance queries
  });
  RegisterContactModel({
      .name = "volume",
      .description = "volume law -k_V grad V on the exact overlap volume of the two meshes (CGAL, offline reference)",
      .needs = {.mesh_A = true, .mesh_B = true, .closed_mesh_B = true},
      .make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
        return std::make_unique<VolumeReference>(in.A.mesh(), in.B.mesh(), in.params.penalty);
      },
      .reference_only = true,
  });
  RegisterContactModel({
      .name = "eq2-halfspace",
      .description = "eq. (2) limit in closed form: a sphere or polyhedron A against B's top face as a halfspace (B a box)",
      .needs = {.mesh_A = true, .mesh_B = true},
      .make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
        return std::make_unique<HalfspaceLimitReference>(in.A.mesh(), in.B.mesh(), in.params.penalty);
      },
      .reference_only = true,
  });
}

}  // namespace contactlab
