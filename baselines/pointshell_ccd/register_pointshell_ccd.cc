// Registers "pointshell-ccd" (pointshell_ccd_model.h) with the contact-model registry. Its
// parameters come from the scene's model section: k_C and L set the proxy's default coupling
// stiffness (the largest the paper's model renders, k_C L), proxy_offset is in cells of B's field.
#include <algorithm>
#include <memory>

#include "baselines/pointshell_ccd/pointshell_ccd_model.h"
#include "contact/model_registry.h"
#include "geometry/aabb.h"

namespace contactlab {

void RegisterPointshellCcdContactModels() {
  ContactModelEntry e;
  e.name = "pointshell-ccd";
  e.description = "proxy that never passes through: continuous collision of A's pointshell against B's field (Xu & Barbic 2017)";
  e.needs.pointshell_A = true;
  e.needs.field_B = true;
  e.make = [](const ContactModelInputs& in) -> std::unique_ptr<ContactModel> {
    const PointshellContactParams& m = in.params;
    CheckPenaltyParams(m.penalty, "pointshell-ccd");
    auto field = in.B.field();
    PointshellCcdParams p;
    p.stiffness = m.proxy_stiffness > 0 ? m.proxy_stiffness : m.penalty.k_C * std::max(1, m.penalty.L);
    // B's field box, its farthest corner from B's origin (per axis the farther face).
    const Aabb box = field->box();
    const double radius = box.min.cwiseAbs().cwiseMax(box.max.cwiseAbs()).norm();
    p.rot_stiffness = m.proxy_rot_stiffness > 0 ? m.proxy_rot_stiffness : p.stiffness * radius * radius;
    p.offset = m.proxy_offset * field->spacing();
    p.iterations = m.proxy_iterations;
    p.lipschitz = m.lipschitz;
    return std::make_unique<PointshellCcdModel>(in.A.pointshell(), std::move(field), p);
  };
  RegisterContactModel(std::move(e));
}

}  // namespace contactlab
