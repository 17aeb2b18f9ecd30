// "pressure-field": hydroelastic contact (Elandt, Drumwright, Sherman & Ruina, "A pressure
// field model for fast, robust approximation of net contact force and moment between nominally
// rigid objects", IROS 2019; Drake's compliant contact), on ContactLab's signed distance fields.
//
// Each body carries a pressure field inside its volume, p_i(x) = E_i e_i(x), with the extent
// e_i = -phi_i(x) / max(-phi_i): 0 on the surface, 1 at the deepest sample of its field. The
// contact surface is where both bodies overlap and p_A = p_B; the wrench on B is
//     F_B = ∫ p n dA,   τ_B = ∫ (x - o_B) × p n dA,
// n the unit normal along -∇(p_A - p_B) (from A's side toward B's). A rigid body (infinite
// modulus) makes the contact surface its own boundary inside the other body, carrying the
// other's pressure.
//
// Extraction. A lattice of spacing h (`lattice` cells of the finer field; 1 by default), on the
// grid of the body with the finer field (B's on a tie) and in its frame, covers the overlap of the two fields' boxes. An octree over it culls
// every block whose centre proves, by the fields' Lipschitz bound, that the block lies outside a
// body or holds no zero of g = p_A - p_B (scaled to metres, pressure_law.h; -phi_A for a rigid A, phi_B for a rigid B). Surviving
// 4x4x4-cell blocks sample both fields at their 125 vertices; each cell is split into six
// tetrahedra (Kuhn), on which g and the fields are linear: the zero set of g is a triangle or
// quad, clipped to where the bodies overlap (phi_A + phi_B <= 0), and the pressure, linear on it, is
// integrated exactly. The integrand is symmetric in the two bodies (g changes sign, the normal
// flips, the pressures trade places), so exchanging the roles changes the result only through
// the lattice, and not at all when one field is finer: the wrench on A is then exactly the
// opposite, by Newton's third law, of the wrench on B.

// K_B is the exact derivative of this discretised wrench in B's pose, taken in the same pass:
// only M's field at the lattice's vertices depends on B's pose (the lattice is fixed in L), so
// the wrench is differentiated backwards through each polygon's integration, clip and cut down
// to a 6-vector sensitivity per lattice vertex (pressure_adjoints.h), which each block then
// multiplies once by the field's gradient along B's twist (pressure_stiffness.h). Surface that a
// motion would carry into a cell that holds none has zero measure and adds nothing.
// Stats: contact_area, patches (connected pieces, by cells sharing a face, edge or corner),
// max_penetration (largest -(phi_A + phi_B) on the surface: the local overlap), points_in_contact
// (cells carrying surface), nodes_visited (octree nodes and cells examined), degraded (the
// lattice doublings the budget forced).
//
// Time budget (graceful degradation): the query's node_budget counts lattice cells, the cells
// of the blocks that survive culling (each sampled at its vertices and tested). When they
// exceed it the lattice doubles its spacing, up to kMaxLatticeDoublings times (16x), until they
// fit: the surface is then cut from a coarser sampling of the same fields, a quarter of the
// cells for each doubling on a surface. The wrench keeps its meaning (pressures and areas are
// the same fields'), and loses the detail finer than the lattice, as pressure_lattice does.
// Contacts (KeepContacts / LatestContacts): the contact surface's polygons (one per tetrahedron
// of a cell the surface crosses, clipped to the overlap; several per cell, so more than
// stats.points_in_contact, which counts cells), each with its centroid (world), its unit normal
// (the direction of its force on B), the depth at its centroid -(phi_A + phi_B) (the local
// overlap of the two bodies, metres, as stats.max_penetration), its area (m^2) and its mean
// pressure (Pa): the force on B is the sum of area * pressure * normal over them.
// Allocation-free and exception-free in Evaluate; rigid bodies only.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "baselines/pressure_field/lattice_blocks.h"
#include "baselines/pressure_field/pressure_integration.h"
#include "baselines/pressure_field/pressure_law.h"
#include "baselines/pressure_field/pressure_adjoints.h"
#include "contact/contact_model.h"
#include "contact/contact_recorder.h"
#include "sdf/distance_field.h"

namespace contactlab {

struct PressureFieldSide {
  std::shared_ptr<const DistanceField> field;  // body frame; a closed body's field
  double modulus = 1e5;                        // E, Pa (ignored when rigid)
  bool rigid = false;
};

// The lattice doublings a time budget may force (pressure_field_model.h).
constexpr int kMaxLatticeDoublings = 4;

struct PressureFieldOptions {
  double lipschitz = 1;       // bound on |∇phi| of the fields, for culling
  int lattice = 1;            // lattice spacing, in cells of the finer field
  bool stiffness = true;      // compute K_B (the integration carries six derivatives)
  std::int64_t max_blocks = 1 << 16;  // 4^3-cell blocks kept per query (beyond: not rendered)
};

class PressureFieldModel final : public ContactModel {
 public:
  // Throws Error naming the model when a field is empty, both sides are rigid, or a field is a
  // soup's (its inside is an offset band, not a volume).
  PressureFieldModel(PressureFieldSide A, PressureFieldSide B, const PressureFieldOptions& options = {});

  std::string_view name() const override { return "pressure-field"; }
  ContactResult Evaluate(const ContactQuery& query) override;
  void Reset() override {}

  double depth_A() const { return depth_A_; }  // max(-phi_A), metres
  double depth_B() const { return depth_B_; }
  double spacing() const { return base_h_; }  // the lattice spacing (before any budget coarsens it)

  // The contact surface of the latest Evaluate: the triangles the wrench was integrated over,
  // clipped to both insides, with the pressure at each corner.
  bool KeepContactSurface(int max_triangles) override;
  void LatestContactSurface(ContactSurface* out) const override;
  // The contact surface's polygons as contacts (see the top of this file).
  bool KeepContacts(int max_contacts) override;
  void LatestContacts(ContactList* out) const override;

 private:
  // The wrench on the lattice body L (L's frame, about L's origin) from the blocks found, with
  // the other body M at X_LM; also the cells with surface and the surface record. D (null:
  // not wanted): the sums' derivatives along B's twist (L's frame), added.
  void Integrate(const Pose& X_LM, PressureSums* sums, Matrix6d* D);
  // Adds a cell's (CI, CJ, CK) corner sensitivities B to its block's vertices'.
  void AddCornerSensitivity(const CornerSensitivity& b, int ci, int cj, int ck);
  // The block's share of the sums' derivatives along B's twist (L's frame): each touched vertex's
  // sensitivity times the derivative of M's field there (the block's first vertex is X0).
  Matrix6d BlockStiffness(const Pose& X_LM, const Eigen::Vector3d& x0) const;
  // Finds the blocks that may hold surface with M at X_LM and samples L's field at them, on the
  // configured lattice or, when their cells exceed BUDGET (> 0), on one *DOUBLINGS times
  // coarser (at most kMaxLatticeDoublings); false when there is none.
  bool FindBlocks(const Pose& X_LM, std::int64_t budget, std::int64_t* nodes, int* doublings);
  // Fits the lattice of spacing h_ and culls its blocks; false when none may hold surface.
  // LIMIT > 0: stops once more than LIMIT blocks qualify (num_blocks_ = LIMIT + 1).
  bool CullLattice(const Pose& X_LM, std::int64_t limit, std::int64_t* nodes);
  int CountPatches();
  // The wrench on B (world, about B's origin) of SUMS, the lattice body's, at the poses.
  Wrench OnB(const PressureSums& sums, const Pose& X_WA, const Pose& X_WB) const;
  Pose LatticeToOther(const Pose& X_WA, const Pose& X_WB) const {
    return lattice_is_A_ ? X_WA.Inverse() * X_WB : X_WB.Inverse() * X_WA;
  }

  PressureFieldOptions options_;
  bool lattice_is_A_ = false;  // A's field is strictly finer
  PressureFieldSide L_, M_;    // the lattice body and the other
  double depth_A_ = 0, depth_B_ = 0;
  double base_h_ = 0, h_ = 0;  // the configured lattice spacing, and the latest query's
  // The two bodies' pressures and their gap p_M - p_L (up to a positive factor; a rigid side's
  // pressure counts as infinite inside it), whose zero set is the contact surface.
  PressureLaw law_;
  // The lattice of the latest query: origin (L's frame) and cells per axis.
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  Eigen::Vector3i cells_ = Eigen::Vector3i::Zero();
  // Linear cell index i + stride_j_ j + stride_k_ k, with a block's margin on each axis (a
  // block may reach past the last cell), for the cells with surface.
  std::int64_t stride_j_ = 0, stride_k_ = 0;
  // Surviving blocks: their first cell, and phi_L at their 125 vertices.
  std::vector<std::array<std::int32_t, 3>> blocks_;
  std::vector<float> block_phi_L_;
  // The current block's vertices' sensitivities (six each), at the vertices touched.
  std::vector<double> block_sensitivity_;
  VertexMask block_touched_;
  std::int64_t num_blocks_ = 0;
  // Cells carrying surface (linear index in the lattice), for patches.
  std::vector<std::int64_t> surface_cells_;
  std::int64_t num_surface_cells_ = 0;
  std::vector<std::int32_t> parent_;
  int record_capacity_ = 0;
  std::vector<Eigen::Vector3f> surface_;
  std::vector<float> surface_pressure_;
  Pose X_WL_;  // the lattice body's pose in the latest query
  ContactRecorder contacts_;  // the latest Evaluate's polygons as contacts, L's frame, when kept
};

}  // namespace contactlab
