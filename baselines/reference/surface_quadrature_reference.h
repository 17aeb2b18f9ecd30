// The reference of the paper's model: the limit of its force as the pointshell gets dense,
// eq. (2) of Barbič & James 2008 (sec. 2.1),
//     F_limit = k_C L ∫_S d(x) N(x) dS / ∫_S dS,
// computed by dense quadrature over the mesh of body A (each triangle cut into n^2 similar
// sub-triangles of edge <= target_edge, one sample at each centroid, weight = its area,
// N = A's inward face normal) with EXACT signed distances to the mesh of body B (CGAL AABB
// tree closest point; sign by CGAL::Side_of_triangle_mesh), not an interpolated grid.
//
// Registered as contact model "reference" for offline comparisons. It is slow (a CGAL inside
// test per sample in B's bounding box) and allocates in CGAL; it never runs in a haptic cycle.
// Built only with CONTACTLAB_WITH_CGAL (CONTACTLAB_HAVE_CGAL defined).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "baselines/reference/analytic_references.h"
#include "contact/contact_model.h"
#include "contact/penalty_params.h"
#include "geometry/triangle_mesh.h"

namespace contactlab {

struct QuadratureReferenceParams {
  PenaltyParams penalty;       // as the paper's model; L must be > 0 (the limit is k_C L times an area average)
  double target_edge = 5e-4;   // metres, longest sub-triangle edge on A
};

class QuadratureReference final : public ContactModel {
 public:
  // MESH_A: any triangle mesh (oriented outward). MESH_B: closed. Throws Error for an empty
  // or (B) open mesh, L <= 0, a non-positive target_edge, or more than 50 million samples.
  QuadratureReference(std::shared_ptr<const TriangleMesh> mesh_A, std::shared_ptr<const TriangleMesh> mesh_B,
                      const QuadratureReferenceParams& params);
  ~QuadratureReference() override;

  std::string_view name() const override { return "reference"; }
  // The eq. (2) limit at the query's poses (wrench on B about B's origin, world frame) and
  // its halfspace gradient (each sample a halfspace with its normal, weighted like its
  // force). stats: points_in_contact = samples inside B, nodes_visited = samples examined,
  // max_penetration = largest -d. Offline only: allocates inside CGAL.
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override {}

  // The limit alone.
  ForceLimit Limit(const Pose& X_WA, const Pose& X_WB) const;
  // Exact signed distance to B's mesh at a point in B's frame (metres, negative inside).
  double SignedDistance(const Eigen::Vector3d& p_B) const;
  int num_samples() const { return static_cast<int>(weight_.size()); }

 private:
  ContactResult Compute(const Pose& X_WA, const Pose& X_WB, double* area_inside) const;

  struct Distance;  // CGAL tree and inside test of B
  std::unique_ptr<Distance> distance_;
  QuadratureReferenceParams params_;
  std::shared_ptr<const TriangleMesh> mesh_A_, mesh_B_;
  std::vector<Eigen::Vector3d> point_A_;   // (#S) sample positions, A's frame
  std::vector<Eigen::Vector3d> normal_A_;  // (#S) inward unit normals, A's frame
  std::vector<double> weight_;             // (#S) areas, m^2
  Eigen::Vector3d box_min_B_, box_max_B_;  // B's bounding box, B's frame
};

}  // namespace contactlab
