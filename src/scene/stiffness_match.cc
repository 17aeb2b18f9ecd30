#include "scene/stiffness_match.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "contact/model_registry.h"
#include "contact/scaled_contact_model.h"
#include "geometry/triangle_mesh.h"
#include "sdf/distance_field.h"
#include "util/error.h"

namespace contactlab {

namespace {

// The entry whose stiffness the others are matched to (ContactModelEntry::stiffness_reference).
const ContactModelEntry& StiffnessReference(std::string_view where) {
  return SoleContactModelWith([](const ContactModelEntry& e) { return e.stiffness_reference; },
                              "the stiffness reference", where);
}

// How far A moves from X_WA_FAR along DIRECTION (unit, world) until a vertex of A's mesh first
// reaches B's surface (B's signed distance field at X_WB): sphere tracing on the smallest
// distance of A's vertices, a 1-Lipschitz function of the travel, to 1e-7 m. Negative when A
// passes B without touching within MAX_TRAVEL.
double TravelToTouch(const TriangleMesh& mesh_A, const DistanceField& field_B, const Pose& X_WA_far, const Pose& X_WB,
                     const Eigen::Vector3d& direction, double max_travel) {
  const Pose X_BW = X_WB.Inverse();
  auto gap = [&](double s) {
    Pose X_WA = X_WA_far;
    X_WA.translation += s * direction;
    const Pose X_BA = X_BW * X_WA;
    double g = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& v : mesh_A.vertices) g = std::min(g, field_B.Distance(X_BA * v));
    return g;
  };
  for (double s = 0; s <= max_travel;) {
    const double g = gap(s);
    if (g <= 1e-7) return s;
    s += g;
  }
  return -1;
}

}  // namespace

double MatchedStiffnessScale(ContactModel& model, std::string_view name, const Scene& scene, SceneAssets& assets) {
  const std::string where = (scene.file.empty() ? std::string("scene") : scene.file) + ": model.stiffness: matched (" +
                            std::string(name) + ")";
  const Pose& X_WA = scene.pointshell_body.pose;
  const Pose& X_WB = scene.field_body.pose;
  const Eigen::Vector3d direction = X_WB.translation - X_WA.translation;
  if (!(direction.norm() > 0)) Fail(where, "the reference press moves A toward B's origin, but both start at the same point");
  const Eigen::Vector3d dir = direction.normalized();
  const double depth = scene.model.match_depth;
  // From a full reach back, to where A's mesh first touches B's surface, then DEPTH further.
  const auto mesh_A = assets.A.mesh();
  const double reach = mesh_A->Bounds().size().norm() + assets.B.mesh()->Bounds().size().norm();
  Pose far = X_WA;
  far.translation -= reach * dir;
  const double travel = TravelToTouch(*mesh_A, *assets.B.field(), far, X_WB, dir, 2 * reach);
  if (travel < 0) Fail(where, "A's mesh never touches B moving from its start pose toward B's origin");
  ContactQuery q;
  q.X_WA = far;
  q.X_WA.translation += (travel + depth) * dir;
  q.X_WB = X_WB;
  std::unique_ptr<ContactModel> paper =
      MakeContactModel(StiffnessReference(where).name, ContactModelInputs{assets.A, assets.B, scene.model, scene.model_params}, where);
  model.Reset();
  const Eigen::Vector3d F = paper->Evaluate(q).on_B.force;
  const Eigen::Vector3d m = model.Evaluate(q).on_B.force;
  model.Reset();
  const double cross = F.dot(m), own = m.squaredNorm();
  if (!(own > 0) || !std::isfinite(own)) {
    Fail(where, "the model gives no force on the reference press (A moved toward B's origin, match_depth = " +
                    std::to_string(depth) + " m past where its mesh first touches B): nothing to scale; try a larger "
                    "match_depth");
  }
  const double scale = cross / own;
  if (!(scale > 0) || !std::isfinite(scale)) {
    Fail(where, "the model's force on the reference press points away from the paper's model's; no positive "
                "scale matches them");
  }
  return scale;
}

std::unique_ptr<ContactModel> ApplyStiffnessRule(std::unique_ptr<ContactModel> model, std::string_view name,
                                                 const Scene& scene, SceneAssets& assets) {
  if (scene.model.stiffness == StiffnessRule::kOwn) return model;
  if (const ContactModelEntry* entry = FindContactModel(name); entry != nullptr && entry->stiffness_reference) return model;
  const double scale = MatchedStiffnessScale(*model, name, scene, assets);
  return std::make_unique<ScaledContactModel>(std::move(model), scale);
}

}  // namespace contactlab
