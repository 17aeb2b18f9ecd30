// Barbič & James 2008, sec. 4.1: deformable pointshell against a rigid distance field.
#include "contact/deformable_pointshell_contact_model.h"

#include <cmath>
#include <limits>

#include "contact/reduced_force_sum.h"
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

  float EvaluatePoint(int i) {
    const EmbeddedPoints& points = shell.points();
    float p_AQ[3], p_BQ[3];
    points.PositionF(i, q, p_AQ);
    X_BA.Apply(p_AQ[0], p_AQ[1], p_AQ[2], p_BQ);
    const float d = field.Distance(p_BQ[0], p_BQ[1], p_BQ[2]);
    if (d < 0.f) {
      float n_A[3];
      points.CorrectedNormalF(i, q, n_A);
      AddContactPoint(field, X_BA, n_A, p_BQ, d, gradient, acc);
      if (sum != nullptr) {
        float w[kMaxReducedModes];
        points.ProjectF(i, n_A, w);
        sum->Add(d, w);
      }
    }
    return d;
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
  return LinearPointStates(shell_->shell(), max_level_, points, out, [&](int i) {
    float p_AQ[3], p_BQ[3];
    shell_->points().PositionF(i, q, p_AQ);
    X_BA.Apply(p_AQ[0], p_AQ[1], p_AQ[2], p_BQ);
    return field_->Distance(p_BQ[0], p_BQ[1], p_BQ[2]);
  });
}

}  // namespace contactlab
