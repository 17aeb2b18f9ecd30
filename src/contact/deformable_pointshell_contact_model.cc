// Barbič & James 2008, sec. 4.1: deformable pointshell against a rigid distance field.
#include "contact/deformable_pointshell_contact_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/reduced_force_sum.h"
#include "sdf/batch_distance.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Points at X + U q with corrected normals, radii R(q), coherence on a clock of closable
// distance; point forces also summed into the reduced force g = sum_i d_i U_i^T N_i.
struct DeformableShellPolicy {
  const Pointshell& s;
  const DeformablePointshell& shell;
  const DistanceField& field;
  const FloatTransform X_BA;
  ContactGradient gradient;
  ContactAccumulator* acc;
  const float* q;      // (r)
  const float* abs_q;  // (r)
  ReducedForceSum* sum;  // A's reduced force, or null
  double* wake;        // (#N)
  double clock;
  const BatchTransform X_batch = X_BA.AsBatch();

  // The deformed positions x = X + U q of a chunk, then their distances as one batch.
  void EvaluatePoints(int begin, const std::int32_t* index, int n, float* d) {
    constexpr int kChunk = 256;
    float px[kChunk], py[kChunk], pz[kChunk];
    for (int c0 = 0; c0 < n; c0 += kChunk) {
      const int m = std::min(kChunk, n - c0);
      for (int k = 0; k < m; ++k) {
        float p[3];
        shell.points().PositionF(index ? index[c0 + k] : begin + c0 + k, q, p);
        px[k] = p[0], py[k] = p[1], pz[k] = p[2];
      }
      BatchDistances(field, X_batch, px, py, pz, nullptr, m, d + c0);
      for (int k = 0; k < m; ++k) {
        if (d[c0 + k] < 0.f) [[unlikely]] {
          const float p_AQ[3] = {px[k], py[k], pz[k]};
          AddContact(index ? index[c0 + k] : begin + c0 + k, p_AQ, d[c0 + k]);
        }
      }
    }
  }
  // Point I, at P_AQ in A with distance D < 0: its force on B and its reduced force on A.
  void AddContact(int i, const float* p_AQ, float d) {
    const EmbeddedPoints& points = shell.points();
    float p_BQ[3];
    X_BA.Apply(p_AQ[0], p_AQ[1], p_AQ[2], p_BQ);
    float n_A[3];
    points.CorrectedNormalF(i, q, n_A);
    AddContactPoint(field, X_BA, n_A, p_BQ, d, gradient, acc);
    if (sum != nullptr) {
      float w[kMaxReducedModes];
      points.ProjectF(i, n_A, w);
      sum->Add(d, w);
    }
  }
  float Radius(int node) const { return shell.RadiusF(node, abs_q); }
  bool Asleep(int node) const { return clock < wake[node]; }
  void Sleep(int node, double margin) { wake[node] = clock + margin; }
};

}  // namespace

DeformablePointshellContactModel::DeformablePointshellContactModel(Variant variant,
                                                                   std::shared_ptr<const DeformablePointshell> shell,
                                                                   std::shared_ptr<const DistanceField> field,
                                                                   const PointshellContactParams& params)
    : variant_(variant), shell_(std::move(shell)), field_(std::move(field)), params_(params) {
  const std::string where = std::string("contact model ") + std::string(name()) + " (deformable pointshell)";
  if (!shell_) Fail(where, "needs a deformable pointshell");
  max_level_ = ValidatePointshellModelInputs(&shell_->shell(), field_.get(), params_, where);
  traversal_ = TreeTraversalState(shell_->shell());
  wake_.assign(std::size_t(shell_->shell().num_nodes()), -std::numeric_limits<double>::infinity());
}

void DeformablePointshellContactModel::Reset() {
  std::fill(wake_.begin(), wake_.end(), -std::numeric_limits<double>::infinity());
  traversal_.Reset();
  has_previous_q_ = false;
}

ContactResult DeformablePointshellContactModel::Evaluate(const ContactQuery& query) {
  const int r = shell_->r();
  float q[kMaxReducedModes], abs_q[kMaxReducedModes];
  ReducedForceSum sum;
  const bool want_force = query.reduced_force_A != nullptr;
  if (want_force) sum.Start(r, query.reduced_stiffness_A != nullptr);
  const bool deformed = query.q_A != nullptr && query.q_A->size() == r;
  for (int j = 0; j < r; ++j) {
    q[j] = deformed ? float(query.q_A->q[j]) : 0.f;
    abs_q[j] = std::fabs(q[j]);
  }
  // The coherence clock: distance closable by rigid motion (cycles) plus by deformation.
  if (has_previous_q_) {
    for (int j = 0; j < r; ++j) deformation_travel_ += double(shell_->mode_travel(j)) * std::fabs(q[j] - previous_q_[j]);
  }
  for (int j = 0; j < r; ++j) previous_q_[j] = q[j];
  has_previous_q_ = true;
  const double clock = params_.lipschitz * (double(query.cycle) * params_.max_point_speed * params_.cycle_seconds +
                                            deformation_travel_);

  ContactAccumulator acc;
  DeformableShellPolicy policy{shell_->shell(), *shell_, *field_, FloatTransform(query.X_WB.Inverse() * query.X_WA),
                               params_.gradient, &acc, q, abs_q, want_force ? &sum : nullptr, wake_.data(), clock};
  ContactResult result;
  if (variant_ == Variant::kLinear) {
    RunLinearTraversal(shell_->shell(), max_level_, policy, &result.stats);
  } else {
    traversal_.Run(shell_->shell(), max_level_, params_, query.node_budget, policy, &result.stats);
  }
  acc.Finish(params_.penalty, query.X_WB, &result);
  if (want_force) {
    // Force on A at point i: -k d_i N_i, so the reduced force is -k g.
    double scale = 1;
    sum.Write(params_.penalty.StiffnessFor(acc.count(), &scale), -1.0, query.reduced_force_A,
              query.reduced_stiffness_A);
  }
  return result;
}

int DeformablePointshellContactModel::PointStates(const ContactQuery& query, std::span<const std::int32_t> points,
                                                  PointState* out) {
  if (variant_ == Variant::kTree) return traversal_.PointStates(points, out);
  // The points at the query's q, as Evaluate places them.
  const int r = shell_->r();
  const bool deformed = query.q_A != nullptr && query.q_A->size() == r;
  float q[kMaxReducedModes];
  for (int j = 0; j < r; ++j) q[j] = deformed ? float(query.q_A->q[j]) : 0.f;
  const FloatTransform X_BA(query.X_WB.Inverse() * query.X_WA);
  return LinearPointStates(shell_->shell(), max_level_, points, out, [&](const std::int32_t* index, int n, float* d) {
    float px[kLinearPointStatesPerCall], py[kLinearPointStatesPerCall], pz[kLinearPointStatesPerCall];
    for (int k = 0; k < n; ++k) {
      float p[3];
      shell_->points().PositionF(index[k], q, p);
      px[k] = p[0], py[k] = p[1], pz[k] = p[2];
    }
    BatchDistances(*field_, X_BA.AsBatch(), px, py, pz, nullptr, n, d);
  });
}

}  // namespace contactlab
