#include "scene/contact_placement.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

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
  // 1. A coarse march, kPlacementCoarseSteps over the travel, to the first step at DEPTH.
  const double coarse = max_travel / kPlacementCoarseSteps;
  double coarse_lo = -1, coarse_hi = -1;
  for (int j = 0; j <= kPlacementCoarseSteps; ++j) {
    const double s = std::min(max_travel, j * coarse);
    if (penetration(s) >= depth) {
      coarse_hi = s;
      break;
    }
    coarse_lo = s;
  }
  if (coarse_hi < 0) {
    out.X_WA = X_WA_start;
    return out;
  }
  // 2. The fine march from 0 in steps of DEPTH / 4 (at most kPlacementFineSteps of them
  // between two coarse steps), probing only from the last coarse step short of DEPTH on.
  const double step = std::max(depth / 4, coarse / kPlacementFineSteps);
  double lo = 0, hi = -1;
  for (double s = 0; s <= max_travel; s += step) {
    if (s >= coarse_lo && penetration(s) >= depth) {
      hi = s;
      break;
    }
    lo = s;
    if (s >= coarse_hi) break;
  }
  if (hi < 0) {  // no fine step up to the coarse one reached DEPTH: between the coarse ones
    lo = std::max(0.0, coarse_lo);
    hi = coarse_hi;
  }
  // Bisection to 1 % of DEPTH, or until no number lies between the ends.
  for (int i = 0; i < kPlacementMaxBisections && hi - lo > 0.01 * depth; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
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
