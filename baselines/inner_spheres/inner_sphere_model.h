// "inner-spheres": penetration-volume contact of Inner Sphere Trees (Weller & Zachmann, RSS
// 2009; for 6-DoF haptics, Weller, Sagardia, Mainzer, Hulin, Zachmann & Preusche, 2010). Both
// bodies are filled with non-overlapping inner spheres (sphere_packing.h) under a hierarchy
// (sphere_tree.h); the penetration volume V is the sum of the lens volumes of every pair of
// overlapping spheres, one of each body, and
//     F_B = -k_V ∇_x V,   τ_B = -k_V ∇_θ V   (gradients in B's pose, contact_model.h),
// the volume law of the "volume" reference (k_V = k_C L / sqrt(area of A's surface)), so the
// two compare directly. A pair's lens shrinks at the rate of its intersection disc's area π a²
// as the centres part, so each pair pushes B along the line of centres with k_V π a², about
// A's sphere's centre (torque).
//
// K_B (the static virtual coupling's gradient; Weller & Zachmann give none) is one of three;
// the wrench is the same under all, so the choice is the coupling's, not the method's.
//  - kExact: the exact derivative of the wrench (-k_V times the Hessian of V). The summed lens
//    volume is not convex: a disc turns with its line of centres (+k_V π a²/d across it), a
//    pair softens once its smaller sphere is more than about half inside the larger (a² falls
//    as the centres close: the lens saturates at the smaller ball; deeper, a sphere sits in
//    the gaps between the other body's spheres) and the force turns under rotation. These give
//    K_B positive eigenvalues of up to ~10^4 N/m on the closed-loop scenes; where they exceed
//    a soft k_vc, the coupling's Newton step (K_VC + K_B) delta = -W climbs the energy instead
//    of descending it and the loop puts energy into the hand (docs/results-models.md).
//  - kProjected (default): the symmetric part of the exact derivative with its positive
//    eigenvalues set to zero: negative semidefinite, and equal to the exact one where that is.
//  - kHalfspace: each pair as the sec. 5 halfspace rule of the paper's model treats a point, a
//    spring along its line of centres, K_pair = -k_n w w^T with w = (u, a x u) and
//    k_n = k_V π max(0, -d(a²)/dd) >= 0: negative semidefinite, without the terms above.
//
// The traversal descends both trees breadth first, level by level, splitting the larger of two
// overlapping bounding spheres. A query's node budget (graceful degradation, as in the paper's
// model) stops it: each overlapping pair not yet resolved then counts as the lens of its two
// proxy spheres (each a subtree's volume at its centroid). Stats: points_in_contact = sphere
// pairs overlapping, nodes_visited = pairs tested, level_rendered = levels completed before the
// budget ran out, degraded = the levels the traversal went on past it (at least 1 when the
// budget or the pair buffer cut it), max_penetration = the largest overlap depth r_a + r_b - d
// of a pair.
// Contacts (KeepContacts / LatestContacts): the overlapping sphere pairs, one per pair counted
// (as many as stats.points_in_contact, a pair of proxy spheres included when the budget cut the
// traversal): the centre of the overlap (the midpoint, on the line of centres, of the segment
// both balls cover), the line of centres from A's sphere to B's (the direction of the pair's
// force on B; B's frame +z when the centres coincide) and the overlap depth r_a + r_b - d.
// Allocation-free and exception-free in Evaluate; rigid bodies only.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "baselines/inner_spheres/sphere_packing.h"
#include "baselines/inner_spheres/sphere_tree.h"
#include "contact/contact_model.h"
#include "contact/contact_recorder.h"
#include "contact/volume_fill.h"

namespace contactlab {

// Which K_B the model reports (above).
enum class SphereStiffness { kHalfspace, kExact, kProjected };

class InnerSphereModel final : public ContactModel, public VolumeFill {
 public:
  // K_V: the volume stiffness, N/m^2. STIFFNESS: the K_B reported. MAX_PAIRS: pairs held per
  // traversal level (beyond: the pair counts through its proxies). Throws Error for an empty
  // packing or k_V <= 0.
  InnerSphereModel(std::shared_ptr<const SpherePacking> A, std::shared_ptr<const SpherePacking> B, double k_V,
                   SphereStiffness stiffness = SphereStiffness::kProjected, std::int64_t max_pairs = 1 << 20);

  std::string_view name() const override { return "inner-spheres"; }
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override {}
  // The overlapping sphere pairs (see the top of this file), recorded during Evaluate.
  bool KeepContacts(int max_contacts) override {
    contacts_.Keep(max_contacts);
    return true;
  }
  void LatestContacts(ContactList* out) const override { contacts_.Fill(X_WB_contacts_, 1.0, out); }
  // The fraction of each body's volume its packing fills.
  double fill_A() const override { return A_->Coverage(); }
  double fill_B() const override { return B_->Coverage(); }

  double k_V() const { return k_V_; }
  SphereStiffness stiffness() const { return stiffness_; }
  // The penetration volume V of the latest Evaluate, m^3.
  double volume() const { return volume_; }
  const SpherePacking& packing_A() const { return *A_; }
  const SpherePacking& packing_B() const { return *B_; }

 private:
  struct Pair {
    std::int32_t a, b;
  };
  std::shared_ptr<const SpherePacking> A_, B_;
  SphereTree tree_A_, tree_B_;
  double k_V_ = 0;
  SphereStiffness stiffness_ = SphereStiffness::kProjected;
  double volume_ = 0;
  std::vector<Pair> level_, next_;
  ContactRecorder contacts_;  // the latest Evaluate's pairs, B's frame, when kept
  Pose X_WB_contacts_;        // and B's pose then
};

}  // namespace contactlab
