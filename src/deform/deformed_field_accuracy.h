// How well a deformed distance field (Barbič & James 2008, sec. 4.2) matches the exact deformed
// distance, as in the paper's Fig. 10: a pose of the body under point loads (e.g. two legs
// pulled apart), the exact distance to the body's surface mesh deformed by the same q, and the
// error of the proxy approximation in the contact band |d| <= band, plus the volume of
// spurious "inside" the approximation adds away from the body (the mirroring of Fig. 10(b)).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "deform/deformed_distance_field.h"
#include "deform/embedded_points.h"
#include "deform/reduced_forces.h"
#include "deform/tet_mesh.h"
#include "geometry/triangle_mesh.h"
#include "sdf/mesh_signed_distance.h"

namespace contactlab {

// A body's surface mesh with its vertices embedded in the simulation mesh: the exact deformed
// surface for any q.
class EmbeddedSurface {
 public:
  // REST: the surface mesh (body frame, metres); TETS and U (3#V x r): the reduced model.
  EmbeddedSurface(const TriangleMesh& rest, const TetMesh& tets, const Eigen::MatrixXd& U);
  const TriangleMesh& rest() const { return rest_; }
  // The surface at reduced coordinates Q (r entries).
  TriangleMesh Deformed(const Eigen::VectorXd& q) const;
  // Largest vertex displacement |U_v q| over the surface, metres.
  double MaxDisplacement(const Eigen::VectorXd& q) const;

 private:
  TriangleMesh rest_;
  EmbeddedPoints vertices_;
};

// A point force at a material point: AT in the rest body frame (metres), FORCE a direction
// (its length sets the loads' ratios; they are scaled together).
struct PointLoad {
  Eigen::Vector3d at = Eigen::Vector3d::Zero();
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
};

// The static equilibrium q of FORCES (the reduced model's internal forces) under LOADS applied
// through the points' interpolated bases (EmbeddedPoints::AddPointForce on TETS, U), with the
// loads scaled together so that SURFACE's largest displacement is TARGET metres (within 0.1%;
// a linear model in one solve, reduced StVK by a few rescaled solves). Throws Error naming
// WHERE when there is no load, the loads have no effect on the modes, or TARGET <= 0.
Eigen::VectorXd SolveScaledPointLoadPose(const ReducedInternalForces& forces, const TetMesh& tets,
                                         const Eigen::MatrixXd& U, const std::vector<PointLoad>& loads,
                                         const EmbeddedSurface& surface, double target, const std::string& where);

struct BandErrorOptions {
  double band = 0;                       // metres: the contact band |d_exact| <= band (> 0)
  int points = 2000;                     // band points to measure
  std::uint64_t seed = 1;
  std::int64_t max_candidates_per_point = 2000;  // gives up after points * this samples
};

// Errors are approximate minus exact, metres.
struct BandError {
  int points = 0;                 // band points measured
  std::int64_t candidates = 0;    // uniform samples of the box drawn to find them
  double box_volume = 0;          // m^3, the sampled box
  double rms = 0, max = 0, mean = 0;
  // Volume (m^3) of the sampled box where the approximation says inside (d < 0) but the exact
  // distance is outside the band (d > band): geometry that is not there, e.g. mirrored parts.
  double false_inside_volume = 0;
  std::vector<float> band_points;  // the band points, 3 floats each (for timing queries)
  std::vector<double> exact;       // their exact distances
};

// Samples points uniformly in the bounding box of EXACT's mesh grown by OPTIONS.band until
// OPTIONS.points fall in the band, and compares FIELD at STATE with EXACT there. Throws Error
// naming WHERE when the band points cannot be found within the candidate limit.
BandError MeasureBandError(const DeformedDistanceField& field, const DeformedFieldState& state,
                           const MeshSignedDistance& exact, const BandErrorOptions& options, const std::string& where);

}  // namespace contactlab
