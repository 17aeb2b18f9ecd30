// contact_query SCENE.yaml [MODEL]: loads a scene, makes a contact model by name (default: the
// scene's first) and prints the force on the field body at the scene's start poses.
#include <cstdio>
#include <exception>

#include "contact/register_contact_models.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"

int main(int argc, char** argv) try {
  if (argc < 2) return std::fprintf(stderr, "usage: %s SCENE.yaml [MODEL]\n", argv[0]), 2;
  contactlab::RegisterContactModels();  // "fcl", "bullet", "vps", ... beside "pointshell"
  const contactlab::Scene scene = contactlab::LoadScene(argv[1]);
  contactlab::SceneAssets assets(scene, contactlab::AssetOptions{});  // builds or reads the field and pointshell
  const auto model = contactlab::MakeSceneContactModel(argc > 2 ? argv[2] : scene.models.front(), scene, assets);
  contactlab::ContactQuery query;
  query.X_WA = scene.pointshell_body.pose;
  query.X_WB = scene.field_body.pose;
  const Eigen::Vector3d f = model->Evaluate(query).on_B.force;
  std::printf("%.*s: force on %s = [%.6g, %.6g, %.6g] N\n", int(model->name().size()), model->name().data(),
              scene.field_body.name.c_str(), f.x(), f.y(), f.z());
} catch (const std::exception& e) {
  std::fprintf(stderr, "contact_query: %s\n", e.what());
  return 1;
}
