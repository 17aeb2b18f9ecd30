#include "baselines/inner_spheres/inner_sphere_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "geometry/rotation_math.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr double kPi = std::numbers::pi;

// The wrench on B (B's frame, about its origin) and its gradient, summed over sphere pairs.
struct PairSums {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  Matrix6d K = Matrix6d::Zero();
  double volume = 0;
  double max_depth = 0;
  std::int32_t pairs = 0;
  ContactRecorder* contacts = nullptr;  // where each overlapping pair is kept, or null

  // A's sphere (centre a in B's frame, radius ra) and B's (b, rb); K_V the volume stiffness;
  // EXACT: K the exact derivative, else the halfspace rule (inner_sphere_model.h).
  void Add(const Eigen::Vector3d& a, double ra, const Eigen::Vector3d& b, double rb, double k_V, bool exact) {
    const Eigen::Vector3d ab = b - a;
    const double d = ab.norm();
    if (d >= ra + rb) return;
    ++pairs;
    max_depth = std::max(max_depth, ra + rb - d);
    if (contacts != nullptr) {
      // The overlap along the line of centres runs from b - rb u to a + ra u.
      const Eigen::Vector3d u = d > 0 ? Eigen::Vector3d(ab / d) : Eigen::Vector3d::UnitZ();
      contacts->Add(0.5 * ((a + ra * u) + (b - rb * u)), u, ra + rb - d);
    }
    const double small = std::min(ra, rb);
    if (d <= std::abs(ra - rb)) {  // one inside the other: the smaller ball, and no gradient
      volume += 4.0 / 3.0 * kPi * small * small * small;
      return;
    }
    const double s = ra + rb - d;
    volume += kPi * s * s * (d * d + 2 * d * (ra + rb) - 3 * (ra - rb) * (ra - rb)) / (12 * d);
    // The intersection disc: at x from a along u, radius^2 = ra^2 - x^2.
    const Eigen::Vector3d u = ab / d;
    const double x = (d * d + ra * ra - rb * rb) / (2 * d);
    const double disc = std::max(0.0, ra * ra - x * x);
    const double ddisc = -2 * x * (0.5 - (ra * ra - rb * rb) / (2 * d * d));  // d(disc)/dd
    const Eigen::Vector3d f = k_V * kPi * disc * u;
    force += f;
    torque += a.cross(f);
    if (!exact) {
      // A spring along the line of centres: -k_n w w^T, w = (u, a x u) (= (u, b x u)).
      const double k_n = k_V * kPi * std::max(0.0, -ddisc);
      Vector6d w;
      w << u, a.cross(u);
      K.noalias() -= k_n * w * w.transpose();
      return;
    }
    const Eigen::Matrix3d uu = u * u.transpose();
    const Eigen::Matrix3d Kb = k_V * kPi * (ddisc * uu + (disc / d) * (Eigen::Matrix3d::Identity() - uu));
    const Eigen::Matrix3d Sa = Skew(a), Sb = Skew(b);
    K.block<3, 3>(0, 0) += Kb;
    K.block<3, 3>(0, 3) -= Kb * Sb;
    K.block<3, 3>(3, 0) += Skew(f) + Sa * Kb;
    K.block<3, 3>(3, 3) -= Sa * Kb * Sb;
  }
};

}  // namespace

InnerSphereModel::InnerSphereModel(std::shared_ptr<const SpherePacking> A, std::shared_ptr<const SpherePacking> B,
                                   double k_V, SphereStiffness stiffness, std::int64_t max_pairs)
    : A_(std::move(A)), B_(std::move(B)), k_V_(k_V), stiffness_(stiffness) {
  if (!A_ || !B_ || A_->radii.empty() || B_->radii.empty()) Fail("inner-spheres", "needs a sphere packing of each body");
  if (!(k_V_ > 0)) Fail("inner-spheres", "the volume stiffness k_V must be > 0");
  if (max_pairs < 2) Fail("inner-spheres", "max_pairs must be at least 2");
  tree_A_ = BuildSphereTree(*A_);
  tree_B_ = BuildSphereTree(*B_);
  level_.resize(std::size_t(max_pairs));
  next_.resize(std::size_t(max_pairs));
}

ContactResult InnerSphereModel::Evaluate(const ContactQuery& query) {
  ContactResult r;
  const Pose X_BA = query.X_WB.Inverse() * query.X_WA;
  const Eigen::Matrix3d R_BA = X_BA.R();
  const Eigen::Vector3d& p_BA = X_BA.translation;
  PairSums sums;
  contacts_.Clear();
  X_WB_contacts_ = query.X_WB;
  if (contacts_.keeping()) sums.contacts = &contacts_;
  const bool exact = stiffness_ != SphereStiffness::kHalfspace;
  std::int64_t visited = 0;
  const std::int64_t budget = query.node_budget;
  const std::int64_t capacity = std::int64_t(level_.size());
  std::int64_t count = 0, next_count = 0;
  level_[0] = {0, 0};
  count = 1;
  int levels_done = -1, levels_walked = -1;
  bool degraded = false;
  // Counts a pair through its proxies (the budget or the pair buffer ran out).
  auto approximate = [&](const SphereTreeNode& na, const SphereTreeNode& nb) {
    sums.Add(R_BA * na.proxy_center + p_BA, na.proxy_radius, nb.proxy_center, nb.proxy_radius, k_V_, exact);
    degraded = true;
  };
  while (count > 0) {
    next_count = 0;
    for (std::int64_t i = 0; i < count; ++i) {
      const Pair pr = level_[std::size_t(i)];
      const SphereTreeNode& na = tree_A_.nodes[std::size_t(pr.a)];
      const SphereTreeNode& nb = tree_B_.nodes[std::size_t(pr.b)];
      ++visited;
      const Eigen::Vector3d ca = R_BA * na.center + p_BA;
      if ((ca - nb.center).squaredNorm() >= (na.radius + nb.radius) * (na.radius + nb.radius)) continue;
      if (na.leaf() && nb.leaf()) {
        sums.Add(ca, A_->radii[std::size_t(na.sphere)], nb.center, B_->radii[std::size_t(nb.sphere)], k_V_, exact);
        // A leaf's bounding sphere is its sphere (centre and radius).
        continue;
      }
      if ((budget > 0 && visited >= budget) || next_count + 2 > capacity) {
        approximate(na, nb);
        continue;
      }
      const bool split_a = nb.leaf() || (!na.leaf() && na.radius >= nb.radius);
      if (split_a) {
        next_[std::size_t(next_count++)] = {na.child[0], pr.b};
        next_[std::size_t(next_count++)] = {na.child[1], pr.b};
      } else {
        next_[std::size_t(next_count++)] = {pr.a, nb.child[0]};
        next_[std::size_t(next_count++)] = {pr.a, nb.child[1]};
      }
    }
    if (!degraded) ++levels_done;
    ++levels_walked;
    std::swap(level_, next_);
    count = next_count;
  }
  volume_ = sums.volume;
  const Eigen::Matrix3d R = query.X_WB.R();
  r.on_B.force = R * sums.force;
  r.on_B.torque = R * sums.torque;
  Matrix6d T = Matrix6d::Zero();
  T.block<3, 3>(0, 0) = R;
  T.block<3, 3>(3, 3) = R;
  r.K_B = T * sums.K * T.transpose();
  if (stiffness_ == SphereStiffness::kProjected) {  // the nearest negative semidefinite matrix
    const Matrix6d S = 0.5 * (r.K_B + r.K_B.transpose());
    Eigen::SelfAdjointEigenSolver<Matrix6d> es(S);
    Vector6d ev = es.eigenvalues().cwiseMin(0.0);
    r.K_B = es.eigenvectors() * ev.asDiagonal() * es.eigenvectors().transpose();
  }
  r.stats.points_in_contact = sums.pairs;
  r.stats.nodes_visited = visited;
  r.stats.level_rendered = levels_done;
  r.stats.degraded = degraded ? std::max(1, levels_walked - levels_done) : 0;
  r.stats.max_penetration = sums.max_depth;
  return r;
}

}  // namespace contactlab
