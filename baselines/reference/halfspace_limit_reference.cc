#include "baselines/reference/halfspace_limit_reference.h"

#include <cmath>

#include "baselines/reference/analytic_references.h"
#include "geometry/aabb.h"
#include "util/error.h"

namespace contactlab {

HalfspaceLimitReference::HalfspaceLimitReference(std::shared_ptr<const TriangleMesh> mesh_A,
                                                 std::shared_ptr<const TriangleMesh> mesh_B,
                                                 const PenaltyParams& penalty)
    : mesh_A_(std::move(mesh_A)), penalty_(penalty) {
  if (!mesh_A_ || mesh_A_->vertices.empty() || !mesh_B || mesh_B->vertices.empty()) {
    Fail("eq2-halfspace reference", "needs two non-empty meshes");
  }
  if (penalty_.L <= 0) penalty_.L = PenaltyParams::kDefaultManyPointThreshold;
  const Aabb box = mesh_B->Bounds();
  const double tol = 1e-9 * box.size().norm();
  for (const Eigen::Vector3d& v : mesh_B->vertices) {
    bool on_face = false;
    for (int a = 0; a < 3; ++a) {
      on_face = on_face || std::abs(v[a] - box.min[a]) <= tol || std::abs(v[a] - box.max[a]) <= tol;
    }
    if (!on_face) {
      Fail("eq2-halfspace reference", "body B ('" + mesh_B->name +
                                          "') is not an axis-aligned box: a vertex lies inside its bounding box");
    }
  }
  top_B_ = box.max.z();
  sphere_ = mesh_A_->name.rfind("sphere:", 0) == 0;
  if (sphere_) {
    const Aabb a = mesh_A_->Bounds();
    centre_A_ = 0.5 * (a.min + a.max);
    for (const Eigen::Vector3d& v : mesh_A_->vertices) radius_A_ = std::max(radius_A_, (v - centre_A_).norm());
  }
}

ContactResult HalfspaceLimitReference::Evaluate(const ContactQuery& query) {
  const Eigen::Vector3d q_W = query.X_WB * Eigen::Vector3d(0, 0, top_B_);
  const Eigen::Vector3d n_W = query.X_WB.rotation * Eigen::Vector3d::UnitZ();
  const int L = penalty_.L;
  ForceLimit limit;
  if (sphere_) {
    const Eigen::Vector3d c_WA = query.X_WA * centre_A_;
    if (n_W.dot(c_WA - q_W) > -radius_A_) {
      limit = SphereHalfspaceLimit(c_WA, radius_A_, q_W, n_W, query.X_WB.translation, penalty_.k_C, L);
    }
  } else {
    limit = PolyhedronHalfspaceLimit(*mesh_A_, query.X_WA, q_W, n_W, query.X_WB.translation, penalty_.k_C, L);
  }
  ContactResult r;
  r.on_B = limit.on_B;
  r.stats.max_penetration = limit.max_penetration;
  r.stats.points_in_contact = limit.area_inside > 0 ? 1 : 0;
  return r;
}

}  // namespace contactlab
