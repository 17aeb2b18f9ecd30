// Closed-form and 1-D-quadrature limits of the paper's contact force as the pointshell gets
// dense (Barbič & James 2008, sec. 2.1 and eq. (2)):
//     F_limit = k_C L ∫_S d(x) N(x) dS / ∫_S dS,
// S the part of the pointshell body A's surface inside the field body B (where d < 0), N A's
// inward unit normal, d the exact signed distance to B. The L / l stiffness scaling turns the
// sum over l points into k_C L times their mean, hence the area average. The result is the
// wrench on B (world frame, torque about B's origin p_WB). These are references for tests
// and characterization; they are not contact models.
#pragma once

#include <Eigen/Core>

#include "contact/contact_model.h"
#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"

namespace contactlab {

// A limit wrench and the area of S it averages over (m^2; 0 when nothing penetrates).
struct ForceLimit {
  Wrench on_B;
  double area_inside = 0;
  double max_penetration = 0;  // largest -d over S, metres
};

// |F_limit| for a sphere of radius R (m) whose centre is at height H (m, |H| < R) above a
// halfspace: k_C L R (R/3 - H/2 + H^3/(6 R^2)) / (R - H) = k_C L d (3R - d) / (6R) with the
// depth d = R - H (computed in that form, stable as d -> 0). Throws Error unless R > 0 and
// -R < H < R.
double SphereHalfspaceForceMagnitude(double R, double H, double k_C, int L);

// Sphere A (centre c_WA, radius R) against the halfspace B = {x : n·(x - q_W) < 0} (n unit,
// pointing out of B), B's origin at p_WB. The force on B is -|F| n, along the line through
// the centre. Zero when the sphere does not reach the plane. Throws Error as above when the
// centre is below the plane (H <= -R is outside the formula) or n is not unit length.
ForceLimit SphereHalfspaceLimit(const Eigen::Vector3d& c_WA, double R, const Eigen::Vector3d& q_W,
                                const Eigen::Vector3d& n_W, const Eigen::Vector3d& p_WB, double k_C, int L);

// Sphere A (centre c_WA, radius R_A) against sphere B (centre c_WB, radius R_B), B's origin
// at p_WB: 1-D quadrature (composite Simpson, SAMPLES intervals) over the polar angle of A's
// cap inside B, with the exact distance d = |x - c_WB| - R_B. Throws Error for non-positive
// radii or SAMPLES < 2, or when A's centre lies inside B (the cap would not be a cap).
ForceLimit SphereSphereLimit(const Eigen::Vector3d& c_WA, double R_A, const Eigen::Vector3d& c_WB, double R_B,
                             const Eigen::Vector3d& p_WB, double k_C, int L, int samples = 20000);

// Any closed polyhedron A (MESH_A in its body frame, outward-oriented triangles; e.g. a box,
// tilted by X_WA) against the halfspace B = {x : n·(x - q_W) < 0}: exact, by clipping every
// triangle at the plane and integrating the linear d N (and the quadratic torque integrand)
// over the submerged polygons. Throws Error when n is not unit length.
ForceLimit PolyhedronHalfspaceLimit(const TriangleMesh& mesh_A, const Pose& X_WA, const Eigen::Vector3d& q_W,
                                    const Eigen::Vector3d& n_W, const Eigen::Vector3d& p_WB, double k_C, int L);

}  // namespace contactlab
