// A model-independent reference of "which way should the contact push": the exact volume of
// the overlap of two closed meshes (CGAL corefinement, Polygon_mesh_processing::
// corefine_and_compute_intersection on Surface_mesh, exact predicates) and its
// central-difference gradient with respect to B's pose. -∇V (translation part) is the
// direction of steepest overlap decrease, the reference direction of the force on B; it
// differs from the eq. (2) limit (Barbič & James 2008, sec. 2.1) only in weighting the
// penetrating surface by 1 instead of by its depth. Built only with CONTACTLAB_WITH_CGAL.
#pragma once

#include <memory>

#include "contact/contact_model.h"
#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"

namespace contactlab {

class PenetrationVolume {
 public:
  // MESH_A, MESH_B: closed triangle meshes in their body frames (metres); they should not
  // self-intersect (corefinement's precondition). Throws Error naming the mesh when one is
  // empty or open.
  PenetrationVolume(const TriangleMesh& mesh_A, const TriangleMesh& mesh_B);
  ~PenetrationVolume();

  // Volume of A ∩ B at the given poses, m^3. Throws Error when corefinement fails (e.g. a
  // self-intersecting input).
  double Volume(const Pose& X_WA, const Pose& X_WB) const;

  // dV / d(dx, dθ) of B for the perturbation X_WB -> (exp([dθ]) R_WB, p_WB + dx) (the
  // convention of contact_model.h: rotation about B's origin, world axes), by central
  // differences with steps STEP (metres) and ANGLE_STEP (radians): 12 volumes, or 6 and a
  // zero rotation part without WITH_ROTATION. Units m^2 (translation) and m^3 / rad
  // (rotation). Throws like Volume.
  Vector6d Gradient(const Pose& X_WA, const Pose& X_WB, double step, double angle_step,
                    bool with_rotation = true) const;

  // True when the mesh self-intersects (CGAL); slow, for checking inputs.
  static bool SelfIntersects(const TriangleMesh& mesh);

 private:
  struct Meshes;
  std::unique_ptr<Meshes> meshes_;
};

}  // namespace contactlab
