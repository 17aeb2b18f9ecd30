// The two traversals of the paper's contact model (Barbič & James 2008, sec. 3), shared by
// the rigid and the deformable pointshell models. What differs between them — where a point
// is, a node's bounding radius, and how long a culled node may sleep under temporal
// coherence — is a policy type with inline members, so the rigid loop compiles to exactly its
// own code (no branch per point on "deformable?"):
//
//   struct Policy {
//     float EvaluatePoint(int i);        // d of point i in B's field; adds its force when d < 0
//     float Radius(int node) const;      // bounding radius of the node's subtree this cycle
//     bool Asleep(int node) const;       // temporal coherence: skip the node this cycle
//     void Sleep(int node, double margin);  // the node's ball is MARGIN (> 0) clear of contact
//   };
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "contact/contact_accumulator.h"
#include "contact/contact_model.h"
#include "contact/float_transform.h"
#include "contact/pointshell_contact_params.h"
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

// Scratch of the tree traversal, sized once for a shell.
class TreeTraversalState {
 public:
  TreeTraversalState() = default;
  explicit TreeTraversalState(const Pointshell& s)
      : queue_a_(std::size_t(s.num_nodes())),
        queue_b_(std::size_t(s.num_nodes())),
        point_stamp_(std::size_t(s.num_points()), 0u),
        point_d_(std::size_t(s.num_points()), 0.f) {}

  int last_level_rendered() const { return last_level_rendered_; }
  void Reset() { last_level_rendered_ = -1; }

  // ContactModel::PointStates of the latest Run: a point was evaluated when it carries the
  // current stamp, and is in contact when its cached d < 0. Reads the stamps only.
  int PointStates(std::span<const std::int32_t> points, PointState* out) const {
    for (std::size_t k = 0; k < points.size(); ++k) {
      const std::int32_t i = points[k];
      out[k] = stamp_ == 0 || point_stamp_[i] != stamp_ ? PointState::kNotEvaluated
               : point_d_[i] < 0.f                     ? PointState::kInContact
                                                       : PointState::kClear;
    }
    return int(points.size());
  }

  // Breadth-first traversal of S down to MAX_LEVEL (sec. 3): a node is culled with its subtree
  // when its point's d exceeds LIPSCHITZ times its radius; with a node budget (> 0) a level
  // is rendered only if the nodes visited so far plus its queue fit the warm threshold (the
  // cold one, COLD_FRACTION of it, for a level deeper than last cycle's). Each point's
  // distance is evaluated (and its force added) once per cycle however many of its instances
  // are visited. Fills STATS' traversal counts.
  template <class Policy>
  void Run(const Pointshell& s, int max_level, const PointshellContactParams& params, std::int64_t budget,
           Policy& policy, ContactStats* stats) {
    if (++stamp_ == 0) {  // a new stamp marks the points already evaluated this cycle
      std::fill(point_stamp_.begin(), point_stamp_.end(), 0u);
      stamp_ = 1;
    }
    const float lip = float(params.lipschitz);
    const double warm = double(budget);
    const double cold = params.cold_fraction * double(budget);
    std::int32_t* current = queue_a_.data();
    std::int32_t* next = queue_b_.data();
    std::int64_t current_size = 0;
    for (int n = s.level_node_begin[0]; n < s.level_node_begin[1]; ++n) current[current_size++] = n;

    std::int64_t visited = 0;
    std::int32_t skipped = 0;
    int rendered = -1;
    for (int level = 0; level <= max_level; ++level) {
      if (current_size == 0) {  // everything culled: deeper levels add nothing
        rendered = max_level;
        break;
      }
      if (level > 0 && budget > 0) {  // graceful degradation
        const double threshold = level <= last_level_rendered_ ? warm : cold;
        if (double(visited + current_size) > threshold) break;
      }
      const bool leaf_level = (level == max_level) || (level + 1 >= s.num_levels());
      std::int64_t next_size = 0;
      for (std::int64_t k = 0; k < current_size; ++k) {
        const std::int32_t node = current[k];
        if (params.coherence && policy.Asleep(node)) {
          ++skipped;
          continue;
        }
        ++visited;
        const std::int32_t i = s.node_point[node];
        float d;
        if (point_stamp_[i] == stamp_) {
          d = point_d_[i];
        } else {
          d = policy.EvaluatePoint(i);
          point_stamp_[i] = stamp_;
          point_d_[i] = d;
        }
        const float radius = leaf_level ? 0.f : policy.Radius(node);
        if (d > lip * radius) {
          if (params.coherence) policy.Sleep(node, double(d - lip * radius));
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
    stats->nodes_visited = visited;
    stats->level_rendered = rendered;
    stats->nodes_skipped_coherence = skipped;
  }

 private:
  std::vector<std::int32_t> queue_a_, queue_b_;  // (#N) traversal queues
  std::vector<std::uint32_t> point_stamp_;       // (#P) evaluation stamp of each point's d
  std::vector<float> point_d_;                   // (#P) d cached for the stamp
  std::uint32_t stamp_ = 0;
  int last_level_rendered_ = -1;
};

// The tree-less reference: every point of tree levels 0..MAX_LEVEL, in order.
template <class Policy>
void RunLinearTraversal(const Pointshell& s, int max_level, Policy& policy, ContactStats* stats) {
  const int n = s.level_point_end[max_level];
  for (int i = 0; i < n; ++i) policy.EvaluatePoint(i);
  stats->nodes_visited = n;
  stats->level_rendered = max_level;
}

// ContactModel::PointStates of the linear traversal, which keeps no per-point record: every
// point of tree levels 0..MAX_LEVEL was evaluated, and DISTANCE(i) evaluates point i's d again at
// the latest query (no force added). At most kLinearPointStatesPerCall points per call, so the
// re-evaluation adds a few microseconds to a cycle.
constexpr int kLinearPointStatesPerCall = 256;
template <class Distance>
int LinearPointStates(const Pointshell& s, int max_level, std::span<const std::int32_t> points, PointState* out,
                      Distance&& distance) {
  const int n = int(std::min<std::size_t>(points.size(), kLinearPointStatesPerCall));
  const int end = s.level_point_end[max_level];
  for (int k = 0; k < n; ++k) {
    const std::int32_t i = points[k];
    out[k] = i >= end ? PointState::kNotEvaluated : distance(i) < 0.f ? PointState::kInContact : PointState::kClear;
  }
  return n;
}

}  // namespace contactlab
