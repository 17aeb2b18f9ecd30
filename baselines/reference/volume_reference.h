// The model-independent reference of issue 15's comparisons: the volume law on the exact
// overlap volume V of the two meshes (PenetrationVolume: CGAL corefinement),
//     F_B = -k_V ∇_x V,   τ_B = -k_V ∇_θ V,
// gradients with respect to B's pose (contact_model.h's convention), by central differences.
// Its direction, -∇V, is the direction that reduces the overlap fastest and belongs to no
// model's force law; the closest published relative is the penetration-volume force of Inner
// Sphere Trees (Weller & Zachmann 2009). Its magnitude is a law of its own: k_V |∇V| grows with
// the area of the overlap's boundary, where the paper's force (eq. 2, L/l rule) grows with the
// mean depth and FCL's and Bullet's with their contact counts, so magnitudes are compared after
// a per-model stiffness calibration (experiment/studies/contact/metrics.h, ErrorAgainstReference).
//
// k_V = k_C L / sqrt(area of A's surface) (N/m^2): a flat face of area A_c pressed in feels
// k_V A_c at every depth, and scaling the whole scene by s scales the force by s, as in the
// penalty laws. Registered as "volume", a reference only (not listed among the models
// compared); offline: 12 corefinements per query, milliseconds to seconds.
#pragma once

#include <memory>

#include "baselines/reference/penetration_volume.h"
#include "contact/contact_model.h"
#include "contact/penalty_params.h"
#include "geometry/triangle_mesh.h"

namespace contactlab {

class VolumeReference final : public ContactModel {
 public:
  // MESH_A, MESH_B: closed meshes (body frames). K_C, L: the scene's penalty (L <= 0: the
  // default L). Throws Error for an empty or open mesh.
  VolumeReference(std::shared_ptr<const TriangleMesh> mesh_A, std::shared_ptr<const TriangleMesh> mesh_B,
                  const PenaltyParams& penalty);
  ~VolumeReference() override;

  std::string_view name() const override { return "volume"; }
  // -k_V ∇V at the query's poses (zero when the bounding boxes do not overlap). stats:
  // points_in_contact = 1 when V > 0; K_B is left zero. Throws Error when corefinement fails.
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override {}

  double k_V() const { return k_V_; }
  // Finite-difference steps: STEP = 1e-3 of B's bounding-box diagonal, ANGLE_STEP = 1e-3 rad.
  double step() const { return step_; }

 private:
  std::shared_ptr<const TriangleMesh> mesh_A_, mesh_B_;
  std::unique_ptr<PenetrationVolume> volume_;
  double k_V_ = 0, step_ = 0;
};

}  // namespace contactlab
