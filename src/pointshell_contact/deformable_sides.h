// The deformable sides of the paper's contact model (Barbič & James 2008, sec. 4), answering the
// calls of the rigid sides (contact/rigid_sides.h) and, in addition, where a point's reaction
// goes as a reduced force:
//
//   DeformableShell (sec. 4.1)  points at x = X + U q with the linear normal correction, node
//       radii R(q) = R_0 + sum_j |q_j| rho_j (the point-based BD-tree). For temporal coherence
//       it keeps the q of its last kHistory queries: between a node's sleep and now its ball
//       moved and grew by at most sum_j c_nj |q_j - q_sleep,j| (DeformablePointshell::
//       node_travel, the node's own bound). A point's force F_i (A's frame) enters A's reduced
//       force through U_i^T.
//   DeformedField (sec. 4.2)    distances from the proxies at q_B (nearest k, eq. (3), pulled
//       back through the proxies' deformation gradients, domains combined by minimum). Nothing
//       cheap bounds how fast its distances drop, so the model refuses temporal coherence
//       against it. A point's force enters B's reduced force at its nearest proxy (or the
//       query's k proxies, weighted).
//
// Both take q as float once a query.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

#include "contact/float_transform.h"
#include "pointshell_contact/reduced_force_sum.h"
#include "deform/deformable_pointshell.h"
#include "deform/deformed_distance_field.h"
#include "deform/deformed_field_batch.h"
#include "deform/reduced_point_batch.h"
#include "reduced/reduced_state.h"

namespace contactlab {

// Reduced coordinates of one query in float.
class ReducedCoordinatesF {
 public:
  // Q (null: at rest) for a body of R coordinates. False when Q has another size than R
  // (nothing is changed then).
  bool Load(const ReducedState* q, int r) {
    if (q != nullptr && q->size() != r) return false;
    for (int j = 0; j < r; ++j) {
      const float v = q != nullptr ? float(q->q[j]) : 0.f;
      q_[j] = v;
      abs_q_[j] = std::fabs(v);
    }
    return true;
  }
  // Q and |Q| (r entries, then zeros up to kMaxBasisStride).
  const float* q() const { return q_; }
  const float* abs_q() const { return abs_q_; }

 private:
  alignas(64) float q_[kMaxBasisStride] = {};
  alignas(64) float abs_q_[kMaxBasisStride] = {};
};

class DeformableShell {
 public:
  using Source = std::shared_ptr<const DeformablePointshell>;
  static constexpr bool kDeforms = true;
  static constexpr const char* kWhat = "deformable pointshell";

  DeformableShell() = default;
  explicit DeformableShell(Source shell) : shell_(std::move(shell)) {}
  const Pointshell* get() const { return shell_ ? &shell_->shell() : nullptr; }
  const Pointshell& shell() const { return shell_->shell(); }
  int r() const { return shell_->r(); }

  // Also records Q as this query's entry of the history.
  bool Begin(const ReducedState* q) {
    if (!q_.Load(q, r())) return false;
    ++stamp_;
    std::copy(q_.q(), q_.q() + kMaxBasisStride, history_[stamp_ % kHistory]);
    return true;
  }
  float Radius(int node) const { return shell_->RadiusF(node, q_.abs_q()); }

  // Temporal coherence: this query's stamp, and how far NODE's ball may have moved closer since
  // the query stamped SINCE (infinite once that query has left the history).
  static constexpr std::uint32_t kHistory = 256;
  std::uint32_t stamp() const { return stamp_; }
  float Travel(int node, std::uint32_t since) const {
    if (stamp_ - since >= kHistory) return std::numeric_limits<float>::infinity();
    return shell_->NodeTravelF(node, q_.q(), history_[since % kHistory]);
  }

  // Points INDEX[k] (BEGIN + k when INDEX is null), k < N, at this query's q (A's frame) into
  // X, Y, Z.
  void Positions(const std::int32_t* index, int begin, int n, float* x, float* y, float* z) const {
    const Pointshell& s = shell();
    DeformedPositions(shell_->points(), s.x.data(), s.y.data(), s.z.data(), q_.q(), index, begin, n, x, y, z);
  }
  // The corrected unit normals of points INDEX[k], k < N, at this query's q into NX, NY, NZ.
  void Normals(const std::int32_t* index, int n, float* nx, float* ny, float* nz) const {
    const Pointshell& s = shell();
    CorrectedNormals(shell_->points(), s.nx.data(), s.ny.data(), s.nz.data(), q_.q(), index, n, nx, ny, nz);
  }
  // Points INDEX[k], k < N, in contact at depths D[k] < 0 with normals (NX, NY, NZ)[INDEX[k]]
  // (A's frame): their part of A's reduced force, summed in float a run at a time.
  void AddReduced(const float* nx, const float* ny, const float* nz, const std::int32_t* index, const float* d, int n,
                  ReducedForceSum* sum) const {
    const EmbeddedPoints& P = shell_->points();
    const int stride = P.basis_stride(), r = P.r();
    alignas(64) float g[kMaxBasisStride];
    alignas(64) float G[kMaxReducedModes * kMaxBasisStride];
    std::fill(g, g + stride, 0.f);
    if (sum->stiffness()) std::fill(G, G + r * stride, 0.f);
    AddReducedPointSums(P, nx, ny, nz, index, d, n, g, sum->stiffness() ? G : nullptr);
    sum->AddSums(g, G, stride);
  }

 private:
  Source shell_;
  ReducedCoordinatesF q_;
  std::uint32_t stamp_ = 0;                                  // queries begun
  alignas(64) float history_[kHistory][kMaxBasisStride] = {};  // q of query s at [s % kHistory]
};

class DeformedField {
 public:
  using Source = std::shared_ptr<const DeformedDistanceField>;
  static constexpr bool kDeforms = true;
  static constexpr const char* kWhat = "deformed distance field";

  DeformedField() = default;
  explicit DeformedField(Source field) : field_(std::move(field)) {
    if (field_) state_ = DeformedFieldState(*field_);
  }
  const DistanceField* rest_field_ptr() const { return field_ ? &field_->rest_field() : nullptr; }
  const DistanceField& rest_field() const { return field_->rest_field(); }
  int r() const { return field_->r(); }

  // Also moves the proxies to Q, held fixed during the query.
  bool Begin(const ReducedState* q) {
    if (!q_.Load(q, r())) return false;
    state_.Update(*field_, q != nullptr ? q->q.data() : nullptr);
    return true;
  }
  // Placed in B a chunk at a time, then answered as one batch (deform/deformed_field_batch.h).
  void Distances(const FloatTransform& X_BA, const float* x, const float* y, const float* z,
                 const std::int32_t* index, int n, float* d, std::int32_t* nearest) const {
    constexpr int kChunk = 256;
    float bx[kChunk], by[kChunk], bz[kChunk];
    for (int c0 = 0; c0 < n; c0 += kChunk) {
      const int m = std::min(kChunk, n - c0);
      for (int k = 0; k < m; ++k) {
        const int i = index ? index[c0 + k] : c0 + k;
        float p_B[3];
        X_BA.Apply(x[i], y[i], z[i], p_B);
        bx[k] = p_B[0], by[k] = p_B[1], bz[k] = p_B[2];
      }
      DeformedFieldDistances(*field_, state_, bx, by, bz, m, d + c0, nearest ? nearest + c0 : nullptr);
    }
  }
  // By central differences of the deformed field, half a rest cell apart.
  Eigen::Vector3d Gradient(const Eigen::Vector3d& p_B) const {
    const double h = 0.5 * field_->rest_field().spacing();
    Eigen::Vector3d g;
    for (int c = 0; c < 3; ++c) {
      float a[3] = {float(p_B[0]), float(p_B[1]), float(p_B[2])}, b[3] = {a[0], a[1], a[2]};
      a[c] += float(h);
      b[c] -= float(h);
      g[c] = double(field_->Distance(state_, a, nullptr) - field_->Distance(state_, b, nullptr)) / (2.0 * float(h));
    }
    return g;
  }
  // A point in contact at P_B (B's frame) with normal N_B and depth D < 0, whose lookup found
  // proxy slot NEAREST: its part of B's reduced force.
  void AddReduced(int nearest, const float* p_B, const float* n_B, float d, ReducedForceSum* sum) const {
    if (nearest < 0) return;
    float w[kMaxReducedModes];
    if (field_->force_at() == DeformedFieldOptions::ForceAt::kNearestProxy) {
      field_->proxies().ProjectF(nearest, n_B, w);
    } else {  // sum_i w_i U_i^T N over the query's k proxies
      int slots[kMaxProxyNeighbours];
      float weights[kMaxProxyNeighbours], wi[kMaxReducedModes];
      const int n = field_->Weights(state_, field_->domain_of_slot(nearest), p_B, slots, weights);
      const int r = field_->r();
      for (int j = 0; j < r; ++j) w[j] = 0.f;
      for (int a = 0; a < n; ++a) {
        if (weights[a] == 0.f) continue;
        field_->proxies().ProjectF(slots[a], n_B, wi);
        for (int j = 0; j < r; ++j) w[j] += weights[a] * wi[j];
      }
    }
    sum->Add(d, w);
  }

 private:
  Source field_;
  DeformedFieldState state_;
  ReducedCoordinatesF q_;
};

}  // namespace contactlab
