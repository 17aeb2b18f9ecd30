// Continuous collision of a pointshell against a distance field (time_of_impact.h).
#include "baselines/pointshell_ccd/time_of_impact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "geometry/rotation_math.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Conservative-advancement steps a tree node takes before handing its time to its children.
constexpr int kNodeSteps = 4;
// Steps a point takes before it stops where it is (a safe time, earlier than its impact).
constexpr int kPointSteps = 64;
// Points the leaf level steps at once: their steps are independent, and the processor overlaps
// them.
constexpr int kLanes = 4;
// Regula-falsi iterations and the bracket width (in t) at which the impact is taken.
constexpr int kRefineSteps = 60;
constexpr double kRefineWidth = 1e-10;

// Where B is at one pose: p_B = Rt (p_A - o).
struct Frame {
  Eigen::Matrix3d Rt;
  Eigen::Vector3d o;
};

double DistanceAt(const DistanceField& field, const Frame& F, const Eigen::Vector3d& p_A) {
  const Eigen::Vector3d q = F.Rt * (p_A - F.o);
  return field.Distance(float(q.x()), float(q.y()), float(q.z()));
}

// The frame of B at pose (R0, O0), the start of a motion from there.
Frame StartFrame(const Eigen::Quaterniond& R0, const Eigen::Vector3d& o0) {
  return {R0.toRotationMatrix().transpose(), o0};
}

// Where a point of A is in B's frame along one motion. With R(t) = exp(φ [k]) R0, φ = t θ,
//     q(t) = R0^T exp(-φ [k]) (a - t v),   a = p - o0,
// and exp(-φ [k]) x = x cos φ - (k x x) sin φ + k (k·x) (1 - cos φ), so with the point's
// A1 = R0^T a, A2 = R0^T (k x a), ka = k·a and the motion's K = R0^T k, V1 = R0^T v,
// V2 = R0^T (k x v), kv = k·v:
//     q(t) = c A1 - s A2 + (1 - c) ka K - t (c V1 - s V2 + (1 - c) kv K).
// A point's terms are made once (PointPath); each time then costs a few products, where a
// frame per time (a quaternion, its matrix, a matrix product) cost about three times as much.
// At t = 0 the sum is A1 bit for bit: the start frame's R0^T (p - o0), as Near computes it.
class MotionPaths {
 public:
  struct PointPath {
    Eigen::Vector3d A1, A2;
    double ka = 0;
  };

  explicit MotionPaths(const BlendMotion& m) : theta_(m.w.norm()) {
    k_ = theta_ > 0 ? Eigen::Vector3d(m.w / theta_) : Eigen::Vector3d::Zero();
    R0t_ = m.R0.toRotationMatrix().transpose();
    o0_ = m.o0;
    K_ = R0t_ * k_;
    V1_ = R0t_ * m.v;
    V2_ = R0t_ * k_.cross(m.v);
    kv_ = k_.dot(m.v);
  }
  double theta() const { return theta_; }

  PointPath Of(const Eigen::Vector3d& p_A) const {
    const Eigen::Vector3d a = p_A - o0_;
    return {R0t_ * a, R0t_ * k_.cross(a), k_.dot(a)};
  }

  // The point in B's frame at T.
  Eigen::Vector3d At(const PointPath& P, double t) const {
    if (theta_ == 0) return P.A1 - t * V1_;
    // cos φ, sin φ and 1 - cos φ; below 0.1 rad by their series (the first term left out is
    // below 1e-17 of the sum).
    const double phi = t * theta_;
    double c, sn, omc;
    if (phi < 0.1) {
      const double p2 = phi * phi;
      sn = phi * (1 - p2 * (1.0 / 6) * (1 - p2 * (1.0 / 20) * (1 - p2 * (1.0 / 42) * (1 - p2 * (1.0 / 72)))));
      omc = p2 * 0.5 * (1 - p2 * (1.0 / 12) * (1 - p2 * (1.0 / 30) * (1 - p2 * (1.0 / 56) * (1 - p2 * (1.0 / 90)))));
      c = 1 - omc;
    } else {
      sn = std::sin(phi);
      c = std::cos(phi);
      const double half = std::sin(0.5 * phi);
      omc = 2 * half * half;
    }
    const Eigen::Vector3d point = c * P.A1 - sn * P.A2 + (omc * P.ka) * K_;
    const Eigen::Vector3d travel = c * V1_ - sn * V2_ + (omc * kv_) * K_;
    return point - t * travel;
  }

  double DistanceAt(const DistanceField& field, const PointPath& P, double t) const {
    const Eigen::Vector3d q = At(P, t);
    return field.Distance(float(q.x()), float(q.y()), float(q.z()));
  }

 private:
  double theta_;
  Eigen::Matrix3d R0t_;
  Eigen::Vector3d o0_, k_, K_, V1_, V2_;
  double kv_ = 0;
};

// What every impact search along one motion reads: B's field along the motion's paths, the level
// points stop at, the Lipschitz bound λ and the slack eps.
struct LevelAlongMotion {
  const DistanceField& field;
  const MotionPaths& paths;
  double level, lambda, eps;
  double DistanceAt(const MotionPaths::PointPath& P, double t) const { return paths.DistanceAt(field, P, t); }
};

// The crossing of a point (its path P) through LVL, bracketed in [A, B] with f(a) > 0 >= f(b),
// f = d - LVL. Illinois regula falsi; the impact is taken at a (a time at which the point is
// still above its level).
double RefineCrossing(const LevelAlongMotion& m, const MotionPaths::PointPath& P, double lvl, double a, double fa,
                      double b, double fb) {
  int side = 0;
  for (int it = 0; it < kRefineSteps && b - a > kRefineWidth; ++it) {
    double t = b - fb * (b - a) / (fb - fa);
    if (!(t > a && t < b)) t = 0.5 * (a + b);
    const double ft = m.DistanceAt(P, t) - lvl;
    if (ft > 0) {
      a = t, fa = ft;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = t, fb = ft;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  return a;
}

// max(|C - O0|, |C - O1|) with one square root (the larger square's root is the larger root,
// bit for bit).
double FartherEnd(const Eigen::Vector3d& c, const Eigen::Vector3d& o0, const Eigen::Vector3d& o1) {
  return std::sqrt(std::max((c - o0).squaredNorm(), (c - o1).squaredNorm()));
}

// A node's distance at its start time when known, else null: inherited from its parent (KNOWN,
// NaN when not), or kept by Near (START: null when not).
const float* KnownDistance(const float& known, const float* start) { return known == known ? &known : start; }

// The earliest time in [T0, T_HIT) at which a point, moving no faster than its speed, reaches
// its level, a step at a time: Begin, then Step until it says it is done. Each step looks the
// field up once and the next depends on it, so one point's steps wait for each other; the leaf
// level of the search keeps kLanes points going at once, their steps independent.
class PointSteps {
 public:
  // Starts point P_A (A's frame) moving at SPEED from T0, D0_KNOWN its distance there when
  // known (else null), T_HIT the earliest impact so far. True when it is done already, with its
  // time in *OUT.
  bool Begin(const LevelAlongMotion& m, const Eigen::Vector3d& p_A, double speed, double t0, const float* d0_known,
             double t_hit, double* out) {
    t_ = t0;
    if (!d0_known) P_ = m.paths.Of(p_A);
    const double d0 = d0_known ? double(*d0_known) : m.DistanceAt(P_, t_);
    lvl_ = t0 == 0 ? std::min(m.level, d0 - m.eps) : m.level;
    // Steps may pass a dip down to the field's zero (never below it), or eps below a level
    // that is itself below eps.
    dip_ = std::max(m.eps, lvl_);
    ls_ = m.lambda * speed;
    f_ = d0 - lvl_;
    steps_ = 0;
    if (!(f_ > 0)) {
      *out = f_ <= 0 ? t0 : 2.0;  // at the level at t0 (NaN: a field without values here)
      return true;
    }
    // The first step as Step takes it when it passes T_HIT without a lookup (a later, earlier
    // T_HIT would end it the same way): most points far from B end here, their path unmade.
    if (t_ + std::max(f_, dip_) / ls_ >= t_hit && f_ >= ls_ * (t_hit - t_)) {
      *out = 2.0;
      return true;
    }
    if (d0_known) P_ = m.paths.Of(p_A);
    return false;
  }

  // The time the point has safely reached.
  double time() const { return t_; }

  // One step with T_HIT the earliest impact so far. True when the point is done: *OUT is the
  // time it reaches its level, or T_HIT or later when it does not before T_HIT.
  bool Step(const LevelAlongMotion& m, double t_hit, double* out) {
    if (steps_ == kPointSteps) {
      *out = t_;  // out of steps: safe up to here
      return true;
    }
    ++steps_;
    const double t1 = t_ + std::max(f_, dip_) / ls_;
    if (t1 >= t_hit) {
      // The step passes the earliest impact so far. If the point may have reached its level
      // by then and is below it there, the crossing is bracketed; otherwise it dips at most
      // DIP below its level before t_hit.
      if (f_ >= ls_ * (t_hit - t_)) {
        *out = 2.0;
        return true;
      }
      const double fe = m.DistanceAt(P_, t_hit) - lvl_;
      *out = fe > 0 ? 2.0 : RefineCrossing(m, P_, lvl_, t_, f_, t_hit, fe);
      return true;
    }
    const double f1 = m.DistanceAt(P_, t1) - lvl_;
    if (f1 <= 0) {
      *out = RefineCrossing(m, P_, lvl_, t_, f_, t1, f1);
      return true;
    }
    t_ = t1;
    f_ = f1;
    return false;
  }

 private:
  MotionPaths::PointPath P_;
  double t_ = 0, f_ = 0, lvl_ = 0, dip_ = 0, ls_ = 0;  // ls: λ times the speed
  int steps_ = 0;
};

// Whether NODE_BUDGET (<= 0: none) leaves no room for WANTED more nodes or steps.
bool BudgetShort(std::int64_t node_budget, const ImpactResult& result, std::int64_t wanted) {
  return node_budget > 0 && result.nodes_visited + result.steps + wanted > node_budget;
}

// The budget stops a point or node at T: it (its subtree) reaches the level no earlier, so the
// impact is T at the latest (*T_HIT, RESULT).
void CutAt(double t, double* t_hit, ImpactResult* result) {
  result->degraded = true;
  if (t < *t_hit) {
    result->hit = true;
    result->point = -1;
    *t_hit = t;
  }
}

// Past NODE_BUDGET a queued point or node (starting at T < *T_HIT) is not expanded: CutAt(T).
// True when that is so.
bool BudgetCutsAt(std::int64_t node_budget, double t, double* t_hit, ImpactResult* result) {
  if (!BudgetShort(node_budget, *result, 1)) return false;
  CutAt(t, t_hit, result);
  return true;
}

// The tree's last level (SHELL's nodes QUEUE[k] from times QUEUE_T[k], their distance there
// QUEUE_D[k] when inherited, NaN when not, in that order): each point's earliest impact before
// *T_HIT, kLanes points in flight, *T_HIT and RESULT updated as they finish.
// START_DISTANCE(node): its distance kept by Near, or null. Past NODE_BUDGET the queued points
// are cut (BudgetCutsAt) and those in flight stop at the time they have safely reached.
template <class StartDistanceOf>
void LeafLevel(const Pointshell& s, const std::vector<std::int32_t>& queue, const std::vector<double>& queue_t,
               const std::vector<float>& queue_d, const LevelAlongMotion& along, const BlendMotion& motion, std::int64_t node_budget,
               StartDistanceOf&& start_distance, double* t_hit, ImpactResult* result) {
  const double theta = along.paths.theta(), travel = motion.v.norm();
  const Eigen::Vector3d o1 = motion.o0 + motion.v;
  PointSteps lane[kLanes];
  std::int32_t lane_point[kLanes];
  int busy = 0;
  auto done = [&](double ti, std::int32_t ip) {
    if (ti < *t_hit) {
      *t_hit = ti;
      result->hit = true;
      result->point = ip;
    }
  };
  std::size_t k = 0;
  while (k < queue.size() || busy > 0) {
    // Fill the free lanes from the queue, in its order.
    while (busy < kLanes && k < queue.size()) {
      const std::int32_t n = queue[k];
      const float& known = queue_d[k];
      const double t = queue_t[k++];
      if (t >= *t_hit) continue;
      if (BudgetCutsAt(node_budget, t, t_hit, result)) continue;
      ++result->nodes_visited;
      const std::int32_t ip = s.node_point[n];
      const Eigen::Vector3d c(s.x[ip], s.y[ip], s.z[ip]);
      const double speed = theta * (FartherEnd(c, motion.o0, o1) + s.node_radius[n]) + travel;
      if (!(speed > 0)) continue;  // a point on the rotation axis at B's origin does not move
      double ti;
      if (lane[busy].Begin(along, c, speed, t, KnownDistance(known, t == 0 ? start_distance(n) : nullptr), *t_hit,
                           &ti)) {
        done(ti, ip);
      } else {
        lane_point[busy++] = ip;
      }
    }
    // Past the budget the points in flight stop where they are: none reaches its level before.
    if (busy > 0 && BudgetShort(node_budget, *result, busy)) {
      for (int i = 0; i < busy; ++i) CutAt(lane[i].time(), t_hit, result);
      busy = 0;
      continue;
    }
    // One step of every point in flight; a point that is done hands its lane to the last one.
    result->steps += busy;
    for (int i = 0; i < busy;) {
      double ti;
      if (lane[i].Step(along, *t_hit, &ti)) {
        done(ti, lane_point[i]);
        --busy;
        lane[i] = lane[busy];
        lane_point[i] = lane_point[busy];
      } else {
        ++i;
      }
    }
  }
}

// Conservative advancement of a node (centre C in A's frame, bounding radius R, moving no
// faster than SPEED) from T, a step at a time like PointSteps: the time from which its subtree
// may reach the level, at most kNodeSteps steps on; T_HIT or later when none of it can before
// T_HIT. With the time, the distance of C there when the last step looked it up there (NaN
// otherwise), which the node's first child, the same point, starts from.
class NodeSteps {
 public:
  // Starts the node from T, D_T its distance there when known (else null). True when it is
  // done already (on D_T), with its time and distance in *T_OUT, *D_OUT.
  bool Begin(const LevelAlongMotion& m, const Eigen::Vector3d& c, double r, double speed, double t, double t_hit,
             const float* d_t, double* t_out, float* d_out) {
    c_ = c;
    r_ = r;
    speed_ = speed;
    t_ = t;
    step_ = 0;
    made_ = false;
    if (!d_t) return false;
    return Advance(m, double(*d_t), t_hit, t_out, d_out);
  }

  // The time from which the subtree may reach the level, as far as the steps so far say.
  double time() const { return t_; }

  // One step (a lookup) with T_HIT the earliest impact so far; as Begin.
  bool Step(const LevelAlongMotion& m, double t_hit, double* t_out, float* d_out) {
    if (!made_) {  // made at the first lookup: a node culled on its known distance needs none
      P_ = m.paths.Of(c_);
      made_ = true;
    }
    return Advance(m, m.DistanceAt(P_, t_), t_hit, t_out, d_out);
  }

 private:
  // The step from the distance D at the node's time.
  bool Advance(const LevelAlongMotion& m, double d, double t_hit, double* t_out, float* d_out) {
    const double f = d - m.lambda * r_ - m.level;
    if (!(f > m.eps)) {  // may reach the level from t on
      *t_out = t_;
      *d_out = float(d);
      return true;
    }
    t_ += f / (m.lambda * speed_);
    if (++step_ == kNodeSteps || t_ >= t_hit) {
      *t_out = t_;
      *d_out = std::numeric_limits<float>::quiet_NaN();
      return true;
    }
    return false;
  }

  MotionPaths::PointPath P_;
  Eigen::Vector3d c_;
  double r_ = 0, speed_ = 0, t_ = 0;
  int step_ = 0;
  bool made_ = false;
};

// One level above the last (SHELL's nodes QUEUE[k] from times QUEUE_T[k], their distance there
// QUEUE_D[k] when inherited, NaN when not): each node's advanced time into ADV_T[k] (infinite
// when it was not advanced) and its distance there into ADV_D[k], kLanes nodes in flight. The
// earliest impact changes only where the budget cuts a node (*T_HIT, RESULT), in queue order,
// so each node advances exactly as it would alone; past the budget the nodes in flight keep the
// time they have reached (their subtrees may reach the level from there). START_DISTANCE as for
// LeafLevel.
template <class StartDistanceOf>
void NodeLevel(const Pointshell& s, const std::vector<std::int32_t>& queue, const std::vector<double>& queue_t,
               const std::vector<float>& queue_d, const LevelAlongMotion& along, const BlendMotion& motion,
               std::int64_t node_budget, StartDistanceOf&& start_distance, double* t_hit, ImpactResult* result,
               std::vector<double>* adv_t, std::vector<float>* adv_d) {
  const double theta = along.paths.theta(), travel = motion.v.norm();
  const Eigen::Vector3d o1 = motion.o0 + motion.v;
  adv_t->assign(queue.size(), std::numeric_limits<double>::infinity());
  adv_d->resize(queue.size());
  NodeSteps lane[kLanes];
  std::size_t lane_k[kLanes];
  int busy = 0;
  std::size_t k = 0;
  while (k < queue.size() || busy > 0) {
    // Fill the free lanes from the queue, in its order.
    while (busy < kLanes && k < queue.size()) {
      const std::size_t j = k++;
      const std::int32_t n = queue[j];
      const double t = queue_t[j];
      if (t >= *t_hit) continue;
      if (BudgetCutsAt(node_budget, t, t_hit, result)) continue;
      ++result->nodes_visited;
      const std::int32_t ip = s.node_point[n];
      const Eigen::Vector3d c(s.x[ip], s.y[ip], s.z[ip]);
      const double r = s.node_radius[n];
      const double speed = theta * (FartherEnd(c, motion.o0, o1) + r) + travel;
      if (!(speed > 0)) continue;  // a point on the rotation axis at B's origin does not move
      const float* known = KnownDistance(queue_d[j], t == 0 ? start_distance(n) : nullptr);
      if (!lane[busy].Begin(along, c, r, speed, t, *t_hit, known, &(*adv_t)[j], &(*adv_d)[j])) lane_k[busy++] = j;
    }
    // Past the budget the nodes in flight stop where they are: their subtrees may reach the
    // level from there on.
    if (busy > 0 && BudgetShort(node_budget, *result, busy)) {
      result->degraded = true;
      for (int i = 0; i < busy; ++i) {
        (*adv_t)[lane_k[i]] = lane[i].time();
        (*adv_d)[lane_k[i]] = std::numeric_limits<float>::quiet_NaN();
      }
      busy = 0;
      continue;
    }
    // One step of every node in flight; a node that is done hands its lane to the last one.
    result->steps += busy;
    for (int i = 0; i < busy;) {
      const std::size_t j = lane_k[i];
      if (lane[i].Step(along, *t_hit, &(*adv_t)[j], &(*adv_d)[j])) {
        --busy;
        lane[i] = lane[busy];
        lane_k[i] = lane_k[busy];
      } else {
        ++i;
      }
    }
  }
}

}  // namespace

BlendMotion BlendMotion::Between(const Pose& X0, const Pose& X1) {
  // The rotation vector of X1 X0^-1, angle in [0, pi]: the shorter way round.
  return {X0.rotation, X0.translation, X1.translation - X0.translation,
          CalcRotationVector((X1.rotation * X0.rotation.conjugate()).normalized())};
}

Pose BlendMotion::At(double t) const { return {(RotationFromVector(t * w) * R0).normalized(), o0 + t * v}; }

ImpactSearch::ImpactSearch(std::shared_ptr<const Pointshell> shell, std::shared_ptr<const DistanceField> field)
    : shell_(std::move(shell)), field_(std::move(field)) {
  if (!shell_ || !field_ || field_->empty()) Fail("continuous collision", "needs a pointshell and a distance field");
  const std::size_t nodes = std::size_t(shell_->num_nodes());
  queue_.reserve(nodes);
  next_.reserve(nodes);
  queue_t_.reserve(nodes);
  next_t_.reserve(nodes);
  queue_d_.reserve(nodes);
  next_d_.reserve(nodes);
  band_.reserve(nodes);
  adv_t_.reserve(nodes);
  adv_d_.reserve(nodes);
  start_stamp_.assign(nodes, 0u);
  start_d_.assign(nodes, 0.f);
}

ImpactResult ImpactSearch::Earliest(const BlendMotion& motion, const ImpactParams& params) {
  ImpactResult result;
  const Pointshell& s = *shell_;
  const DistanceField& field = *field_;
  const MotionPaths paths(motion);
  const double theta = paths.theta(), travel = motion.v.norm();
  if (s.num_levels() == 0 || (theta == 0 && travel == 0)) return result;
  const double lambda = params.lipschitz, level = params.level;
  const double eps = std::max(params.slack, std::numeric_limits<double>::min());
  double t_hit = 1;
  const LevelAlongMotion along{field, paths, level, lambda, eps};
  // The nodes that start at t = 0 take their distance from the latest Near when it ran here.
  start_valid_ = near_kept_ && motion.R0.coeffs() == near_R_.coeffs() && motion.o0 == near_o_;

  // Breadth-first over the tree from its top level, each node with the time it starts at.
  constexpr float kUnknown = std::numeric_limits<float>::quiet_NaN();
  queue_.clear();
  queue_t_.clear();
  queue_d_.clear();
  for (std::int32_t n = s.level_node_begin[0]; n < s.level_node_begin[1]; ++n) {
    queue_.push_back(n);
    queue_t_.push_back(0);
    queue_d_.push_back(kUnknown);
  }
  // Every level but the last: the nodes' conservative advancement. The last: the points'.
  const auto start_distance = [this](std::int32_t n) { return StartDistance(n); };
  const int levels = s.num_levels();
  for (int L = 0; L < levels - 1 && !queue_.empty(); ++L) {
    NodeLevel(s, queue_, queue_t_, queue_d_, along, motion, params.node_budget, start_distance, &t_hit, &result,
              &adv_t_, &adv_d_);
    // The children of the nodes not culled (nothing of a culled node reaches the level before
    // the earliest impact), in the queue's order.
    next_.clear();
    next_t_.clear();
    next_d_.clear();
    for (std::size_t k = 0; k < queue_.size(); ++k) {
      const double t = adv_t_[k];
      if (!(t < t_hit)) continue;
      const std::int32_t n = queue_[k];
      for (std::int32_t ch = s.child_begin[n]; ch < s.child_begin[n + 1]; ++ch) {
        next_.push_back(ch);
        next_t_.push_back(t);
        next_d_.push_back(ch == s.child_begin[n] && s.node_point[ch] == s.node_point[n] ? adv_d_[k] : kUnknown);
      }
    }
    std::swap(queue_, next_);
    std::swap(queue_t_, next_t_);
    std::swap(queue_d_, next_d_);
  }
  LeafLevel(s, queue_, queue_t_, queue_d_, along, motion, params.node_budget, start_distance, &t_hit, &result);
  result.t = t_hit;
  start_valid_ = false;
  return result;
}

int ImpactSearch::Near(const Pose& X_AB, double band, double lipschitz, std::int64_t node_budget, NearPoint* out,
                       int capacity, std::int64_t* visited, bool* degraded) {
  const Pointshell& s = *shell_;
  const DistanceField& field = *field_;
  if (s.num_levels() == 0) return 0;
  const Pose X_BA = X_AB.Inverse();
  const Eigen::Matrix3d R_BA = X_BA.R(), R_AB = X_AB.R();
  // The float lookups as Earliest makes them at a motion's start (kept for it, see the header);
  // a near point's distance and gradient in double at X_BA c.
  const Frame F = StartFrame(X_AB.rotation, X_AB.translation);
  if (++stamp_ == 0) {  // the stamp wrapped: forget every node's
    std::fill(start_stamp_.begin(), start_stamp_.end(), 0u);
    stamp_ = 1;
  }
  near_R_ = X_AB.rotation;
  near_o_ = X_AB.translation;
  near_kept_ = true;
  auto keep = [&](std::int32_t n, float d) {
    start_stamp_[std::size_t(n)] = stamp_;
    start_d_[std::size_t(n)] = d;
    return double(d);
  };
  auto lookup = [&](std::int32_t n, const Eigen::Vector3d& c) { return keep(n, float(DistanceAt(field, F, c))); };
  int written = 0;
  std::int64_t count = 0;
  auto emit = [&](std::int32_t ip, const Eigen::Vector3d& c, double bound) {
    if (written >= capacity) return;
    Eigen::Vector3d g;
    const double d = field.DistanceAndGradient(R_BA * c + X_BA.translation, &g);
    NearPoint& np = out[written++];
    np.point = ip;
    np.distance = std::min(d, bound);
    np.p_A = c;
    np.gradient_A = R_AB * g;
  };
  // Each node with its point's distance when its parent, the same point, looked it up (NaN
  // when not).
  constexpr float kUnknown = std::numeric_limits<float>::quiet_NaN();
  queue_.clear();
  queue_d_.clear();
  for (std::int32_t n = s.level_node_begin[0]; n < s.level_node_begin[1]; ++n) {
    queue_.push_back(n);
    queue_d_.push_back(kUnknown);
  }
  const int levels = s.num_levels();
  for (int L = 0; L < levels && !queue_.empty(); ++L) {
    const bool leaf = L == levels - 1;
    next_.clear();
    next_d_.clear();
    band_.clear();
    for (std::size_t k = 0; k < queue_.size(); ++k) {
      const std::int32_t n = queue_[k];
      const std::int32_t ip = s.node_point[n];
      const Eigen::Vector3d c(s.x[ip], s.y[ip], s.z[ip]);
      const double r = s.node_radius[n];
      const float inherited = queue_d_[k];
      const double d = inherited == inherited ? keep(n, inherited) : lookup(n, c);
      ++count;
      if (d - lipschitz * r > band) continue;
      if (leaf) {
        emit(ip, c, std::numeric_limits<double>::infinity());
        continue;
      }
      band_.push_back(n);
      for (std::int32_t ch = s.child_begin[n]; ch < s.child_begin[n + 1]; ++ch) {
        next_.push_back(ch);
        next_d_.push_back(ch == s.child_begin[n] && s.node_point[ch] == ip ? float(d) : kUnknown);
      }
    }
    if (!leaf && node_budget > 0 && count + std::int64_t(next_.size()) > node_budget) {
      // The next level does not fit: this level's nodes in the band stand for their subtrees,
      // each at its subtree's lower bound.
      if (degraded) *degraded = true;
      for (const std::int32_t n : band_) {
        const std::int32_t ip = s.node_point[n];
        const Eigen::Vector3d c(s.x[ip], s.y[ip], s.z[ip]);
        emit(ip, c, double(start_d_[std::size_t(n)]) - lipschitz * s.node_radius[n]);
      }
      break;
    }
    std::swap(queue_, next_);
    std::swap(queue_d_, next_d_);
  }
  if (visited) *visited += count;
  return written;
}

}  // namespace contactlab
