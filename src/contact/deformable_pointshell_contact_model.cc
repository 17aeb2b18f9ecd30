// Barbič & James 2008, sec. 4.1: deformable pointshell against a rigid distance field.
#include "contact/deformable_pointshell_contact_model.h"

#include <cmath>
#include <limits>

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
  double* g;           // (r) sum d U^T N
  double* G;           // (r x r, column-major) sum (U^T N)(U^T N)^T, or null
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
      float w[kMaxReducedModes];
      points.ProjectF(i, n_A, w);
      const int r = points.r();
      for (int j = 0; j < r; ++j) g[j] += double(d * w[j]);
      if (G != nullptr) {
        for (int b = 0; b < r; ++b)
          for (int a = 0; a <= b; ++a) G[b * r + a] += double(w[a] * w[b]);
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
  double g[kMaxReducedModes];
  double G[kMaxReducedModes * kMaxReducedModes];
  const bool want_stiffness = query.reduced_force_A != nullptr && query.reduced_stiffness_A != nullptr;
  if (want_stiffness) std::fill(G, G + r * r, 0.0);
  const bool deformed = query.q_A != nullptr && query.q_A->size() == r;
  for (int j = 0; j < r; ++j) {
    q[j] = deformed ? float(query.q_A->q[j]) : 0.f;
    abs_q[j] = std::fabs(q[j]);
    g[j] = 0;
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
                               params_.gradient, &acc, q, abs_q, g, want_stiffness ? G : nullptr, wake_.data(), clock};
  ContactResult result;
  if (variant_ == Variant::kLinear) {
    RunLinearTraversal(shell_->shell(), max_level_, policy, &result.stats);
  } else {
    traversal_.Run(shell_->shell(), max_level_, params_, query.node_budget, policy, &result.stats);
  }
  acc.Finish(params_.penalty, query.X_WB, &result);
  if (query.reduced_force_A != nullptr) {
    // Force on A at point i: -k d_i N_i, so the reduced force is -k g.
    double scale = 1;
    const double k = params_.penalty.StiffnessFor(acc.count(), &scale);
    query.reduced_force_A->resize(r);
    for (int j = 0; j < r; ++j) (*query.reduced_force_A)[j] = -k * g[j];
    if (want_stiffness) {
      ReducedMatrix& K = *query.reduced_stiffness_A;
      K.resize(r, r);
      for (int b = 0; b < r; ++b)
        for (int a = 0; a <= b; ++a) K(a, b) = K(b, a) = k * G[b * r + a];
    }
  }
  return result;
}

}  // namespace contactlab
