// Registration of the baseline contact models (see register_baselines.h).
#include "baselines/register_baselines.h"

#include <memory>

#include "baselines/bullet/bullet_contact_model.h"
#include "baselines/fcl/fcl_contact_model.h"
#include "experiment/model_factory.h"
#ifdef CONTACTLAB_HAVE_CGAL
#include "baselines/reference/surface_quadrature_reference.h"
#endif
// VPS comes from another folder (baselines/vps) and is linked only when it is built.
#if defined(CONTACTLAB_HAVE_VPS) && __has_include("baselines/vps/vps_contact_model.h")
#include "baselines/vps/vps_contact_model.h"
#define CONTACTLAB_REGISTER_VPS 1
#endif

namespace contactlab {

void RegisterBaselineContactModels() {
  RegisterContactModel("fcl", [](const Scene& scene, SceneAssets& assets) -> std::unique_ptr<ContactModel> {
    FclContactParams p;
    p.k_C = scene.model.k_C;
    p.L = scene.model.L;
    return std::make_unique<FclContactModel>(assets.A.mesh(), assets.B.mesh(), p);
  });
  RegisterContactModel("bullet", [](const Scene& scene, SceneAssets& assets) -> std::unique_ptr<ContactModel> {
    BulletContactParams p;
    p.k_C = scene.model.k_C;
    p.L = scene.model.L;
    return std::make_unique<BulletContactModel>(assets.A.mesh(), assets.B.mesh(), p);
  });
#ifdef CONTACTLAB_HAVE_CGAL
  RegisterContactModel("reference", [](const Scene& scene, SceneAssets& assets) -> std::unique_ptr<ContactModel> {
    QuadratureReferenceParams p;
    p.k_C = scene.model.k_C;
    p.L = scene.model.L > 0 ? scene.model.L : 10;
    return std::make_unique<QuadratureReference>(assets.A.mesh(), assets.B.mesh(), p);
  });
#endif
#ifdef CONTACTLAB_REGISTER_VPS
  RegisterVpsContactModels();
#endif
}

}  // namespace contactlab
