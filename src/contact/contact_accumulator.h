// Sums per-point penalty forces of the paper's contact model (Barbič & James 2008, eq. (1):
// F = k_C d N on the field body) and their halfspace gradient (sec. 5), in the field body's
// frame. Used inside the haptic cycle: fixed-size, allocation-free, inline.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "contact/contact_model.h"
#include "contact/penalty_params.h"
#include "geometry/pose.h"

namespace contactlab {

// How the contact gradient treats each point in contact.
enum class ContactGradient {
  kHalfspace,  // paper sec. 5: a halfspace oriented by the point's normal N
  kField,      // the field's own gradient g at the point (exact derivative of the model)
};

// Sums over many points in contact under the halfspace rule (g = N), with G = N x p. Then
// p x N = -G, so the sums of ContactAccumulator::Add are M = NN, MP = NG, PM = -NG^T, PMP = -GG.
struct HalfspaceSums {
  double dN[3] = {};      // sum d N
  double p_x_dN[3] = {};  // sum p x (d N)
  double NN[6] = {};      // sum N N^T: xx, xy, xz, yy, yz, zz
  double NG[9] = {};      // sum N G^T, row-major
  double GG[6] = {};      // sum G G^T: xx, xy, xz, yy, yz, zz
  int count = 0;
  double max_penetration = 0;
};

class ContactAccumulator {
 public:
  // One point in contact, field-body frame B: position p_B (metres), the pointshell point's
  // inward unit normal N_B, signed distance d < 0 (metres), gradient direction g_B (N_B for
  // the halfspace rule). Adds d N (unscaled by k) and its gradient terms.
  void Add(const Eigen::Vector3d& p_B, const Eigen::Vector3d& N_B, double d, const Eigen::Vector3d& g_B) {
    const Eigen::Vector3d f = d * N_B;
    force_ += f;
    torque_ += p_B.cross(f);
    // With P = [p]x (so P^T = -P): g^T P = (g x p)^T and P N = p x N, hence
    // M P = N (g x p)^T, P M = (p x N) g^T, P M P = (p x N)(g x p)^T: four outer products
    // instead of three 3x3 matrix products per point.
    const Eigen::Vector3d gp = g_B.cross(p_B);
    const Eigen::Vector3d pN = p_B.cross(N_B);
    M_.noalias() += N_B * g_B.transpose();
    MP_.noalias() += N_B * gp.transpose();
    PM_.noalias() += pN * g_B.transpose();
    PMP_.noalias() += pN * gp.transpose();
    ++count_;
    if (-d > max_penetration_) max_penetration_ = -d;
  }

  // Many halfspace points at once (contact/halfspace_contacts.h).
  void Add(const HalfspaceSums& s) {
    force_ += Eigen::Vector3d(s.dN[0], s.dN[1], s.dN[2]);
    torque_ += Eigen::Vector3d(s.p_x_dN[0], s.p_x_dN[1], s.p_x_dN[2]);
    const Eigen::Matrix3d NN = Symmetric(s.NN), GG = Symmetric(s.GG);
    const Eigen::Matrix3d NG = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(s.NG);
    M_ += NN;
    MP_ += NG;
    PM_ -= NG.transpose();
    PMP_ -= GG;
    count_ += s.count;
    if (s.max_penetration > max_penetration_) max_penetration_ = s.max_penetration;
  }

  int count() const { return count_; }
  double max_penetration() const { return max_penetration_; }

  // Counts each point added so far F times (F >= 1): a budget that looked at one point in F of a
  // uniform sample stands for the whole (the sums, their gradient and the count, rounded).
  void Scale(double f) {
    force_ *= f;
    torque_ *= f;
    M_ *= f;
    MP_ *= f;
    PM_ *= f;
    PMP_ *= f;
    count_ = int(std::lround(double(count_) * f));
  }

  // The wrench on B (world frame, torque about B's origin) and its gradient under the
  // penalty law PENALTY: k_C, scaled by L / l when l >= L points touch (L = 0 disables it).
  void Finish(const PenaltyParams& penalty, const Pose& X_WB, ContactResult* out) const {
    double scale = 1;
    const double k = penalty.StiffnessFor(count_, &scale);
    const Eigen::Vector3d F_B = k * force_;
    const Eigen::Vector3d T_B = k * torque_;
    Matrix6d K_B;
    K_B.block<3, 3>(0, 0) = -k * M_;
    K_B.block<3, 3>(0, 3) = k * MP_;
    K_B.block<3, 3>(3, 0) = Skew(F_B) - k * PM_;
    K_B.block<3, 3>(3, 3) = k * PMP_;
    const Eigen::Matrix3d R = X_WB.R();
    out->on_B.force = R * F_B;
    out->on_B.torque = R * T_B;
    Matrix6d Rb = Matrix6d::Zero();
    Rb.block<3, 3>(0, 0) = R;
    Rb.block<3, 3>(3, 3) = R;
    out->K_B = Rb * K_B * Rb.transpose();
    out->stats.points_in_contact = count_;
    out->stats.max_penetration = max_penetration_;
    out->stats.stiffness_scale = scale;
  }

  // The symmetric matrix of the upper triangle U = (xx, xy, xz, yy, yz, zz).
  static Eigen::Matrix3d Symmetric(const double* U) {
    Eigen::Matrix3d S;
    S << U[0], U[1], U[2], U[1], U[3], U[4], U[2], U[4], U[5];
    return S;
  }

  static Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
    Eigen::Matrix3d S;
    S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
    return S;
  }

 private:
  Eigen::Vector3d force_ = Eigen::Vector3d::Zero();   // sum d N
  Eigen::Vector3d torque_ = Eigen::Vector3d::Zero();  // sum p x (d N)
  Eigen::Matrix3d M_ = Eigen::Matrix3d::Zero();       // sum N g^T
  Eigen::Matrix3d MP_ = Eigen::Matrix3d::Zero();      // sum N g^T [p]x
  Eigen::Matrix3d PM_ = Eigen::Matrix3d::Zero();      // sum [p]x N g^T
  Eigen::Matrix3d PMP_ = Eigen::Matrix3d::Zero();     // sum [p]x N g^T [p]x
  int count_ = 0;
  double max_penetration_ = 0;
};

}  // namespace contactlab
