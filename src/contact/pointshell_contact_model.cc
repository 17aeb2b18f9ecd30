// Barbič & James 2008, sec. 2.1, 3 and 5: the pointshell-vs-distance-field contact model.
#include "contact/pointshell_contact_model.h"

#include <cmath>
#include <limits>

#include "contact/float_transform.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Adds point I of the shell, in contact at p_BQ (already in B's frame) with distance D < 0.
inline void AddPoint(const Pointshell& s, const DistanceField& field, const FloatTransform& X_BA, int i,
                     const float* p_BQ, float d, ContactGradient gradient, ContactAccumulator* acc) {
  float n_B[3];
  X_BA.Rotate(s.nx[i], s.ny[i], s.nz[i], n_B);
  const Eigen::Vector3d p(p_BQ[0], p_BQ[1], p_BQ[2]);
  const Eigen::Vector3d N(n_B[0], n_B[1], n_B[2]);
  if (gradient == ContactGradient::kHalfspace) {
    acc->Add(p, N, d, N);
  } else {
    Eigen::Vector3d g_B;
    field.DistanceAndGradient(p, &g_B);
    acc->Add(p, N, d, g_B);
  }
}

}  // namespace

PointshellContactModel::PointshellContactModel(Variant variant, std::shared_ptr<const Pointshell> shell,
                                               std::shared_ptr<const DistanceField> field,
                                               const PointshellContactParams& params)
    : variant_(variant), shell_(std::move(shell)), field_(std::move(field)), params_(params) {
  const std::string where = std::string("contact model ") + std::string(name());
  if (!shell_ || shell_->num_points() == 0 || shell_->num_levels() == 0) Fail(where, "needs a non-empty pointshell");
  if (!field_ || field_->empty()) Fail(where, "needs a distance field");
  CheckPenaltyParams(params.penalty, where);
  if (params.level >= shell_->num_levels() || params.level < -1) {
    Fail(where, "level " + std::to_string(params.level) + " is out of range (the pointshell has " +
                    std::to_string(shell_->num_levels()) + " levels)");
  }
  if (!(params.max_point_speed > 0) || !(params.cycle_seconds > 0) || !(params.lipschitz >= 1)) {
    Fail(where, "max_point_speed and cycle_seconds must be positive and lipschitz >= 1");
  }
  if (!(params.cold_fraction > 0 && params.cold_fraction <= 1)) Fail(where, "cold_fraction must be in (0, 1]");
  max_level_ = params.level < 0 ? shell_->num_levels() - 1 : params.level;
  const std::size_t nodes = std::size_t(shell_->num_nodes());
  queue_a_.resize(nodes);
  queue_b_.resize(nodes);
  point_stamp_.assign(std::size_t(shell_->num_points()), 0);
  point_d_.assign(std::size_t(shell_->num_points()), 0.f);
  earliest_cycle_.assign(nodes, std::numeric_limits<std::int64_t>::min());
}

void PointshellContactModel::Reset() {
  std::fill(earliest_cycle_.begin(), earliest_cycle_.end(), std::numeric_limits<std::int64_t>::min());
  last_level_rendered_ = -1;
}

ContactResult PointshellContactModel::Evaluate(const ContactQuery& query) {
  return variant_ == Variant::kLinear ? EvaluateLinear(query) : EvaluateTree(query);
}

ContactResult PointshellContactModel::EvaluateLinear(const ContactQuery& query) {
  const Pointshell& s = *shell_;
  const DistanceField& field = *field_;
  const FloatTransform X_BA(query.X_WB.Inverse() * query.X_WA);
  ContactAccumulator acc;
  const int n = s.level_point_end[max_level_];
  const float* xs = s.x.data();
  const float* ys = s.y.data();
  const float* zs = s.z.data();
  // Every point of the level: transform into B, look the field up, add if in contact.
  for (int i = 0; i < n; ++i) {
    float p_BQ[3];
    X_BA.Apply(xs[i], ys[i], zs[i], p_BQ);
    const float d = field.Distance(p_BQ[0], p_BQ[1], p_BQ[2]);
    if (d < 0.f) AddPoint(s, field, X_BA, i, p_BQ, d, params_.gradient, &acc);
  }
  ContactResult result;
  acc.Finish(params_.penalty, query.X_WB, &result);
  result.stats.nodes_visited = n;
  result.stats.level_rendered = max_level_;
  return result;
}

ContactResult PointshellContactModel::EvaluateTree(const ContactQuery& query) {
  const Pointshell& s = *shell_;
  const DistanceField& field = *field_;
  const FloatTransform X_BA(query.X_WB.Inverse() * query.X_WA);
  ContactAccumulator acc;

  // A new stamp marks which points already have their distance (and force) this cycle.
  if (++stamp_ == 0) {
    std::fill(point_stamp_.begin(), point_stamp_.end(), 0u);
    stamp_ = 1;
  }
  const double step = params_.lipschitz * params_.max_point_speed * params_.cycle_seconds;
  const float lip = float(params_.lipschitz);
  const std::int64_t budget = query.node_budget;
  const double warm = double(budget);
  const double cold = params_.cold_fraction * double(budget);

  std::int32_t* current = queue_a_.data();
  std::int32_t* next = queue_b_.data();
  // Level 0: every node of the coarsest level.
  std::int64_t current_size = 0;
  for (int nidx = s.level_node_begin[0]; nidx < s.level_node_begin[1]; ++nidx) current[current_size++] = nidx;

  std::int64_t visited = 0;
  std::int32_t skipped = 0;
  int rendered = -1;
  for (int level = 0; level <= max_level_; ++level) {
    // Everything culled: the deeper levels add nothing, so they count as rendered.
    if (current_size == 0) {
      rendered = max_level_;
      break;
    }
    // Graceful degradation: render the level only if its queue fits the threshold.
    if (level > 0 && budget > 0) {
      const double threshold = level <= last_level_rendered_ ? warm : cold;
      if (double(visited + current_size) > threshold) break;
    }
    const bool leaf_level = (level == max_level_) || (level + 1 >= s.num_levels());
    std::int64_t next_size = 0;
    for (std::int64_t q = 0; q < current_size; ++q) {
      const std::int32_t node = current[q];
      // Temporal coherence: the node's ball cannot touch before this cycle.
      if (params_.coherence && query.cycle < earliest_cycle_[node]) {
        ++skipped;
        continue;
      }
      ++visited;
      const std::int32_t i = s.node_point[node];
      float d;
      if (point_stamp_[i] == stamp_) {
        d = point_d_[i];  // an instance of this point was evaluated (and counted) already
      } else {
        float p_BQ[3];
        X_BA.Apply(s.x[i], s.y[i], s.z[i], p_BQ);
        d = field.Distance(p_BQ[0], p_BQ[1], p_BQ[2]);
        point_stamp_[i] = stamp_;
        point_d_[i] = d;
        if (d < 0.f) AddPoint(s, field, X_BA, i, p_BQ, d, params_.gradient, &acc);
      }
      const float radius = leaf_level ? 0.f : s.node_radius[node];
      if (d > lip * radius) {
        if (params_.coherence) {
          // Earliest cycle at which some point of the ball could reach d <= 0.
          const double cycles = std::ceil(double(d - lip * radius) / step);
          earliest_cycle_[node] = query.cycle + std::int64_t(std::min(cycles, 1e15));
        }
        continue;
      }
      if (leaf_level) continue;
      for (std::int32_t c = s.child_begin[node]; c < s.child_begin[node + 1]; ++c) next[next_size++] = c;
    }
    rendered = level;
    std::swap(current, next);
    current_size = next_size;
  }
  last_level_rendered_ = rendered;

  ContactResult result;
  acc.Finish(params_.penalty, query.X_WB, &result);
  result.stats.nodes_visited = visited;
  result.stats.level_rendered = rendered;
  result.stats.nodes_skipped_coherence = skipped;
  return result;
}

}  // namespace contactlab
