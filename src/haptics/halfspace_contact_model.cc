// Analytic penalty halfspace contact model (Barbič & James 2008, sec. 5 contact gradients).
#include "haptics/halfspace_contact_model.h"

#include <cmath>
#include <string>

#include "geometry/rotation_math.h"
#include "util/error.h"

namespace contactlab {

HalfspaceContactModel::HalfspaceContactModel(const Eigen::Matrix3Xd& p_BQ, double k) : p_BQ_(p_BQ), k_(k) {
  if (p_BQ_.cols() == 0) Fail("halfspace contact model", "needs at least one sample point");
  if (!p_BQ_.allFinite()) Fail("halfspace contact model", "sample points must be finite");
  if (!std::isfinite(k) || k <= 0) Fail("halfspace contact model", "stiffness must be > 0, got " + std::to_string(k));
}

ContactResult HalfspaceContactModel::Evaluate(const ContactQuery& query) {
  ContactResult result;
  const Eigen::Matrix3d R_WB = query.X_WB.R();
  const Eigen::Vector3d& p_WB = query.X_WB.translation;
  const Eigen::Vector3d n = query.X_WA.rotation * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d& p_WA = query.X_WA.translation;
  const Eigen::Matrix3d nnT = n * n.transpose();
  Eigen::Matrix3d dF_dx = Eigen::Matrix3d::Zero(), dF_dth = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dT_dx = Eigen::Matrix3d::Zero(), dT_dth = Eigen::Matrix3d::Zero();
  for (Eigen::Index i = 0; i < p_BQ_.cols(); ++i) {
    const Eigen::Vector3d r = R_WB * p_BQ_.col(i);  // p_WQ - p_WB
    const double d = n.dot(p_WB + r - p_WA);
    if (d >= 0) continue;
    // Force at Q and its moment about B's origin.
    const Eigen::Vector3d f = -k_ * d * n;
    result.on_B.force += f;
    result.on_B.torque += r.cross(f);
    // dp_WQ = dx + dθ x r = dx - [r]x dθ; df = -k n n^T dp_WQ; dT = dr x f + r x df.
    const Eigen::Matrix3d Sr = Skew(r);
    const Eigen::Matrix3d A = -k_ * nnT;  // df/dp_WQ
    dF_dx += A;
    dF_dth -= A * Sr;
    dT_dx += Sr * A;
    dT_dth += Skew(f) * Sr - Sr * A * Sr;
    ++result.stats.points_in_contact;
    result.stats.max_penetration = std::max(result.stats.max_penetration, -d);
  }
  result.stats.nodes_visited = p_BQ_.cols();
  result.K_B << dF_dx, dF_dth, dT_dx, dT_dth;
  return result;
}

Eigen::Matrix3Xd MakeBoxSamplePoints(const Eigen::Vector3d& h, int n) {
  if (n < 2) Fail("MakeBoxSamplePoints", "n must be >= 2, got " + std::to_string(n));
  std::vector<Eigen::Vector3d> pts;
  // Grid on each of the 6 faces; shared edge points are kept once by a tolerance check.
  for (int axis = 0; axis < 3; ++axis) {
    for (int side = -1; side <= 1; side += 2) {
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          Eigen::Vector3d p;
          p[axis] = side * h[axis];
          p[a1] = h[a1] * (-1.0 + 2.0 * i / (n - 1));
          p[a2] = h[a2] * (-1.0 + 2.0 * j / (n - 1));
          bool dup = false;
          for (const auto& q : pts) dup = dup || (q - p).norm() < 1e-12;
          if (!dup) pts.push_back(p);
        }
      }
    }
  }
  Eigen::Matrix3Xd P(3, Eigen::Index(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i) P.col(Eigen::Index(i)) = pts[i];
  return P;
}

}  // namespace contactlab
