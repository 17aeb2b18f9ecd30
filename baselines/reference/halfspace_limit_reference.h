// The eq. (2) limit in closed form (analytic_references.h) as a reference model, for
// convergence studies of pointshell-type models: body B is a box pressed from above, its top
// face (+z of B's frame, at the top of B's bounding box) taken as a halfspace; body A is a
// procedural sphere (mesh named "sphere:...": the exact sphere through its vertices,
// SphereHalfspaceLimit, not the icosphere) or any closed polyhedron (PolyhedronHalfspaceLimit,
// exact for a box). Registered as the reference-only "eq2-halfspace". It is the pointshell
// family's own continuum limit, named for what it is: a model with another force law is not
// wrong for departing from it (compare those against "volume").
#pragma once

#include <memory>

#include "contact/contact_model.h"
#include "contact/penalty_params.h"
#include "geometry/triangle_mesh.h"

namespace contactlab {

class HalfspaceLimitReference final : public ContactModel {
 public:
  // Throws Error when B is not an axis-aligned box (8 distinct corner values per axis are
  // checked: every vertex lies on a face of its bounding box) or A's mesh is empty.
  HalfspaceLimitReference(std::shared_ptr<const TriangleMesh> mesh_A, std::shared_ptr<const TriangleMesh> mesh_B,
                          const PenaltyParams& penalty);

  std::string_view name() const override { return "eq2-halfspace"; }
  // The limit's wrench on B; stats.max_penetration its deepest point, points_in_contact 1 when
  // anything penetrates. K_B is left zero.
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override {}

 private:
  std::shared_ptr<const TriangleMesh> mesh_A_;
  PenaltyParams penalty_;
  bool sphere_ = false;
  Eigen::Vector3d centre_A_ = Eigen::Vector3d::Zero();  // sphere centre, A's frame
  double radius_A_ = 0;
  double top_B_ = 0;  // z of B's top face, B's frame
};

}  // namespace contactlab
