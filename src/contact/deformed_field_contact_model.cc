// Barbič & James 2008, sec. 4.2: pointshell (rigid or deformable) against a deformed field.
#include "contact/deformed_field_contact_model.h"

#include <cmath>
#include <limits>

#include "contact/reduced_force_sum.h"
#include "util/error.h"

namespace contactlab {
namespace {

template <bool kDeformableA>
struct DeformedFieldPolicy {
  const Pointshell& s;
  const DeformablePointshell* shell_A;  // kDeformableA only
  const DeformedDistanceField& field;
  const DeformedFieldState& state;
  const FloatTransform X_BA;
  ContactGradient gradient;
  float gradient_step;  // metres, central differences of the deformed field (kField)
  ContactAccumulator* acc;
  const float* q_A;      // (r_A)
  const float* abs_q_A;  // (r_A)
  ReducedForceSum* sum_A;  // A's reduced force (at the points), or null
  ReducedForceSum* sum_B;  // B's (at the proxies), or null
  double* wake;
  double clock;

  float EvaluatePoint(int i) {
    float p_AQ[3], p_BQ[3];
    if constexpr (kDeformableA) {
      shell_A->points().PositionF(i, q_A, p_AQ);
    } else {
      p_AQ[0] = s.x[i], p_AQ[1] = s.y[i], p_AQ[2] = s.z[i];
    }
    X_BA.Apply(p_AQ[0], p_AQ[1], p_AQ[2], p_BQ);
    int nearest = -1;
    const float d = field.Distance(state, p_BQ, &nearest);
    if (!(d < 0.f)) return d;
    float n_A[3], n_B[3];
    if constexpr (kDeformableA) {
      shell_A->points().CorrectedNormalF(i, q_A, n_A);
    } else {
      n_A[0] = s.nx[i], n_A[1] = s.ny[i], n_A[2] = s.nz[i];
    }
    // The kField gradient by central differences of the deformed field.
    AddContactPointWith(X_BA, n_A, p_BQ, d, gradient, acc,
                        [this, &p_BQ](const Eigen::Vector3d&) {
                          Eigen::Vector3d g;
                          for (int c = 0; c < 3; ++c) {
                            float a[3] = {p_BQ[0], p_BQ[1], p_BQ[2]}, b[3] = {p_BQ[0], p_BQ[1], p_BQ[2]};
                            a[c] += gradient_step;
                            b[c] -= gradient_step;
                            g[c] = double(field.Distance(state, a, nullptr) - field.Distance(state, b, nullptr)) /
                                   (2.0 * gradient_step);
                          }
                          return g;
                        },
                        n_B);
    float w[kMaxReducedModes];
    if constexpr (kDeformableA) {
      if (sum_A != nullptr) {
        shell_A->points().ProjectF(i, n_A, w);
        sum_A->Add(d, w);
      }
    }
    if (sum_B != nullptr && nearest >= 0) {
      const int r = field.r();
      if (field.force_at() == DeformedFieldOptions::ForceAt::kNearestProxy) {
        field.proxies().ProjectF(nearest, n_B, w);
      } else {  // sum_i w_i U_i^T N over the query's k proxies
        int slots[kMaxProxyNeighbours];
        float weights[kMaxProxyNeighbours], wi[kMaxReducedModes];
        const int n = field.Weights(state, field.domain_of_slot(nearest), p_BQ, slots, weights);
        for (int j = 0; j < r; ++j) w[j] = 0.f;
        for (int a = 0; a < n; ++a) {
          if (weights[a] == 0.f) continue;
          field.proxies().ProjectF(slots[a], n_B, wi);
          for (int j = 0; j < r; ++j) w[j] += weights[a] * wi[j];
        }
      }
      sum_B->Add(d, w);
    }
    return d;
  }
  float Radius(int node) const {
    if constexpr (kDeformableA) {
      return shell_A->RadiusF(node, abs_q_A);
    } else {
      return s.node_radius[node];
    }
  }
  bool Asleep(int node) const { return clock < wake[node]; }
  void Sleep(int node, double margin) { wake[node] = clock + margin; }
};

}  // namespace

DeformedFieldContactModel::DeformedFieldContactModel(Variant variant, std::shared_ptr<const Pointshell> shell,
                                                     std::shared_ptr<const DeformablePointshell> deformable_shell,
                                                     std::shared_ptr<const DeformedDistanceField> field,
                                                     const PointshellContactParams& params)
    : variant_(variant), shell_(std::move(shell)), deformable_(std::move(deformable_shell)), field_(std::move(field)),
      params_(params) {
  const std::string where = std::string("contact model ") + std::string(name()) + " (deformed field)";
  if (deformable_) shell_ = std::shared_ptr<const Pointshell>(deformable_, &deformable_->shell());
  if (!field_) Fail(where, "needs a deformed distance field");
  max_level_ = ValidatePointshellModelInputs(shell_.get(), &field_->rest_field(), params_, where);
  state_ = DeformedFieldState(*field_);
  traversal_ = TreeTraversalState(*shell_);
  wake_.assign(std::size_t(shell_->num_nodes()), -std::numeric_limits<double>::infinity());
}

void DeformedFieldContactModel::Reset() {
  std::fill(wake_.begin(), wake_.end(), -std::numeric_limits<double>::infinity());
  traversal_.Reset();
  has_previous_ = false;
}

ContactResult DeformedFieldContactModel::Evaluate(const ContactQuery& query) {
  return deformable_ ? EvaluateImpl<true>(query) : EvaluateImpl<false>(query);
}

template <bool kDeformableA>
ContactResult DeformedFieldContactModel::EvaluateImpl(const ContactQuery& query) {
  const int rA = deformable_ ? deformable_->r() : 0;
  const int rB = field_->r();
  float qA[kMaxReducedModes], abs_qA[kMaxReducedModes], qB[kMaxReducedModes];
  const bool deformedA = query.q_A != nullptr && query.q_A->size() == rA;
  const bool deformedB = query.q_B != nullptr && query.q_B->size() == rB;
  for (int j = 0; j < rA; ++j) {
    qA[j] = deformedA ? float(query.q_A->q[j]) : 0.f;
    abs_qA[j] = std::fabs(qA[j]);
  }
  for (int j = 0; j < rB; ++j) {
    qB[j] = deformedB ? float(query.q_B->q[j]) : 0.f;
  }
  const bool wantA = kDeformableA && query.reduced_force_A != nullptr;
  const bool wantB = query.reduced_force_B != nullptr;
  ReducedForceSum sumA, sumB;
  if (wantA) sumA.Start(rA, query.reduced_stiffness_A != nullptr);
  if (wantB) sumB.Start(rB, query.reduced_stiffness_B != nullptr);

  // B's field at q_B, held fixed during the traversal.
  state_.Update(*field_, deformedB ? query.q_B->q.data() : nullptr);

  // The coherence clock: distance closable by rigid motion plus by A's and B's deformation.
  if (has_previous_) {
    for (int j = 0; j < rA; ++j) travel_ += double(deformable_->mode_travel(j)) * std::fabs(qA[j] - previous_qA_[j]);
    for (int j = 0; j < rB; ++j) travel_ += double(field_->mode_travel(j)) * std::fabs(qB[j] - previous_qB_[j]);
  }
  std::copy(qA, qA + rA, previous_qA_);
  std::copy(qB, qB + rB, previous_qB_);
  has_previous_ = true;
  const double clock =
      params_.lipschitz * (double(query.cycle) * params_.max_point_speed * params_.cycle_seconds + travel_);

  ContactAccumulator acc;
  DeformedFieldPolicy<kDeformableA> policy{*shell_,
                                           deformable_.get(),
                                           *field_,
                                           state_,
                                           FloatTransform(query.X_WB.Inverse() * query.X_WA),
                                           params_.gradient,
                                           float(0.5 * field_->rest_field().spacing()),
                                           &acc,
                                           qA,
                                           abs_qA,
                                           wantA ? &sumA : nullptr,
                                           wantB ? &sumB : nullptr,
                                           wake_.data(),
                                           clock};
  ContactResult result;
  if (variant_ == Variant::kLinear) {
    RunLinearTraversal(*shell_, max_level_, policy, &result.stats);
  } else {
    traversal_.Run(*shell_, max_level_, params_, query.node_budget, policy, &result.stats);
  }
  acc.Finish(params_.penalty, query.X_WB, &result);
  double scale = 1;
  const double k = params_.penalty.StiffnessFor(acc.count(), &scale);
  // Force on A at a point: -k d N_A; on B: +k d N_B.
  if (wantA) sumA.Write(k, -1.0, query.reduced_force_A, query.reduced_stiffness_A);
  if (wantB) sumB.Write(k, 1.0, query.reduced_force_B, query.reduced_stiffness_B);
  return result;
}

int DeformedFieldContactModel::PointStates(const ContactQuery& query, std::span<const std::int32_t> points,
                                           PointState* out) {
  if (variant_ == Variant::kTree) return traversal_.PointStates(points, out);
  // A's points at the query's q_A, as EvaluateImpl places them, in B's field as the query left
  // it (state_ at q_B).
  const int rA = deformable_ ? deformable_->r() : 0;
  const bool deformedA = query.q_A != nullptr && query.q_A->size() == rA;
  float qA[kMaxReducedModes];
  for (int j = 0; j < rA; ++j) qA[j] = deformedA ? float(query.q_A->q[j]) : 0.f;
  const FloatTransform X_BA(query.X_WB.Inverse() * query.X_WA);
  const Pointshell& s = *shell_;
  return LinearPointStates(s, max_level_, points, out, [&](const std::int32_t* index, int n, float* d) {
    for (int k = 0; k < n; ++k) {
      const int i = index[k];
      float p_AQ[3], p_BQ[3];
      if (deformable_) {
        deformable_->points().PositionF(i, qA, p_AQ);
      } else {
        p_AQ[0] = s.x[i], p_AQ[1] = s.y[i], p_AQ[2] = s.z[i];
      }
      X_BA.Apply(p_AQ[0], p_AQ[1], p_AQ[2], p_BQ);
      d[k] = field_->Distance(state_, p_BQ, nullptr);
    }
  });
}

}  // namespace contactlab
