#include "baselines/reference/volume_reference.h"

#include <cmath>

#include "geometry/aabb.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr double kAngleStep = 1e-3;  // rad

Aabb WorldBox(const TriangleMesh& mesh, const Pose& X) {
  Aabb box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.Extend(X * v);
  return box;
}

}  // namespace

VolumeReference::VolumeReference(std::shared_ptr<const TriangleMesh> mesh_A, std::shared_ptr<const TriangleMesh> mesh_B,
                                 const PenaltyParams& penalty)
    : mesh_A_(std::move(mesh_A)), mesh_B_(std::move(mesh_B)) {
  if (!mesh_A_ || !mesh_B_ || mesh_A_->triangles.empty() || mesh_B_->triangles.empty()) {
    Fail("volume reference", "needs two non-empty closed meshes");
  }
  volume_ = std::make_unique<PenetrationVolume>(*mesh_A_, *mesh_B_);
  k_V_ = penalty.VolumeStiffness(mesh_A_->SurfaceArea());
  step_ = 1e-3 * mesh_B_->Bounds().size().norm();
}

VolumeReference::~VolumeReference() = default;

ContactResult VolumeReference::Evaluate(const ContactQuery& query) {
  ContactResult r;
  const Aabb a = WorldBox(*mesh_A_, query.X_WA), b = WorldBox(*mesh_B_, query.X_WB);
  // Apart by more than a finite-difference step: no overlap at any perturbed pose either.
  if ((a.min.array() > b.max.array() + step_).any() || (b.min.array() > a.max.array() + step_).any()) return r;
  const Vector6d g = volume_->Gradient(query.X_WA, query.X_WB, step_, kAngleStep, /*with_rotation=*/true);
  r.on_B.force = -k_V_ * g.head<3>();
  r.on_B.torque = -k_V_ * g.tail<3>();
  r.stats.points_in_contact = g.head<3>().norm() > 0 ? 1 : 0;
  r.stats.nodes_visited = 12;
  return r;
}

}  // namespace contactlab
