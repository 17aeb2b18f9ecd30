#include "scene/contact_placement.h"

#include <cmath>

#include "contact/model_registry.h"
#include "util/error.h"

namespace contactlab {

Placement PlaceAtDepth(ContactModel& model, const Pose& X_WA_start, const Pose& X_WB, Eigen::Vector3d direction,
                       double depth, double max_travel) {
  if (!(depth > 0) || !(max_travel > 0) || direction.norm() == 0) {
    Fail("PlaceAtDepth", "needs depth > 0, max_travel > 0 and a non-zero direction");
  }
  direction.normalize();
  auto penetration = [&](double s) {
    ContactQuery q;
    q.X_WA = X_WA_start;
    q.X_WA.translation += s * direction;
    q.X_WB = X_WB;
    model.Reset();
    return model.Evaluate(q).stats.max_penetration;
  };
  Placement out;
  const double step = depth / 4;
  double lo = 0, hi = -1;
  for (double s = 0; s <= max_travel; s += step) {
    if (penetration(s) >= depth) {
      hi = s;
      break;
    }
    lo = s;
  }
  if (hi < 0) {
    out.X_WA = X_WA_start;
    return out;
  }
  while (hi - lo > 0.01 * depth) {
    const double mid = 0.5 * (lo + hi);
    (penetration(mid) >= depth ? hi : lo) = mid;
  }
  out.X_WA = X_WA_start;
  out.X_WA.translation += hi * direction;
  out.travel = hi;
  out.depth = penetration(hi);
  out.found = true;
  return out;
}

Pose TouchAlong(const Scene& scene, SceneAssets& assets, bool move_B, const Pose& X_WA, const Pose& X_WB,
                const Eigen::Vector3d& direction, double depth, const std::string& where) {
  const Eigen::Vector3d dir = direction.normalized();
  // The registry's depth probe (ContactModelEntry::make_depth_probe), from the scene's parameters.
  const ContactModelEntry& prober = SoleContactModelWith(
      [](const ContactModelEntry& e) { return bool(e.make_depth_probe); }, "a depth probe", where);
  const std::unique_ptr<ContactModel> probe =
      prober.make_depth_probe(ContactModelInputs{assets.A, assets.B, scene.model, scene.model_params});
  // Moving B by s along DIR is moving A by s against it; start a full reach back.
  const Eigen::Vector3d a_dir = move_B ? Eigen::Vector3d(-dir) : dir;
  const double reach = assets.A.mesh()->Bounds().size().norm() + assets.B.mesh()->Bounds().size().norm();
  Pose far = X_WA;
  far.translation -= reach * a_dir;
  const Placement placed = PlaceAtDepth(*probe, far, X_WB, a_dir, depth, 2 * reach);
  if (!placed.found) Fail(where, "the bodies never touch moving along the direction");
  if (!move_B) return placed.X_WA;
  Pose moved = X_WB;
  moved.translation += (placed.travel - reach) * dir;
  return moved;
}

}  // namespace contactlab
