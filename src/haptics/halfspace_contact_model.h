// An analytic penalty contact model for closed-loop tests, benchmarks and demos of the haptic
// display (Barbič & James 2008, sec. 5: "treating each contact point as undergoing contact
// with an infinite halfspace"): sample points on body B against the halfspace z <= 0 of A.
#pragma once

#include <Eigen/Core>
#include <string_view>
#include <vector>

#include "contact/contact_model.h"

namespace contactlab {

// Body A is the halfspace {z_A <= 0} (outward normal +z_A); body B carries sample points.
// Each point Q below the plane (penetration d = n·(p_WQ - p_WA) < 0) pushes B with force
// -k d n at Q. Returns the wrench on B about B's origin and its exact gradient K_B (the
// convention of contact_model.h). Evaluate allocates nothing and throws nothing.
class HalfspaceContactModel final : public ContactModel {
 public:
  // P_BQ: 3 x N sample points in B's frame, metres; K: stiffness per point, N/m (> 0).
  // Throws Error when P_BQ is empty or non-finite or K <= 0.
  HalfspaceContactModel(const Eigen::Matrix3Xd& p_BQ, double k);

  std::string_view name() const override { return "halfspace"; }
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override {}

  const Eigen::Matrix3Xd& points() const { return p_BQ_; }
  double stiffness() const { return k_; }

 private:
  Eigen::Matrix3Xd p_BQ_;  // 3 x N
  double k_;
};

// The corners and an n x n grid on each face of an axis-aligned box of half extents H centred
// at B's origin: a convenient point set for the halfspace model. N >= 2.
Eigen::Matrix3Xd MakeBoxSamplePoints(const Eigen::Vector3d& half_extents, int n);

}  // namespace contactlab
