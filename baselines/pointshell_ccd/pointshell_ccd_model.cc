// The pointshell-ccd proxy model (pointshell_ccd_model.h).
#include "baselines/pointshell_ccd/pointshell_ccd_model.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "geometry/rotation_math.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Projected Gauss-Seidel sweeps per step, and the violation (a fraction of the offset) at which
// the multipliers are taken as converged.
constexpr int kSweeps = 40;
constexpr double kViolationTolerance = 1e-2;
// Constraint updates (one point's multiplier in one sweep) counted as one lookup of the budget:
// an update is a few multiply-adds on data in cache, a lookup a trilinear read of the field
// with its cache misses. At this rate a budget of 3,000 holds the deep press of bench_models
// under 0.4 ms p99.9 on its four scenes.
constexpr std::int64_t kUpdatesPerLookup = 8;

// POSE with a unit quaternion (UnitQuaternion). False when POSE is not finite.
bool UnitPose(const Pose& pose, Pose* out) {
  if (!pose.translation.allFinite() || !pose.rotation.coeffs().allFinite()) return false;
  *out = {UnitQuaternion(pose.rotation), pose.translation};
  return true;
}

// Constraints that contradict each other (the proxy deep inside B, past a medial surface) drive
// the multipliers up without bound: the correction to GOAL's straight step is kept within the
// straight step's length plus twice DEEPEST_VIOLATION (a consistent set never needs more:
// undoing the step and backing out of the deepest point). RADIUS weighs rotations as lengths.
void LimitCorrection(const BlendMotion& goal, double radius, double deepest_violation, Eigen::Vector3d* v,
                     Eigen::Vector3d* w) {
  const double reach = goal.v.norm() + goal.w.norm() * radius + 2 * deepest_violation;
  if (const double dv = (*v - goal.v).norm(); dv > reach) *v = goal.v + (reach / dv) * (*v - goal.v);
  if (const double dw = (*w - goal.w).norm() * radius; dw > reach) *w = goal.w + (reach / dw) * (*w - goal.w);
}

// K_B of the spring with the proxy sliding: -M^½ P M^½ with P the projector onto the range of
// G (the sum of u u^T over the tight constraints, A's frame), turned into the world frame by
// A's pose X_WA, into *K_B. K and KR: the translational and rotational stiffness of M.
void SlidingStiffness(const Matrix6d& G, double k, double kr, const Pose& X_WA, Matrix6d* K_B) {
  const Eigen::SelfAdjointEigenSolver<Matrix6d> eig(G);  // (G over every tight constraint)
  const Vector6d ev = eig.eigenvalues();
  const double top = ev.maxCoeff();
  Matrix6d P = Matrix6d::Zero();
  for (int j = 0; j < 6; ++j) {
    if (ev[j] > 1e-9 * top) P.noalias() += eig.eigenvectors().col(j) * eig.eigenvectors().col(j).transpose();
  }
  Vector6d root_m;
  root_m << Eigen::Vector3d::Constant(std::sqrt(k)), Eigen::Vector3d::Constant(std::sqrt(kr));
  const Matrix6d K_A = -(root_m.asDiagonal() * P * root_m.asDiagonal());
  // Rows and twists were in A's frame; K_B is in the world frame.
  Matrix6d T = Matrix6d::Zero();
  T.topLeftCorner<3, 3>() = T.bottomRightCorner<3, 3>() = X_WA.R();
  *K_B = T * K_A * T.transpose();  // assigned, not returned: Eigen evaluates it through a temporary, as before
}

}  // namespace

void PointshellCcdParams::Check(std::string_view where) const {
  auto positive = [&](double v, const char* name) {
    if (!std::isfinite(v) || v <= 0) Fail(where, std::string(name) + " must be finite and > 0, got " + std::to_string(v));
  };
  positive(stiffness, "proxy stiffness");
  positive(rot_stiffness, "proxy rotational stiffness");
  positive(offset, "proxy offset");
  if (iterations < 1) Fail(where, "proxy iterations must be at least 1, got " + std::to_string(iterations));
  if (!std::isfinite(lipschitz) || lipschitz < 1) Fail(where, "lipschitz must be finite and >= 1");
  if (max_constraints < 1) Fail(where, "max_constraints must be at least 1");
}

PointshellCcdModel::PointshellCcdModel(std::shared_ptr<const Pointshell> shell_A,
                                       std::shared_ptr<const DistanceField> field_B, const PointshellCcdParams& params)
    : search_(std::move(shell_A), std::move(field_B)), params_(params) {
  params_.Check("pointshell-ccd");
  // Below kMinProxyOffsetCells the proxy lags or stalls (pointshell_ccd_model.h).
  const double least = kMinProxyOffsetCells * search_.field().spacing();
  if (!(params_.offset >= least)) {
    char text[160];
    std::snprintf(text, sizeof text, "proxy offset %.6g m is below %g cells of B's field (%.6g m)", params_.offset,
                  kMinProxyOffsetCells, least);
    Fail("pointshell-ccd", text);
  }
  const std::size_t capacity = std::size_t(std::min(params_.max_constraints, std::max(1, search_.shell().num_points())));
  near_.resize(capacity);
  moment_.resize(capacity);
  multiplier_.resize(capacity);
  inv_diag_.resize(capacity);
  warm_points_.resize(capacity);
  point_multiplier_.assign(std::size_t(search_.shell().num_points()), 0.0);
}

void PointshellCcdModel::Reset() {
  has_proxy_ = false;
  for (int i = 0; i < warm_count_; ++i) point_multiplier_[std::size_t(warm_points_[i])] = 0;
  warm_count_ = 0;
}

bool PointshellCcdModel::Proxy(Pose* X_WB_proxy) const {
  if (!has_proxy_) return false;
  if (X_WB_proxy) *X_WB_proxy = X_WA_last_ * X_AP_;
  return true;
}

double PointshellCcdModel::LoadConstraints(int n, const Eigen::Vector3d& o, Eigen::Vector3d* v, Eigen::Vector3d* w,
                                           double* deepest) {
  const double l = params_.offset, k = params_.stiffness, kr = params_.rot_stiffness;
  *deepest = 0;
  double deepest_violation = 0;  // largest l - d_i
  for (int i = 0; i < n; ++i) {
    const NearPoint& c = near_[i];
    moment_[i] = (c.p_A - o).cross(c.gradient_A);
    const double diag = c.gradient_A.squaredNorm() / k + moment_[i].squaredNorm() / kr;
    inv_diag_[i] = diag > 0 ? 1 / diag : 0;
    // Warm start from the point's latest multiplier.
    const double mu = point_multiplier_[std::size_t(c.point)];
    multiplier_[i] = mu;
    if (mu > 0) {
      *v -= (mu / k) * c.gradient_A;
      *w -= (mu / kr) * moment_[i];
    }
    *deepest = std::max(*deepest, -c.distance);
    deepest_violation = std::max(deepest_violation, l - c.distance);
  }
  return deepest_violation;
}

int PointshellCcdModel::SolveMultipliers(int n, int max_sweeps, Eigen::Vector3d* v, Eigen::Vector3d* w,
                                         bool* converged) {
  const double l = params_.offset, k = params_.stiffness, kr = params_.rot_stiffness;
  *converged = n == 0;
  int sweep = 0;
  while (sweep < max_sweeps && !*converged) {
    ++sweep;
    double worst = 0;
    for (int i = 0; i < n; ++i) {
      const NearPoint& c = near_[i];
      const double violation = c.gradient_A.dot(*v) + moment_[i].dot(*w) - (c.distance - l);
      const double mu = std::max(0.0, multiplier_[i] + violation * inv_diag_[i]);
      const double dmu = mu - multiplier_[i];
      if (dmu != 0) {
        *v -= (dmu / k) * c.gradient_A;
        *w -= (dmu / kr) * moment_[i];
        multiplier_[i] = mu;
      }
      worst = std::max(worst, violation);
    }
    *converged = worst <= kViolationTolerance * l;
  }
  return sweep;
}

void PointshellCcdModel::KeepMultipliers(int n) {
  for (int i = 0; i < warm_count_; ++i) point_multiplier_[std::size_t(warm_points_[i])] = 0;
  for (int i = 0; i < n; ++i) {
    point_multiplier_[std::size_t(near_[i].point)] = multiplier_[i];
    warm_points_[i] = near_[i].point;
  }
  warm_count_ = n;
}

int PointshellCcdModel::TightConstraints(int n, const Eigen::Vector3d& v, const Eigen::Vector3d& w,
                                         Matrix6d* G) const {
  const double l = params_.offset, k = params_.stiffness, kr = params_.rot_stiffness;
  G->setZero();
  int pushing = 0;
  for (int i = 0; i < n; ++i) {
    // A constraint the step ends on blocks its direction whether or not it happens to carry
    // the multiplier (projected Gauss-Seidel puts a flat face's load on one of its points).
    const NearPoint& c = near_[i];
    const double slack = (c.distance - l) - (c.gradient_A.dot(v) + moment_[i].dot(w));
    if (multiplier_[i] <= 0 && slack > kViolationTolerance * l) continue;
    if (multiplier_[i] > 0) ++pushing;
    Vector6d u;
    u << near_[i].gradient_A / std::sqrt(k), moment_[i] / std::sqrt(kr);
    G->noalias() += u * u.transpose();
  }
  return pushing;
}

ContactResult PointshellCcdModel::Evaluate(const ContactQuery& query) {
  ContactResult out;
  contacts_.Clear();
  Pose X_WA, X_WB;
  if (!UnitPose(query.X_WA, &X_WA) || !UnitPose(query.X_WB, &X_WB)) {
    out.stats.faults = 1;  // nothing to place the proxy against; it keeps its pose
    return out;
  }
  X_WA_last_ = X_WA;
  const Pose X_AB = X_WA.Inverse() * X_WB;
  if (!has_proxy_) {
    X_AP_ = X_AB;
    has_proxy_ = true;
  }
  const double l = params_.offset, lambda = params_.lipschitz;
  const double k = params_.stiffness, kr = params_.rot_stiffness;
  const double radius = std::sqrt(kr / k);  // the length at which a rotation weighs like a translation
  const std::int64_t budget = query.node_budget;
  std::int64_t visited = 0;  // nodes visited by the searches
  std::int64_t work = 0;     // the budget's units: nodes, steps and constraint updates (header)
  bool degraded = false;
  int pushing = 0;
  int last_n = 0;  // the active points of the last step
  double deepest = 0;
  Matrix6d G = Matrix6d::Zero();  // sum of u u^T over pushing constraints, u = M^-1/2 J^T
  auto remaining = [&] { return budget > 0 ? std::max<std::int64_t>(1, budget - work) : std::int64_t(0); };

  for (int it = 0; it < params_.iterations; ++it) {
    if (budget > 0 && work >= budget) {  // spent: the proxy stays where the last step left it
      degraded = true;
      break;
    }
    // The active set at the proxy, and the straight step to B.
    const std::int64_t before = visited;
    const int n = search_.Near(X_AP_, 2 * l, lambda, remaining(), near_.data(), int(near_.size()), &visited, &degraded);
    work += visited - before + n;  // its nodes, and the gradient of each point it keeps
    last_n = n;
    const BlendMotion goal = BlendMotion::Between(X_AP_, X_AB);
    Eigen::Vector3d v = goal.v, w = goal.w;
    const double deepest_violation = LoadConstraints(n, X_AP_.translation, &v, &w, &deepest);
    // min 1/2 (ξ - ξ_goal)^T M (ξ - ξ_goal) subject to J_i ξ <= d_i - l: projected Gauss-Seidel
    // on the multipliers, ξ = ξ_goal - M^-1 sum J_i^T μ_i kept up to date.
    // The sweeps the budget leaves (at least one); a solve cut short is a degraded one.
    int sweeps = kSweeps;
    if (budget > 0 && n > 0) {
      sweeps = int(std::clamp<std::int64_t>((budget - work) * kUpdatesPerLookup / n, 1, kSweeps));
    }
    bool converged = false;
    work += std::int64_t(SolveMultipliers(n, sweeps, &v, &w, &converged)) * n / kUpdatesPerLookup;
    degraded = degraded || (!converged && sweeps < kSweeps);
    LimitCorrection(goal, radius, deepest_violation, &v, &w);
    KeepMultipliers(n);
    pushing = TightConstraints(n, v, w, &G);
    // Nowhere to go: a step of a thousandth of the offset is not taken (at rest in contact the
    // solve leaves rounding-sized steps, each a full search).
    if (v.norm() + w.norm() * radius <= 1e-3 * l) break;
    // Along the step as far as the earliest impact.
    const BlendMotion step = BlendMotion::From(X_AP_, v, w);
    const ImpactResult hit = search_.Earliest(step, {l, 0.5 * l, lambda, remaining()});
    visited += hit.nodes_visited;
    work += hit.nodes_visited + hit.steps;
    degraded = degraded || hit.degraded;
    X_AP_ = step.At(hit.t);
    if (!hit.hit) break;  // the step completed: the constrained goal is reached
  }

  // The spring between proxy and B, and its derivative with the proxy sliding.
  const Pose X_WP = X_WA * X_AP_;
  const Eigen::Vector3d phi = CalcRotationVector(X_WP.rotation * X_WB.rotation.conjugate());
  out.on_B.force = k * (X_WP.translation - X_WB.translation);
  out.on_B.torque = kr * phi;
  if (pushing > 0) SlidingStiffness(G, k, kr, X_WA, &out.K_B);
  // The pushing constraints as contacts, when kept: their depth in B at the query's pose.
  if (contacts_.keeping()) {
    const Eigen::Matrix3d R_WA = X_WA.R();
    const Pose X_BW = X_WB.Inverse();
    for (int i = 0; i < last_n; ++i) {
      if (!(multiplier_[i] > 0)) continue;
      const Eigen::Vector3d p_W = X_WA * near_[i].p_A;
      const double d = search_.field().Distance(X_BW * p_W);
      contacts_.Add(p_W, -(R_WA * near_[i].gradient_A).normalized(), std::max(0.0, -d));
    }
  }
  out.stats.points_in_contact = pushing;
  out.stats.nodes_visited = visited;
  out.stats.level_rendered = degraded ? -1 : search_.shell().num_levels() - 1;
  out.stats.degraded = degraded ? 1 : 0;
  out.stats.max_penetration = deepest;
  return out;
}

}  // namespace contactlab
