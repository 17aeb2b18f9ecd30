// The pressure-field model (pressure_field_model.h; Elandt et al. 2019), composed of its parts:
// the lattice and its culling (lattice_blocks.h), the surface in each cell (cell_surface.h), its
// integration (pressure_integration.h), its patches (contact_patches.h) and K_B
// (pressure_stiffness.h).
#include "baselines/pressure_field/pressure_field_model.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "baselines/pressure_field/cell_surface.h"
#include "baselines/pressure_field/contact_patches.h"
#include "baselines/pressure_field/lattice_blocks.h"
#include "baselines/pressure_field/pressure_integration.h"
#include "baselines/pressure_field/pressure_stiffness.h"
#include "geometry/pose.h"
#include "util/error.h"

namespace contactlab {

struct PressureFieldModel::Sums : PressureSums {};

PressureFieldModel::PressureFieldModel(PressureFieldSide A, PressureFieldSide B, const PressureFieldOptions& options)
    : options_(options) {
  const char* where = "pressure-field";
  for (const PressureFieldSide* s : {&A, &B}) {
    const char* body = s == &A ? "body A" : "body B";
    if (!s->field || s->field->empty()) Fail(where, std::string(body) + " has no distance field");
    if (s->field->info().mode == "soup") {
      Fail(where, std::string(body) + " (mesh " + s->field->info().source +
                      ")'s field is a polygon soup's offset band, not a closed volume a pressure field can fill: the mesh "
                      "is not watertight (or its field.mode is soup); close its holes (`contactlab mesh-info` counts "
                      "them) and use field.mode auto or closed, or compare with a model that takes soups (pointshell, "
                      "fcl, bullet)");
    }
    if (!(s->field->min_value() < 0)) Fail(where, std::string(body) + "'s field has no inside (no negative sample)");
    if (!s->rigid && !(s->modulus > 0 && std::isfinite(s->modulus))) {
      Fail(where, std::string(body) + "'s modulus must be finite and > 0 (an infinite one is a rigid body)");
    }
  }
  if (A.rigid && B.rigid) Fail(where, "both bodies are rigid: a pressure field needs one compliant body");
  if (!(options_.lipschitz >= 1) || !(options_.fd_step > 0) || options_.max_blocks < 1 || options_.lattice < 1) {
    Fail(where, "lipschitz must be >= 1, fd_step > 0, max_blocks >= 1 and lattice >= 1");
  }
  depth_A_ = -double(A.field->min_value());
  depth_B_ = -double(B.field->min_value());
  const Aabb box_B = B.field->box();
  radius_B_ = box_B.min.cwiseAbs().cwiseMax(box_B.max.cwiseAbs()).norm();
  lattice_is_A_ = A.field->spacing() < B.field->spacing();
  L_ = lattice_is_A_ ? std::move(A) : std::move(B);
  M_ = lattice_is_A_ ? std::move(B) : std::move(A);
  // Each body's compliance: metres of depth per pascal of pressure (pressure_law.h).
  const double c_L = L_.rigid ? 0 : -double(L_.field->min_value()) / L_.modulus;
  const double c_M = M_.rigid ? 0 : -double(M_.field->min_value()) / M_.modulus;
  law_ = PressureLaw::FromCompliances(c_M, c_L);
  h_ = L_.field->spacing() * options_.lattice;
  // K_B's difference steps: a hundredth of a cell, and the rotation that moves B's farthest
  // point by as much.
  step_x_ = options_.fd_step * h_;
  step_w_ = options_.fd_step * h_ / std::max(radius_B_, h_);
  // Every block of L's box at spacing h fits (capped).
  const Eigen::Vector3d extent = L_.field->box().size() / (h_ * kBlock);
  const double fit = std::ceil(extent.x() + 1) * std::ceil(extent.y() + 1) * std::ceil(extent.z() + 1);
  const std::int64_t capacity = std::int64_t(std::min<double>(fit, double(options_.max_blocks)));
  blocks_.resize(std::size_t(capacity));
  block_phi_L_.resize(std::size_t(capacity) * kBlockVerts);
  block_surface_.resize(std::size_t(capacity));
  block_candidates_.resize(std::size_t(capacity));
  block_candidate_corners_.resize(std::size_t(capacity));
  surface_cells_.resize(std::size_t(capacity) * kBlock * kBlock * kBlock);
  parent_.resize(surface_cells_.size());
}

bool PressureFieldModel::KeepContactSurface(int max_triangles) {
  record_capacity_ = std::max(0, max_triangles);
  surface_.reserve(std::size_t(record_capacity_) * 3);
  surface_pressure_.reserve(std::size_t(record_capacity_) * 3);
  return true;
}

void PressureFieldModel::LatestContactSurface(ContactSurface* out) const {
  out->corners.resize(surface_.size());
  for (std::size_t i = 0; i < surface_.size(); ++i) out->corners[i] = (X_WL_ * surface_[i].cast<double>()).cast<float>();
  out->pressure = surface_pressure_;
}

bool PressureFieldModel::KeepContacts(int max_contacts) {
  contacts_.Keep(max_contacts, /*with_surface=*/true);
  return true;
}

void PressureFieldModel::LatestContacts(ContactList* out) const {
  // The polygons' normals are the force on the lattice body: on B when that is B, else on A.
  contacts_.Fill(X_WL_, lattice_is_A_ ? -1.0 : 1.0, out);
}

bool PressureFieldModel::FindBlocks(const Pose& X_LM, std::int64_t* nodes) {
  num_blocks_ = 0;
  const DistanceField& fM = *M_.field;
  const DistanceField& fL = *L_.field;
  // The lattice over the overlap of the two boxes, a block's margin past it for cell indices.
  if (!FitLattice(fM.box(), fL.box(), fL.origin(), X_LM, h_, &origin_, &cells_)) return false;
  stride_j_ = std::int64_t(cells_.x()) + kBlock;
  stride_k_ = stride_j_ * (cells_.y() + kBlock);
  int root = kBlock;
  while (root < cells_.maxCoeff()) root *= 2;
  // The blocks that may hold surface, then L's field at their vertices.
  num_blocks_ = CullBlocks(fL, fM, X_LM.Inverse(), law_, origin_, cells_, h_, root, options_.lipschitz, blocks_.data(),
                           std::int64_t(blocks_.size()), nodes);
  for (std::int64_t b = 0; b < num_blocks_; ++b) {
    SampleBlock(fL, origin_, h_, blocks_[std::size_t(b)], block_phi_L_.data() + b * kBlockVerts);
  }
  return num_blocks_ > 0;
}

double PressureFieldModel::StepReach(const Pose& X_LM, const std::array<std::int32_t, 3>& blk) const {
  // B's origin in the lattice body's frame, and the farthest the block reaches from it.
  const Eigen::Vector3d o_B = lattice_is_A_ ? X_LM.translation : Eigen::Vector3d::Zero();
  const double half = 0.5 * kBlock * h_;
  const Eigen::Vector3d centre = origin_ + h_ * Eigen::Vector3d(blk[0], blk[1], blk[2]) + Eigen::Vector3d::Constant(half);
  const double radius = (centre - o_B).norm() + std::sqrt(3.0) * half;
  // A vertex moves by at most step_x (a translation step) or step_w radius (a rotation step
  // about B's origin) in M's frame. A trilinear field's gradient is at most sqrt(3) times its
  // bound along an axis: twice the Lipschitz bound, and a thousandth of a cell for the rounding.
  return 2 * options_.lipschitz * (step_x_ + step_w_ * radius) + 1e-3 * h_;
}

void PressureFieldModel::Integrate(const Pose& X_LM, bool record, Sums* sums) {
  const DistanceField& fM = *M_.field;
  const LatticeInOther lattice_in_M(X_LM.Inverse(), h_);
  const PressureLaw& law = law_;
  const bool clip_M = !M_.rigid, clip_L = !L_.rigid;
  const bool keep_candidates = record && options_.stiffness;
  SurfaceRecord recorder{&surface_, &surface_pressure_, record_capacity_,
                         contacts_.keeping() ? &contacts_ : nullptr};
  if (record) {
    num_surface_cells_ = 0;
    surface_.clear();
    surface_pressure_.clear();
    std::fill(block_surface_.begin(), block_surface_.begin() + num_blocks_, std::uint8_t(0));
  }
  float phi_M[kBlockVerts];
  BlockVertices vertices;
  LatticeCell cell;
  for (std::int64_t bi = 0; bi < num_blocks_; ++bi) {
    const auto& blk = blocks_[std::size_t(bi)];
    const float* phi_L = block_phi_L_.data() + bi * kBlockVerts;
    const Eigen::Vector3d x0 = origin_ + h_ * Eigen::Vector3d(blk[0], blk[1], blk[2]);
    // The cells to look at: all of them, or for a stiffness step only those the recording pass
    // found may hold surface once B has moved by a step, and M's field at their corners only.
    const std::uint64_t cells = record ? ~std::uint64_t(0) : block_candidates_[std::size_t(bi)];
    const VertexMask* needed = record ? nullptr : &block_candidate_corners_[std::size_t(bi)];
    SampleBlockInOther(fM, lattice_in_M, x0, phi_M, needed);
    LoadBlockVertices(phi_M, phi_L, law, keep_candidates ? StepReach(X_LM, blk) : 0, needed, &vertices);
    std::uint64_t candidates = 0;
    VertexMask corners;
    for (int ck = 0; ck < kBlock; ++ck) {
      for (int cj = 0; cj < kBlock; ++cj) {
        for (int ci = 0; ci < kBlock; ++ci) {
          const int c = ci + kBlock * (cj + kBlock * ck);
          if (!(cells >> c & 1)) continue;
          const CellFlags flags = CornerFlags(vertices, ci, cj, ck);
          if (keep_candidates && MayHoldSurfaceOnceMoved(flags, clip_M, clip_L)) {
            candidates |= std::uint64_t(1) << c;
            AddCellCorners(ci, cj, ck, &corners);
          }
          // The surface in each cell the gap changes sign over, where no body is wholly away.
          if (!MayHoldSurface(flags, clip_M, clip_L)) continue;
          LoadCell(phi_M, phi_L, vertices, x0, h_, ci, cj, ck, &cell);
          const double cell_area = IntegrateCell(cell, law, sums, record ? &recorder : nullptr);
          sums->area += cell_area;
          // The cells and blocks that carry surface, for patches and K_B.
          if (record && cell_area > 0) block_surface_[std::size_t(bi)] = 1;
          if (record && cell_area > 0 && num_surface_cells_ < std::int64_t(surface_cells_.size())) {
            const std::int64_t i = blk[0] + ci, j = blk[1] + cj, k = blk[2] + ck;
            surface_cells_[std::size_t(num_surface_cells_++)] = i + stride_j_ * j + stride_k_ * k;
          }
        }
      }
    }
    if (keep_candidates) {
      block_candidates_[std::size_t(bi)] = candidates;
      block_candidate_corners_[std::size_t(bi)] = corners;
    }
  }
}

void PressureFieldModel::KeepSurfaceBlocks() {
  std::int64_t kept = 0;
  for (std::int64_t b = 0; b < num_blocks_; ++b) {
    if (!block_surface_[std::size_t(b)]) continue;
    if (kept != b) {
      blocks_[std::size_t(kept)] = blocks_[std::size_t(b)];
      block_candidates_[std::size_t(kept)] = block_candidates_[std::size_t(b)];
      block_candidate_corners_[std::size_t(kept)] = block_candidate_corners_[std::size_t(b)];
      std::copy_n(block_phi_L_.begin() + b * kBlockVerts, kBlockVerts, block_phi_L_.begin() + kept * kBlockVerts);
    }
    ++kept;
  }
  num_blocks_ = kept;
}

int PressureFieldModel::CountPatches() {
  return contactlab::CountPatches(surface_cells_.data(), num_surface_cells_, stride_j_, stride_k_, parent_.data());
}

Wrench PressureFieldModel::OnB(const Sums& sums, const Pose& X_WA, const Pose& X_WB) const {
  Wrench w;
  if (!lattice_is_A_) {
    const Eigen::Matrix3d R = X_WB.R();
    w.force = R * sums.force;
    w.torque = R * sums.torque;
    return w;
  }
  // The sums are the wrench on A about A's origin: B feels the opposite, about its own origin.
  const Eigen::Matrix3d R = X_WA.R();
  const Eigen::Vector3d F_A = R * sums.force, T_A = R * sums.torque;
  w.force = -F_A;
  w.torque = -(T_A + (X_WA.translation - X_WB.translation).cross(F_A));
  return w;
}

ContactResult PressureFieldModel::Evaluate(const ContactQuery& query) {
  ContactResult r;
  X_WL_ = lattice_is_A_ ? query.X_WA : query.X_WB;
  contacts_.Clear();
  const Pose X_LM = LatticeToOther(query.X_WA, query.X_WB);
  std::int64_t nodes = 0;
  const bool overlap = FindBlocks(X_LM, &nodes);
  r.stats.nodes_visited = nodes + num_blocks_ * kBlock * kBlock * kBlock;
  if (!overlap) {
    num_surface_cells_ = 0;
    surface_.clear();
    surface_pressure_.clear();
    return r;
  }
  Sums base;
  Integrate(X_LM, /*record=*/true, &base);
  r.on_B = OnB(base, query.X_WA, query.X_WB);
  r.stats.contact_area = base.area;
  r.stats.max_penetration = std::max(0.0, base.max_penetration);
  r.stats.points_in_contact = std::int32_t(std::min<std::int64_t>(num_surface_cells_, INT32_MAX));
  r.stats.patches = CountPatches();
  if (options_.stiffness && base.area > 0) {
    KeepSurfaceBlocks();
    // Forward differences in B's pose over the blocks with surface: a step of 1/100 cell moves
    // the surface into another block only where it passes within that of a block's face. In
    // those blocks only the cells that may hold surface once moved are integrated again.
    r.K_B = ForwardDifferenceStiffness(query.X_WB, r.on_B.AsVector(), step_x_, step_w_, [&](const Pose& X_WB) {
      Sums s;
      Integrate(LatticeToOther(query.X_WA, X_WB), /*record=*/false, &s);
      return OnB(s, query.X_WA, X_WB);
    });
  }
  return r;
}

}  // namespace contactlab
