// The pressure-field model (pressure_field_model.h; Elandt et al. 2019), composed of its parts:
// the lattice and its culling (lattice_blocks.h), the surface in each cell (cell_surface.h), its
// integration (pressure_integration.h), its patches (contact_patches.h) and K_B
// (pressure_stiffness.h), taken in the same pass in reverse mode (pressure_adjoints.h).
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
  if (!(options_.lipschitz >= 1) || options_.max_blocks < 1 || options_.lattice < 1) {
    Fail(where, "lipschitz must be >= 1, max_blocks >= 1 and lattice >= 1");
  }
  depth_A_ = -double(A.field->min_value());
  depth_B_ = -double(B.field->min_value());
  lattice_is_A_ = A.field->spacing() < B.field->spacing();
  L_ = lattice_is_A_ ? std::move(A) : std::move(B);
  M_ = lattice_is_A_ ? std::move(B) : std::move(A);
  // Each body's compliance: metres of depth per pascal of pressure (pressure_law.h).
  const double c_L = L_.rigid ? 0 : -double(L_.field->min_value()) / L_.modulus;
  const double c_M = M_.rigid ? 0 : -double(M_.field->min_value()) / M_.modulus;
  law_ = PressureLaw::FromCompliances(c_M, c_L);
  base_h_ = h_ = L_.field->spacing() * options_.lattice;
  // Every block of L's box at spacing h fits (capped).
  const Eigen::Vector3d extent = L_.field->box().size() / (h_ * kBlock);
  const double fit = std::ceil(extent.x() + 1) * std::ceil(extent.y() + 1) * std::ceil(extent.z() + 1);
  const std::int64_t capacity = std::int64_t(std::min<double>(fit, double(options_.max_blocks)));
  blocks_.resize(std::size_t(capacity));
  block_phi_L_.resize(std::size_t(capacity) * kBlockVerts);
  block_sensitivity_.resize(6 * kBlockVerts);
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

bool PressureFieldModel::FindBlocks(const Pose& X_LM, std::int64_t budget, std::int64_t* nodes, int* doublings) {
  // The lattice at the configured spacing, doubled while its blocks hold more cells than the
  // budget allows (graceful degradation: a coarser surface, fewer cells).
  // Each try stops culling as soon as the budget is exceeded, so its cost is bounded too.
  constexpr std::int64_t kCellsPerBlock = kBlock * kBlock * kBlock;
  const std::int64_t limit = budget > 0 ? std::max<std::int64_t>(1, budget / kCellsPerBlock) : 0;
  h_ = base_h_;
  *doublings = 0;
  bool overlap = CullLattice(X_LM, *doublings < kMaxLatticeDoublings ? limit : 0, nodes);
  while (overlap && limit > 0 && num_blocks_ > limit && *doublings < kMaxLatticeDoublings) {
    ++*doublings;
    h_ *= 2;
    overlap = CullLattice(X_LM, *doublings < kMaxLatticeDoublings ? limit : 0, nodes);
  }
  // L's field at the blocks' vertices.
  const DistanceField& fL = *L_.field;
  for (std::int64_t b = 0; b < num_blocks_; ++b) {
    SampleBlock(fL, origin_, h_, blocks_[std::size_t(b)], block_phi_L_.data() + b * kBlockVerts);
  }
  return overlap;
}

bool PressureFieldModel::CullLattice(const Pose& X_LM, std::int64_t limit, std::int64_t* nodes) {
  num_blocks_ = 0;
  const DistanceField& fM = *M_.field;
  const DistanceField& fL = *L_.field;
  // The lattice over the overlap of the two boxes, a block's margin past it for cell indices.
  if (!FitLattice(fM.box(), fL.box(), fL.origin(), X_LM, h_, &origin_, &cells_)) return false;
  stride_j_ = std::int64_t(cells_.x()) + kBlock;
  stride_k_ = stride_j_ * (cells_.y() + kBlock);
  int root = kBlock;
  while (root < cells_.maxCoeff()) root *= 2;
  // The blocks that may hold surface.
  num_blocks_ = CullBlocks(fL, fM, X_LM.Inverse(), law_, origin_, cells_, h_, root, options_.lipschitz, blocks_.data(),
                           std::int64_t(blocks_.size()), nodes, limit);
  return num_blocks_ > 0;
}

Matrix6d PressureFieldModel::BlockStiffness(const Pose& X_LM, const Eigen::Vector3d& x0) const {
  // M's field at a lattice vertex x (L's frame) moves with B's twist (v, w) (L's frame, rotation
  // about B's origin o) by ∇phi_M · dy, dy the vertex's motion seen from M. When L is B,
  // dy = R_ML (v + w × x); when L is A, B's motion moves the vertex the other way about o:
  // dy = -R_ML (v + w × (x - o)). With n = R_LM ∇phi_M, the six derivatives are ±(n, (x - o) × n).
  const double sign = lattice_is_A_ ? -1.0 : 1.0;
  const Eigen::Vector3d o = lattice_is_A_ ? X_LM.translation : Eigen::Vector3d::Zero();
  const Eigen::Matrix3d R_LM = X_LM.R();
  const Pose X_ML = X_LM.Inverse();
  Matrix6d D = Matrix6d::Zero();
  for (int v = 0; v < kBlockVerts; ++v) {
    if (!block_touched_.Has(v)) continue;
    const int i = v % kVerts, j = (v / kVerts) % kVerts, k = v / (kVerts * kVerts);
    const Eigen::Vector3d x = x0 + h_ * Eigen::Vector3d(i, j, k);
    Eigen::Vector3d gradient;
    M_.field->DistanceAndGradient(X_ML * x, &gradient);
    const Eigen::Vector3d n = R_LM * gradient;
    Vector6d d;
    d.head<3>() = sign * n;
    d.tail<3>() = sign * (x - o).cross(n);
    D += Eigen::Map<const Vector6d>(block_sensitivity_.data() + 6 * v) * d.transpose();
  }
  return D;
}

void PressureFieldModel::AddCornerSensitivity(const CornerSensitivity& b, int ci, int cj, int ck) {
  for (int c = 0; c < 8; ++c) {
    const int v = CellCornerVertex(ci, cj, ck, c);
    Eigen::Map<Vector6d> at(block_sensitivity_.data() + 6 * v);
    if (block_touched_.Has(v)) {
      at += b.col(c);
    } else {
      at = b.col(c);
      block_touched_.Add(v);
    }
  }
}

void PressureFieldModel::Integrate(const Pose& X_LM, PressureSums* sums, Matrix6d* D) {
  const DistanceField& fM = *M_.field;
  const LatticeInOther lattice_in_M(X_LM.Inverse(), h_);
  const PressureLaw& law = law_;
  const bool clip_M = !M_.rigid, clip_L = !L_.rigid;
  SurfaceRecord recorder{&surface_, &surface_pressure_, record_capacity_,
                         contacts_.keeping() ? &contacts_ : nullptr};
  num_surface_cells_ = 0;
  surface_.clear();
  surface_pressure_.clear();
  float phi_M[kBlockVerts];
  BlockVertices vertices;
  LatticeCell cell;
  CornerSensitivity corner_sensitivity;
  for (std::int64_t bi = 0; bi < num_blocks_; ++bi) {
    const auto& blk = blocks_[std::size_t(bi)];
    const float* phi_L = block_phi_L_.data() + bi * kBlockVerts;
    const Eigen::Vector3d x0 = origin_ + h_ * Eigen::Vector3d(blk[0], blk[1], blk[2]);
    SampleBlockInOther(fM, lattice_in_M, x0, phi_M);
    LoadBlockVertices(phi_M, phi_L, law, &vertices);
    if (D) block_touched_ = VertexMask();
    for (int ck = 0; ck < kBlock; ++ck) {
      for (int cj = 0; cj < kBlock; ++cj) {
        for (int ci = 0; ci < kBlock; ++ci) {
          // The surface in each cell the gap changes sign over, where no body is wholly away.
          if (!MayHoldSurface(CornerFlags(vertices, ci, cj, ck), clip_M, clip_L)) continue;
          LoadCell(phi_M, phi_L, vertices, x0, h_, ci, cj, ck, &cell);
          if (D) corner_sensitivity.setZero();
          const double cell_area = IntegrateCell(cell, law, sums, &recorder, D ? &corner_sensitivity : nullptr);
          if (D) AddCornerSensitivity(corner_sensitivity, ci, cj, ck);
          sums->area += cell_area;
          // The cells that carry surface, for patches.
          if (cell_area > 0 && num_surface_cells_ < std::int64_t(surface_cells_.size())) {
            const std::int64_t i = blk[0] + ci, j = blk[1] + cj, k = blk[2] + ck;
            surface_cells_[std::size_t(num_surface_cells_++)] = i + stride_j_ * j + stride_k_ * k;
          }
        }
      }
    }
    if (D) *D += BlockStiffness(X_LM, x0);
  }
}

int PressureFieldModel::CountPatches() {
  return contactlab::CountPatches(surface_cells_.data(), num_surface_cells_, stride_j_, stride_k_, parent_.data());
}

Wrench PressureFieldModel::OnB(const PressureSums& sums, const Pose& X_WA, const Pose& X_WB) const {
  const Eigen::Vector3d& force = sums.force;
  const Eigen::Vector3d& torque = sums.torque;
  Wrench w;
  if (!lattice_is_A_) {
    const Eigen::Matrix3d R = X_WB.R();
    w.force = R * force;
    w.torque = R * torque;
    return w;
  }
  // The sums are the wrench on A about A's origin: B feels the opposite, about its own origin.
  const Eigen::Matrix3d R = X_WA.R();
  const Eigen::Vector3d F_A = R * force, T_A = R * torque;
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
  int doublings = 0;
  const bool overlap = FindBlocks(X_LM, query.node_budget, &nodes, &doublings);
  r.stats.nodes_visited = nodes + num_blocks_ * kBlock * kBlock * kBlock;
  r.stats.degraded = doublings;
  if (!overlap) {
    num_surface_cells_ = 0;
    surface_.clear();
    surface_pressure_.clear();
    return r;
  }
  // The wrench, and its derivatives along B's twist in the same pass.
  PressureSums base;
  Matrix6d D = Matrix6d::Zero();
  Integrate(X_LM, &base, options_.stiffness ? &D : nullptr);
  r.on_B = OnB(base, query.X_WA, query.X_WB);
  r.stats.contact_area = base.area;
  r.stats.max_penetration = std::max(0.0, base.max_penetration);
  r.stats.points_in_contact = std::int32_t(std::min<std::int64_t>(num_surface_cells_, INT32_MAX));
  r.stats.patches = CountPatches();
  if (options_.stiffness && base.area > 0) {
    r.K_B = PressureStiffnessOnB(D, r.on_B, lattice_is_A_, query.X_WA, query.X_WB);
  }
  return r;
}

}  // namespace contactlab
