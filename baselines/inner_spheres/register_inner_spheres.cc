// Registers "inner-spheres" (inner_sphere_model.h) with the contact-model registry. Each
// body's packing follows its scene block `inner_spheres:` and is cached beside its field
// (ContactBody::DerivedCachePath), keyed by every packing parameter and the builder's version;
// building one reports how much of the body's volume it fills.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "baselines/inner_spheres/inner_sphere_model.h"
#include "contact/model_registry.h"
#include "geometry/triangle_mesh.h"
#include "util/cached_or_built.h"
#include "util/error.h"

namespace contactlab {
namespace {

std::shared_ptr<const SpherePacking> PackingOf(ContactBody& body) {
  const InnerSphereSpec& spec = body.contact_params().inner_spheres;
  const std::string where = "inner-spheres: body '" + std::string(body.body_name()) + "'";
  const auto field = body.field();
  if (field->info().mode == "soup") Fail(where, "its field is a polygon soup's offset band, not a volume to fill");
  SpherePackingOptions o;
  o.max_spheres = spec.spheres;
  o.coverage = spec.coverage;
  char key[160];
  std::snprintf(key, sizeof key, "inner-spheres v%d spheres=%d coverage=%.17g min_radius_cells=%.17g",
                kSpherePackingVersion, o.max_spheres, o.coverage, o.min_radius_cells);
  return CachedOrBuilt<SpherePacking>(
      body.DerivedCachePath(key), false, "the inner spheres of " + std::string(body.body_name()), LoadSpherePacking,
      SaveSpherePacking, [&] {
        SpherePacking packing = BuildSpherePacking(*field, std::abs(body.mesh()->SignedVolume()), o, where);
        std::fprintf(stderr, "built %zu inner spheres of %s filling %.1f%% of its volume\n", packing.radii.size(),
                     std::string(body.body_name()).c_str(), 100 * packing.Coverage());
        return packing;
      });
}

}  // namespace

void RegisterInnerSphereContactModels() {
  ContactModelEntry e;
  e.name = "inner-spheres";
  e.description = "Inner Sphere Trees: penetration volume of the two bodies' inner-sphere packings, force -k_V grad V (Weller & Zachmann 2009)";
  e.needs.field_A = true;
  e.needs.field_B = true;
  e.needs.mesh_A = true;
  e.needs.mesh_B = true;
  e.make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
    // The volume reference's stiffness (baselines/reference/volume_reference.h).
    CheckPenaltyParams(in.params.penalty, "inner-spheres");
    const double k_V = in.params.penalty.VolumeStiffness(in.A.mesh()->SurfaceArea());
    return std::make_unique<InnerSphereModel>(PackingOf(in.A), PackingOf(in.B), k_V);
  };
  RegisterContactModel(std::move(e));
}

}  // namespace contactlab
