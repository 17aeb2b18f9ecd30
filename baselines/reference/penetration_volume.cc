// Exact overlap volume by CGAL corefinement and its finite-difference gradient (see
// penetration_volume.h).
#include "baselines/reference/penetration_volume.h"

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <string>

#include "baselines/reference/cgal_mesh.h"
#include "geometry/pose.h"
#include "util/error.h"

namespace contactlab {

namespace PMP = CGAL::Polygon_mesh_processing;

struct PenetrationVolume::Meshes {
  cgal::Mesh A, B;  // body frames
};

PenetrationVolume::PenetrationVolume(const TriangleMesh& mesh_A, const TriangleMesh& mesh_B)
    : meshes_(std::make_unique<Meshes>()) {
  meshes_->A = cgal::ToSurfaceMesh(mesh_A, "penetration volume (body A)", /*require_closed=*/true);
  meshes_->B = cgal::ToSurfaceMesh(mesh_B, "penetration volume (body B)", /*require_closed=*/true);
}

PenetrationVolume::~PenetrationVolume() = default;

double PenetrationVolume::Volume(const Pose& X_WA, const Pose& X_WB) const {
  // Corefinement modifies its inputs: work on transformed copies.
  cgal::Mesh a = cgal::Transformed(meshes_->A, X_WA);
  cgal::Mesh b = cgal::Transformed(meshes_->B, X_WB);
  cgal::Mesh out;
  bool ok = false;
  try {
    ok = PMP::corefine_and_compute_intersection(a, b, out);
  } catch (const std::exception& e) {
    Fail("penetration volume", std::string("CGAL corefinement failed: ") + e.what());
  }
  if (!ok) Fail("penetration volume", "CGAL corefinement could not compute the intersection (self-intersecting input?)");
  if (out.number_of_faces() == 0) return 0;
  return PMP::volume(out);
}

Vector6d PenetrationVolume::Gradient(const Pose& X_WA, const Pose& X_WB, double step, double angle_step,
                                     bool with_rotation) const {
  Vector6d g = Vector6d::Zero();
  for (int i = 0; i < (with_rotation ? 6 : 3); ++i) {
    double v[2];
    for (int s = 0; s < 2; ++s) {
      const double sign = s == 0 ? 1 : -1;
      Pose X = X_WB;
      if (i < 3) {
        X.translation[i] += sign * step;
      } else {
        Eigen::Vector3d w = Eigen::Vector3d::Zero();
        w[i - 3] = sign * angle_step;
        X.rotation = (RotationFromVector(w) * X_WB.rotation).normalized();
      }
      v[s] = Volume(X_WA, X);
    }
    g[i] = (v[0] - v[1]) / (2 * (i < 3 ? step : angle_step));
  }
  return g;
}

bool PenetrationVolume::SelfIntersects(const TriangleMesh& mesh) {
  const cgal::Mesh m = cgal::ToSurfaceMesh(mesh, "self-intersection test", /*require_closed=*/false);
  return PMP::does_self_intersect(m);
}

}  // namespace contactlab
