// McNeely, Puterbaugh & Troy 1999 (sec. 4) and 2006 (sec. 3): the Voxmap-PointShell contact
// model, with DLR's distance-layered voxmap (default) or the 1999 tangent-plane surface layer,
// and temporal coherence from the 8-bit voxmap.
#include "baselines/vps/vps_contact_model.h"

#include <cmath>
#include <limits>

#include "baselines/vps/vps_pointshell.h"
#include "contact/contact_accumulator.h"
#include "contact/float_transform.h"
#include "util/error.h"

namespace contactlab {
namespace {

// The low BITS bits of V in reverse order.
std::uint64_t BitReversed(std::uint64_t v, int bits) {
  std::uint64_t r = 0;
  for (int b = 0; b < bits; ++b, v >>= 1) r = (r << 1) | (v & 1);
  return r;
}

// Cycles a point may skip when it cannot touch before moving GAP metres at STEP metres per
// cycle: the first cycle offset m with m * STEP >= GAP (shrunk slightly against rounding of
// the point's voxel). At least 1 (look again next cycle).
inline std::int64_t CyclesToCover(double gap, double step) {
  const double m = std::ceil(gap * (1 - 1e-4) / step);
  return m < 1 ? 1 : (m > 1e15 ? std::int64_t(1e15) : std::int64_t(m));
}

}  // namespace

VpsContactModel::VpsContactModel(std::string name, std::shared_ptr<const Pointshell> shell,
                                 std::shared_ptr<const DistanceField> field, const VpsContactParams& params)
    : name_(std::move(name)), shell_(std::move(shell)), params_(params) {
  const std::string where = "contact model " + name_;
  if (!shell_ || shell_->num_points() == 0) Fail(where, "needs a non-empty pointshell");
  if (!field || field->empty()) Fail(where, "needs a distance field");
  CheckPenaltyParams(params.penalty, where);
  if (!(params.max_point_speed > 0) || !(params.cycle_seconds > 0) || !std::isfinite(params.max_point_speed) ||
      !std::isfinite(params.cycle_seconds)) {
    Fail(where, "max_point_speed and cycle_seconds must be finite and positive");
  }
  if (!std::isfinite(params.interior_depth)) Fail(where, "interior_depth must be finite");
  VoxmapOptions vo;
  vo.voxel_size = params.voxel_size;
  voxmap_ = BuildVoxmap(*field, vo);
  if (params.coherence) wide_ = BuildWideVoxmap(voxmap_);
  if (params.voxmap == VpsVoxmap::kLayered) depths_ = BuildVoxelDepthMap(*field, voxmap_);
  const double v = voxmap_.voxel_size();
  interior_depth_ = params.interior_depth >= 0 ? params.interior_depth : 0.5 * std::sqrt(3.0) * v;
  for (int a = 0; a < 3; ++a) box_hi_[a] = float(voxmap_.origin()[a] + v * voxmap_.dims()[a]);
  next_check_.assign(std::size_t(shell_->num_points()), std::numeric_limits<std::int64_t>::min());
  if (params.friction.on()) anchors_ = FrictionAnchors(shell_->num_points());
  // The order a budget visits the points in: their indices in bit-reversed order.
  const int n = shell_->num_points();
  int bits = 0;
  while ((std::int64_t(1) << bits) < n) ++bits;
  budget_order_.reserve(std::size_t(n));
  for (std::int64_t j = 0; j < (std::int64_t(1) << bits); ++j) {
    const std::uint64_t i = BitReversed(std::uint64_t(j), bits);
    if (i < std::uint64_t(n)) budget_order_.push_back(std::int32_t(i));
  }
}

void VpsContactModel::AddFriction(int i, const Eigen::Vector3d& p_B, const Eigen::Vector3d& N_B, double depth,
                                  FrictionSums* sums) {
  Eigen::Vector3d u;
  const bool slid = AddFrictionContact(&anchors_, sums, params_.friction, i, p_B, N_B, depth, N_B, &u);
  if (contacts_.keeping()) contacts_.AddFriction(depth * u, !slid);
}

void VpsContactModel::Reset() {
  ResetCoherence();
  anchors_.Reset();
}

void VpsContactModel::ResetCoherence() {
  std::fill(next_check_.begin(), next_check_.end(), std::numeric_limits<std::int64_t>::min());
}

VpsModelInfo VpsContactModel::info() const {
  VpsModelInfo info;
  info.voxel_size = voxmap_.voxel_size();
  info.dims = voxmap_.dims();
  info.voxels = voxmap_.num_voxels();
  info.free = voxmap_.count(VoxelClass::kFree);
  info.proximity = voxmap_.count(VoxelClass::kProximity);
  info.surface = voxmap_.count(VoxelClass::kSurface);
  info.interior = voxmap_.count(VoxelClass::kInterior);
  info.voxmap_bytes = voxmap_.memory_bytes();
  info.wide_voxmap_bytes = wide_.memory_bytes();
  info.depth_map_bytes = depths_.memory_bytes();
  info.points = shell_->num_points();
  info.pointshell_bytes = std::size_t(shell_->num_points()) * 6 * sizeof(float);
  info.interior_depth = interior_depth_;
  return info;
}

ContactResult VpsContactModel::Evaluate(const ContactQuery& query) {
  const Pointshell& s = *shell_;
  const FloatTransform X_BA(query.X_WB.Inverse() * query.X_WA);
  ContactAccumulator acc;
  const int n = s.num_points();
  const bool coherence = params_.coherence;
  const bool layered = params_.voxmap == VpsVoxmap::kLayered;
  const double v = voxmap_.voxel_size();
  const double step = params_.max_point_speed * params_.cycle_seconds;  // metres per cycle
  const std::int64_t cycle = query.cycle;
  const Eigen::Vector3d& o = voxmap_.origin();
  std::int64_t visited = 0;
  std::int32_t skipped = 0;
  contacts_.Clear();
  X_WB_contacts_ = query.X_WB;
  const bool keep = contacts_.keeping();
  const bool friction_on = params_.friction.on();
  FrictionSums friction;
  if (friction_on) anchors_.BeginQuery();

  // With a time budget, points in the bit-reversed order of their index (vps_contact_model.h).
  const std::int64_t budget = query.node_budget;
  const bool budgeted = budget > 0;
  int looked_at = n;  // the points the budget let the loop reach
  for (int j = 0; j < n; ++j) {
    const int i = budgeted ? budget_order_[std::size_t(j)] : j;
    // The time budget: the points reached stand for all.
    if (budgeted && visited >= budget && !(coherence && cycle < next_check_[i])) {
      looked_at = j;
      break;
    }
    // Temporal coherence: the point cannot touch before its next check.
    if (coherence && cycle < next_check_[i]) {
      ++skipped;
      continue;
    }
    ++visited;
    // The point in B's frame and its voxel.
    float p_BQ[3];
    X_BA.Apply(s.x[i], s.y[i], s.z[i], p_BQ);
    int vi, vj, vk;
    if (!voxmap_.Locate(p_BQ[0], p_BQ[1], p_BQ[2], &vi, &vj, &vk)) {
      if (coherence) {
        // Outside the voxmap: no contact before the point reaches the voxmap box.
        float e2 = 0.f;
        for (int a = 0; a < 3; ++a) {
          const float lo = float(o[a]) - p_BQ[a], hi = p_BQ[a] - box_hi_[a];
          const float e = lo > 0.f ? lo : (hi > 0.f ? hi : 0.f);
          e2 += e * e;
        }
        // A non-finite point (e2 NaN) is looked at again next cycle.
        next_check_[i] = cycle + (e2 > 0.f ? CyclesToCover(std::sqrt(double(e2)), step) : 1);
      }
      continue;
    }
    // Classify: a contact voxel (surface or interior) or no force; with coherence, a free
    // voxel's layer sets the point's next check. The compact voxmap (2 bits a voxel) answers
    // for most points; the layered depth map (4 bytes a voxel) is read only in contact voxels.
    const std::int64_t idx = voxmap_.Index(vi, vj, vk);
    bool surface = false;
    if (coherence) {
      const std::uint8_t w = wide_.Get(idx);
      if (w != kWideSurface && w != kWideInterior) {
        next_check_[i] = cycle + CyclesToCover(double(w - 1) * v, step);
        continue;
      }
      surface = w == kWideSurface;
    } else {
      const VoxelClass c = voxmap_.Get(idx);
      if (c != VoxelClass::kSurface && c != VoxelClass::kInterior) continue;
      surface = c == VoxelClass::kSurface;
    }
    const Eigen::Vector3d p_B(p_BQ[0], p_BQ[1], p_BQ[2]);
    const Eigen::Vector3d c_B = o + v * Eigen::Vector3d(vi + 0.5, vj + 0.5, vk + 0.5);
    float n_B[3];
    X_BA.Rotate(s.nx[i], s.ny[i], s.nz[i], n_B);
    const Eigen::Vector3d N_B(n_B[0], n_B[1], n_B[2]);
    double depth;
    if (layered) {
      // The distance-layered voxmap: the centre's depth in layers, continued to P along B's
      // normal at the centre. This is what removes the 1999 model's dead band. Measured on
      // data/scenes/sphere-on-plate.yaml (2.5 mm voxels, the plate's top on a voxel face), the
      // surface model gives 0 N from 1.25 to 2.5 mm: the face makes two surface layers, whose
      // centres sit 1.25 mm above and below the real surface; a surface voxel counts only the
      // points below its centre; the interior (fixed depth) begins 2.5 mm down; and the
      // voxel-centre pointshell lies on a lattice of the same spacing and phase, so every
      // point near the ball's bottom has the same offset from its voxel's centre and all of
      // them sit above their centres together while depth mod 2.5 mm is in [1.25, 2.5).
      // Here depth = -d(c) + (c - p) . n(c) is the plane's exact depth whatever the phase.
      const VoxelDepth& e = depths_.Get(idx);
      if (e.depth == kNoDepth) continue;
      float n[3];
      VoxelDepthMap::Normal(e, n);
      depth = v * double(VoxelDepthMap::DepthLayers(e)) + (c_B - p_B).dot(Eigen::Vector3d(n[0], n[1], n[2]));
    } else {
      // McNeely 1999: the tangent plane through a surface voxel's centre perpendicular to the
      // point's normal, or the fixed interior depth.
      depth = surface ? (c_B - p_B).dot(N_B) : interior_depth_;
    }
    if (depth > 0) {
      acc.Add(p_B, N_B, -depth, N_B);
      if (keep) contacts_.Add(p_B, -N_B.normalized(), depth);
      if (friction_on) AddFriction(i, p_B, N_B.normalized(), depth, &friction);
    }
  }

  ContactResult result;
  if (looked_at < n) {
    acc.Scale(double(n) / double(looked_at));
    friction.Scale(double(n) / double(looked_at));
  }
  acc.Finish(params_.penalty, query.X_WB, &result);
  if (friction_on) FinishFriction(friction, params_.penalty, acc.count(), params_.friction, query.X_WB, &contacts_, &result);
  result.stats.degraded = looked_at < n ? int(std::ceil(std::log2(double(n) / double(looked_at)))) : 0;
  result.stats.nodes_visited = visited;
  result.stats.nodes_skipped_coherence = skipped;
  result.stats.level_rendered = -1;
  return result;
}

}  // namespace contactlab
