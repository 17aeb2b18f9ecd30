// The wrench of the pressure over the contact surface, polygon by polygon: the pressure is
// linear on each polygon, so F = ∫ p n dA and τ = ∫ x × p n dA are exact (Elandt et al. 2019,
// eq. (2)-(3); the lattice body's frame, about its origin).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "baselines/pressure_field/polygon_clip.h"
#include "baselines/pressure_field/pressure_law.h"
#include "contact/contact_recorder.h"

namespace contactlab {

// What the surface adds up to, in the lattice body's frame.
struct PressureSums {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // N
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // N m, about the lattice body's origin
  double area = 0;                                   // m^2
  double max_penetration = 0;                        // largest -(phi_M + phi_L), metres
};

// Where the integrated triangles are kept for display: their corners and the pressure at each,
// up to CAPACITY triangles (the vectors' capacity is reserved beforehand; nothing allocates).
// CONTACTS (null: not kept): each polygon as one contact (IntegratePolygon).
struct SurfaceRecord {
  std::vector<Eigen::Vector3f>* corners;
  std::vector<float>* pressure;
  int capacity;
  ContactRecorder* contacts = nullptr;
};

// Adds the wrench of the pressure over the convex polygon POLY (M >= 3 vertices, in order) to
// SUMS, with its normal turned TOWARD decreasing gap, and its area to *AREA. RECORD (null: not
// kept) receives its fan triangles while there is room, and its contacts (when kept) the
// polygon as one contact: its centroid, its normal n, the depth -(phi_M + phi_L) at the
// centroid (the local overlap of the two bodies), its area and its mean pressure, so that
// area * pressure * n is the polygon's force exactly. A polygon of zero area is not kept.
// Returns the polygon's orientation: +1 when its vertex order turns its normal TOWARD, else -1.
double IntegratePolygon(const PolyVertex* poly, int m, const Eigen::Vector3d& toward, const PressureLaw& law,
                      PressureSums* sums, double* area, SurfaceRecord* record);

}  // namespace contactlab
