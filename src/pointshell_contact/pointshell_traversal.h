// The two traversals of the paper's contact model (Barbič & James 2008, sec. 3), shared by
// the rigid and the deformable pointshell models. What differs between them — where a point
// is, a node's bounding radius, and how long a culled node may sleep under temporal
// coherence — is a policy type with inline members, so the rigid loop compiles to exactly its
// own code (no branch per point on "deformable?"):
//
//   struct Policy {
//     // One of the two: point i's d in B's field, adding its force when d < 0; or, many
//     // points at once (BatchPolicy), D[k] for point INDEX[k], or for point BEGIN + k when
//     // INDEX is null, k < N, adding the force of each point in contact.
//     float EvaluatePoint(int i);
//     void EvaluatePoints(int begin, const std::int32_t* index, int n, float* d);
//     float Radius(int node) const;      // bounding radius of the node's subtree this cycle
//     bool Asleep(int node) const;       // temporal coherence: skip the node this cycle
//     void Sleep(int node, double margin);  // the node's ball is MARGIN (> 0) clear of contact
//   };
#pragma once

#include <algorithm>
#include <concepts>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "contact/contact_accumulator.h"
#include "contact/contact_model.h"
#include "contact/float_transform.h"
#include "pointshell_contact/pointshell_contact_params.h"
#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab {

// Adds a point in contact at p_BQ (B's frame) with distance D < 0 and unit normal N_A (A's
// frame): the sec. 5 halfspace gradient, or the field's own gradient FIELD_GRADIENT(p_B) (a
// callable returning B's field gradient at p_B, called only for ContactGradient::kField).
// Writes the normal in B's frame to N_B.
template <class FieldGradient>
inline void AddContactPointWith(const FloatTransform& X_BA, const float* n_A, const float* p_BQ, float d,
                                ContactGradient gradient, ContactAccumulator* acc, FieldGradient&& field_gradient,
                                float* n_B) {
  X_BA.Rotate(n_A[0], n_A[1], n_A[2], n_B);
  const Eigen::Vector3d p(p_BQ[0], p_BQ[1], p_BQ[2]);
  const Eigen::Vector3d N(n_B[0], n_B[1], n_B[2]);
  if (gradient == ContactGradient::kHalfspace) {
    acc->Add(p, N, d, N);
  } else {
    acc->Add(p, N, d, field_gradient(p));
  }
}

// AddContactPointWith for a rigid field B: its trilinear gradient.
inline void AddContactPoint(const DistanceField& field, const FloatTransform& X_BA, const float* n_A,
                            const float* p_BQ, float d, ContactGradient gradient, ContactAccumulator* acc) {
  float n_B[3];
  AddContactPointWith(X_BA, n_A, p_BQ, d, gradient, acc,
                      [&field](const Eigen::Vector3d& p) {
                        Eigen::Vector3d g_B;
                        field.DistanceAndGradient(p, &g_B);
                        return g_B;
                      },
                      n_B);
}

// A policy that evaluates a batch of points at once (the vectorised lookups).
template <class Policy>
concept BatchPolicy = requires(Policy& p, const std::int32_t* index, int n, float* d) {
  { p.EvaluatePoints(0, index, n, d) };
};

// Scratch of the tree traversal, sized once for a shell.
class TreeTraversalState {
 public:
  TreeTraversalState() = default;
  explicit TreeTraversalState(const Pointshell& s)
      : queue_a_(std::size_t(s.num_nodes())),
        queue_b_(std::size_t(s.num_nodes())),
        queue_d_a_(std::size_t(s.num_nodes())),
        queue_d_b_(std::size_t(s.num_nodes())),
        evaluated_(std::size_t(s.num_nodes())),  // at most one entry per node visited, whatever the tree
        evaluated_d_(std::size_t(s.num_nodes())),
        mark_stamp_(std::size_t(s.num_points()), 0u),
        mark_d_(std::size_t(s.num_points()), 0.f) {}

  int last_level_rendered() const { return last_level_rendered_; }
  void Reset() {
    last_level_rendered_ = -1;
    num_evaluated_ = 0;
    ++runs_;
  }
  // The points whose distance the last cycle evaluated, [0, num_evaluated()), with their d.
  int num_evaluated() const { return num_evaluated_; }
  const std::int32_t* evaluated_points() const { return evaluated_.data(); }
  const float* evaluated_distances() const { return evaluated_d_.data(); }

  // ContactModel::PointStates of the latest Run. The first call after a Run spreads its list of
  // evaluated points over a per-point stamp (O(points evaluated)); every call then reads the
  // stamps of POINTS. The traversal itself never touches the stamps.
  int PointStates(std::span<const std::int32_t> points, PointState* out) {
    if (marked_run_ != runs_) {
      if (++mark_value_ == 0) {  // the stamp wrapped: clear it
        std::fill(mark_stamp_.begin(), mark_stamp_.end(), 0u);
        mark_value_ = 1;
      }
      for (int k = 0; k < num_evaluated_; ++k) {
        mark_stamp_[evaluated_[k]] = mark_value_;
        mark_d_[evaluated_[k]] = evaluated_d_[k];
      }
      marked_run_ = runs_;
    }
    for (std::size_t k = 0; k < points.size(); ++k) {
      const std::int32_t i = points[k];
      out[k] = mark_stamp_[i] != mark_value_ ? PointState::kNotEvaluated
               : mark_d_[i] < 0.f            ? PointState::kInContact
                                             : PointState::kClear;
    }
    return int(points.size());
  }

  // Breadth-first traversal of S down to MAX_LEVEL (sec. 3): a node is culled with its subtree
  // when its point's d exceeds LIPSCHITZ times its radius; with a node budget (> 0) a level
  // is rendered only if the nodes visited so far plus its queue fit the warm threshold (the
  // cold one, COLD_FRACTION of it, for a level deeper than last cycle's). Each point's
  // distance is evaluated (and its force added) once per cycle: a node's first child is the
  // same point one level down (ValidatePointshellTree), so it inherits the parent's d, and
  // every other node is a point's first instance. Fills STATS' traversal counts.
  template <class Policy>
  void Run(const Pointshell& s, int max_level, const PointshellContactParams& params, std::int64_t budget,
           Policy& policy, ContactStats* stats) {
    constexpr float kUnknown = std::numeric_limits<float>::quiet_NaN();  // d not known yet
    const float lip = float(params.lipschitz);
    const double warm = double(budget);
    const double cold = params.cold_fraction * double(budget);
    // A level's queue holds its awake nodes only: asleep ones are dropped as they are queued
    // (counted in `queued` for the budget and in `asleep` for the statistics), and the points
    // the awake ones see first are listed for the level's batch, [first, evaluated).
    struct LevelQueue {
      std::int32_t* node;
      float* d;  // the node's point's d, NaN when not known
      std::int64_t size = 0, queued = 0;
      std::int32_t asleep = 0;
      int first = 0;
    };
    int evaluated = 0;
    auto enqueue = [&](LevelQueue& q, std::int32_t node, float d) {
      ++q.queued;
      if (params.coherence && policy.Asleep(node)) {
        ++q.asleep;
        return;
      }
      q.node[q.size] = node;
      q.d[q.size++] = d;
      if (d != d) evaluated_[evaluated++] = s.node_point[node];
    };
    LevelQueue current{queue_a_.data(), queue_d_a_.data()};
    LevelQueue next{queue_b_.data(), queue_d_b_.data()};
    for (int n = s.level_node_begin[0]; n < s.level_node_begin[1]; ++n) enqueue(current, n, kUnknown);

    std::int64_t visited = 0;
    std::int32_t skipped = 0;
    int rendered = -1;
    for (int level = 0; level <= max_level; ++level) {
      if (current.queued == 0) {  // everything culled: deeper levels add nothing
        rendered = max_level;
        break;
      }
      if (level > 0 && budget > 0) {  // graceful degradation
        const double threshold = level <= last_level_rendered_ ? warm : cold;
        if (double(visited + current.queued) > threshold) {
          evaluated = current.first;  // the level is not rendered
          break;
        }
      }
      const bool leaf_level = (level == max_level) || (level + 1 >= s.num_levels());
      visited += current.size;
      skipped += current.asleep;
      // 1. The distances (and forces) of the points the level sees first, as one batch.
      std::int32_t* batch = evaluated_.data() + current.first;
      float* batch_d = evaluated_d_.data() + current.first;
      const int batch_size = evaluated - current.first;
      if constexpr (BatchPolicy<Policy>) {
        policy.EvaluatePoints(0, batch, batch_size, batch_d);
      } else {
        for (int b = 0; b < batch_size; ++b) batch_d[b] = policy.EvaluatePoint(batch[b]);
      }
      // 2. Cull a node whose ball is clear of contact, else queue its children.
      next.size = next.queued = 0;
      next.asleep = 0;
      next.first = evaluated;
      int b = 0;
      for (std::int64_t k = 0; k < current.size; ++k) {
        const std::int32_t node = current.node[k];
        float d = current.d[k];
        if (d != d) d = batch_d[b++];
        const float radius = leaf_level ? 0.f : policy.Radius(node);
        if (d > lip * radius) {
          if (params.coherence) policy.Sleep(node, double(d - lip * radius));
          continue;
        }
        if (leaf_level) continue;
        const std::int32_t cb = s.child_begin[node], ce = s.child_begin[node + 1];
        for (std::int32_t c = cb; c < ce; ++c) enqueue(next, c, c == cb ? d : kUnknown);
      }
      rendered = level;
      std::swap(current, next);
    }
    last_level_rendered_ = rendered;
    num_evaluated_ = evaluated;
    ++runs_;
    stats->nodes_visited = visited;
    stats->level_rendered = rendered;
    stats->nodes_skipped_coherence = skipped;
    stats->degraded = rendered < max_level ? max_level - std::max(rendered, 0) : 0;
  }

 private:
  std::vector<std::int32_t> queue_a_, queue_b_;  // (#N) traversal queues: nodes
  std::vector<float> queue_d_a_, queue_d_b_;     // (#N) and their point's d, NaN when not known
  std::vector<std::int32_t> evaluated_;          // (#N) points evaluated this cycle, level by level
  std::vector<float> evaluated_d_;               // (#N) their distances
  int num_evaluated_ = 0;
  int last_level_rendered_ = -1;
  std::uint32_t runs_ = 0;                  // Run and Reset calls
  std::uint32_t marked_run_ = ~0u;          // runs_ when the marks below were spread
  std::vector<std::uint32_t> mark_stamp_;   // (#P) PointStates: mark_value_ when evaluated
  std::vector<float> mark_d_;               // (#P) and its d
  std::uint32_t mark_value_ = 0;
};

// The tree-less reference: every point of tree levels 0..MAX_LEVEL, in order.
template <class Policy>
void RunLinearTraversal(const Pointshell& s, int max_level, Policy& policy, ContactStats* stats) {
  const int n = s.level_point_end[max_level];
  if constexpr (BatchPolicy<Policy>) {
    constexpr int kChunk = 512;  // distances on the stack, in L1
    float d[kChunk];
    for (int begin = 0; begin < n; begin += kChunk) policy.EvaluatePoints(begin, nullptr, std::min(kChunk, n - begin), d);
  } else {
    for (int i = 0; i < n; ++i) policy.EvaluatePoint(i);
  }
  stats->nodes_visited = n;
  stats->level_rendered = max_level;
}

// ContactModel::PointStates of the linear traversal, which keeps no per-point record: every
// point of tree levels 0..MAX_LEVEL was evaluated, and DISTANCES(index, n, d) evaluates the d of
// points INDEX[0..n) again at the latest query (no force added), rounded as the query's own
// lookups. At most kLinearPointStatesPerCall points per call, so the re-evaluation adds a few
// microseconds to a cycle.
constexpr int kLinearPointStatesPerCall = 256;
template <class Distances>
int LinearPointStates(const Pointshell& s, int max_level, std::span<const std::int32_t> points, PointState* out,
                      Distances&& distances) {
  const int n = int(std::min<std::size_t>(points.size(), kLinearPointStatesPerCall));
  float d[kLinearPointStatesPerCall];
  distances(points.data(), n, d);
  const int end = s.level_point_end[max_level];
  for (int k = 0; k < n; ++k) {
    out[k] = points[k] >= end ? PointState::kNotEvaluated : d[k] < 0.f ? PointState::kInContact : PointState::kClear;
  }
  return n;
}

}  // namespace contactlab
