// Barbič & James 2008, sec. 2.1, 3 and 5: the pointshell-vs-distance-field contact model.
#include "contact/pointshell_contact_model.h"

#include <cmath>
#include <limits>

#include "contact/float_transform.h"
#include "contact/halfspace_contacts.h"
#include "pointshell/point_tree.h"
#include "sdf/batch_distance.h"
#include "util/error.h"

namespace contactlab {

PointshellContactModel::PointshellContactModel(Variant variant, std::shared_ptr<const Pointshell> shell,
                                               std::shared_ptr<const DistanceField> field,
                                               const PointshellContactParams& params)
    : variant_(variant),
      shell_(std::move(shell)),
      field_(std::move(field)),
      params_(params) {
  max_level_ = ValidatePointshellModelInputs(shell_.get(), field_.get(), params_,
                                             std::string("contact model ") + std::string(name()));
  traversal_ = TreeTraversalState(*shell_);
  earliest_cycle_.assign(std::size_t(shell_->num_nodes()), std::numeric_limits<std::int64_t>::min());
}

int ValidatePointshellModelInputs(const Pointshell* shell, const DistanceField* field,
                                  const PointshellContactParams& params, const std::string& where) {
  if (!shell || shell->num_points() == 0 || shell->num_levels() == 0) Fail(where, "needs a non-empty pointshell");
  if (!field || field->empty()) Fail(where, "needs a distance field");
  if (const std::int32_t n = NodeWithoutOwnFirstChild(*shell); n >= 0) {
    Fail(where, "pointshell node " + std::to_string(n) + ": its first child is not its own point one level down");
  }
  CheckPenaltyParams(params.penalty, where);
  if (params.level >= shell->num_levels() || params.level < -1) {
    Fail(where, "level " + std::to_string(params.level) + " is out of range (the pointshell has " +
                    std::to_string(shell->num_levels()) + " levels)");
  }
  if (!(params.max_point_speed > 0) || !(params.cycle_seconds > 0) || !(params.lipschitz >= 1)) {
    Fail(where, "max_point_speed and cycle_seconds must be positive and lipschitz >= 1");
  }
  if (!(params.cold_fraction > 0 && params.cold_fraction <= 1)) Fail(where, "cold_fraction must be in (0, 1]");
  return params.level < 0 ? shell->num_levels() - 1 : params.level;
}

void PointshellContactModel::Reset() {
  std::fill(earliest_cycle_.begin(), earliest_cycle_.end(), std::numeric_limits<std::int64_t>::min());
  traversal_.Reset();
}

ContactResult PointshellContactModel::Evaluate(const ContactQuery& query) {
  return variant_ == Variant::kLinear ? EvaluateLinear(query) : EvaluateTree(query);
}

namespace {

// The rigid shell: points at their rest positions in A, rest radii, coherence by cycles.
struct RigidShellPolicy {
  const Pointshell& s;
  const DistanceField& field;
  const FloatTransform X_BA;
  ContactGradient gradient;
  ContactAccumulator* acc;
  HalfspaceContactBuffer* contacts;  // the points in contact under the halfspace rule
  std::int64_t* earliest_cycle;  // (#N) first cycle a culled node may touch again
  std::int64_t cycle;
  double step;  // lipschitz * max_point_speed * cycle_seconds: distance closed per cycle
  const BatchTransform X_batch = X_BA.AsBatch();

  void EvaluatePoints(int begin, const std::int32_t* index, int n, float* d) {
    const int offset = index ? 0 : begin;
    BatchDistances(field, X_batch, s.x.data() + offset, s.y.data() + offset, s.z.data() + offset, index, n, d);
    if (gradient == ContactGradient::kHalfspace) {
      contacts->Collect(begin, index, d, n);
      return;
    }
    for (int k = 0; k < n; ++k) {
      if (d[k] < 0.f) [[unlikely]] {
        const int i = index ? index[k] : begin + k;
        float p_BQ[3];
        X_BA.Apply(s.x[i], s.y[i], s.z[i], p_BQ);
        const float n_A[3] = {s.nx[i], s.ny[i], s.nz[i]};
        AddContactPoint(field, X_BA, n_A, p_BQ, d[k], gradient, acc);
      }
    }
  }
  float Radius(int node) const { return s.node_radius[node]; }
  bool Asleep(int node) const { return cycle < earliest_cycle[node]; }
  void Sleep(int node, double margin) {
    earliest_cycle[node] = cycle + std::int64_t(std::min(std::ceil(margin / step), 1e15));
  }
};

}  // namespace

ContactResult PointshellContactModel::EvaluateLinear(const ContactQuery& query) {
  ContactAccumulator acc;
  const FloatTransform X_BA(query.X_WB.Inverse() * query.X_WA);
  HalfspaceContactBuffer contacts(*shell_, X_BA.AsBatch(), &acc);
  RigidShellPolicy policy{*shell_, *field_, X_BA, params_.gradient, &acc, &contacts, nullptr, query.cycle, 0.0};
  ContactResult result;
  RunLinearTraversal(*shell_, max_level_, policy, &result.stats);
  contacts.Flush();
  acc.Finish(params_.penalty, query.X_WB, &result);
  return result;
}

ContactResult PointshellContactModel::EvaluateTree(const ContactQuery& query) {
  ContactAccumulator acc;
  const double step = params_.lipschitz * params_.max_point_speed * params_.cycle_seconds;
  const FloatTransform X_BA(query.X_WB.Inverse() * query.X_WA);
  HalfspaceContactBuffer contacts(*shell_, X_BA.AsBatch(), &acc);
  RigidShellPolicy policy{*shell_, *field_, X_BA, params_.gradient, &acc, &contacts, earliest_cycle_.data(),
                          query.cycle, step};
  ContactResult result;
  traversal_.Run(*shell_, max_level_, params_, query.node_budget, policy, &result.stats);
  contacts.Flush();
  acc.Finish(params_.penalty, query.X_WB, &result);
  return result;
}

int PointshellContactModel::PointStates(const ContactQuery& query, std::span<const std::int32_t> points,
                                        PointState* out) {
  if (variant_ == Variant::kTree) return traversal_.PointStates(points, out);
  const FloatTransform X_BA(query.X_WB.Inverse() * query.X_WA);  // as EvaluateLinear's
  const Pointshell& s = *shell_;
  return LinearPointStates(s, max_level_, points, out, [&](const std::int32_t* index, int n, float* d) {
    BatchDistances(*field_, X_BA.AsBatch(), s.x.data(), s.y.data(), s.z.data(), index, n, d);
  });
}

}  // namespace contactlab
