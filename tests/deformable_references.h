// Double-precision references for the paper's contact model with deformable bodies (Barbič &
// James 2008, eq. (1), sec. 4.1, 4.2), written from the paper's formulas and sharing none of the
// model's float hot paths: a deformable pointshell's points and corrected normals as the
// body-export command writes them (EmbeddedPoints in double), B's rest field in double
// (DistanceField::DistanceAndGradient), the deformed field of sec. 4.2 by brute force (k nearest
// proxies, eq. (3) weights, pull-back X_i = P_i + F_i^{-1} (x - p_i)), and the penalty sum
// F_i = -k d_i N_i over the points with d_i < 0 with the L / l scaling of PenaltyParams.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "contact/contact_model.h"
#include "contact/penalty_params.h"
#include "deform/deformable_pointshell.h"
#include "deform/deformed_distance_field.h"
#include "pointshell/pointshell.h"
#include "sdf/distance_field.h"

namespace contactlab::testing {

// The proxies of one domain a query point takes, nearest first, with their eq. (3) weights.
struct ProxyNeighbours {
  std::vector<int> slots;
  std::vector<double> weights;  // sum 1; the k-th is zero
};

// The k nearest proxy slots of domain D of FIELD to X (B's frame) at reduced coordinates Q (r
// entries, null: rest), by sorting every slot's distance; weights w_i ~ 1/|x - p_i| - 1/d_max
// (eq. (3)), normalised; equal weights on the nearest when they all vanish (x equidistant).
inline ProxyNeighbours ReferenceProxyNeighbours(const DeformedDistanceField& field, int D, const double* q,
                                                const Eigen::Vector3d& x) {
  const EmbeddedPoints& P = field.proxies();
  std::vector<std::pair<double, int>> by_distance;
  for (int s = field.slot_begin(D); s < field.slot_end(D); ++s) {
    const Eigen::Vector3d p = q != nullptr ? P.Position(s, q) : P.rest_position(s);
    by_distance.push_back({(x - p).norm(), s});
  }
  const int k = std::min<int>(field.neighbours(), int(by_distance.size()));
  std::partial_sort(by_distance.begin(), by_distance.begin() + k, by_distance.end());
  ProxyNeighbours out;
  const double d_max = by_distance[k - 1].first;
  double W = 0;
  for (int i = 0; i < k; ++i) {
    const double di = by_distance[i].first;
    const double w = di > 0 ? std::max(0.0, 1 / di - 1 / d_max) : std::numeric_limits<double>::infinity();
    out.slots.push_back(by_distance[i].second);
    out.weights.push_back(w);
    W += w;
  }
  if (std::isinf(W)) {  // x on a proxy: that proxy alone
    for (double& w : out.weights) w = std::isinf(w) ? 1 : 0;
    W = 1;
  } else if (!(W > 0)) {  // all k equidistant
    for (double& w : out.weights) w = 1;
    W = k;
  }
  for (double& w : out.weights) w /= W;
  return out;
}

// The deformed distance of sec. 4.2 at X (B's frame) for reduced coordinates Q (null: rest):
// per domain sum_i w_i d_D(P_i + F_i^{-1} (x - p_i)) over its k nearest proxies (a proxy with
// det F_i <= 1e-3 keeps F_i = I, as DeformedFieldState documents), the minimum over domains.
// NEAREST (may be null) gets the nearest slot of the domain giving the minimum, NEIGHBOURS
// (may be null) that domain's proxies and weights.
inline double ReferenceDeformedDistance(const DeformedDistanceField& field, const double* q, const Eigen::Vector3d& x,
                                        int* nearest = nullptr, ProxyNeighbours* neighbours = nullptr) {
  const EmbeddedPoints& P = field.proxies();
  double best = std::numeric_limits<double>::infinity();
  for (int D = 0; D < field.num_domains(); ++D) {
    const ProxyNeighbours nb = ReferenceProxyNeighbours(field, D, q, x);
    double d = 0;
    for (std::size_t i = 0; i < nb.slots.size(); ++i) {
      if (nb.weights[i] == 0) continue;
      const int s = nb.slots[i];
      Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
      Eigen::Vector3d p = P.rest_position(s);
      if (q != nullptr) {
        p = P.Position(s, q);
        F = P.DeformationGradient(s, q);
        if (!(F.determinant() > 1e-3)) F = Eigen::Matrix3d::Identity();
      }
      const Eigen::Vector3d X = P.rest_position(s) + F.inverse() * (x - p);
      d += nb.weights[i] * field.domain_field(D).DistanceAndGradient(X, nullptr);
    }
    if (d < best) {
      best = d;
      if (nearest != nullptr) *nearest = nb.slots[0];
      if (neighbours != nullptr) *neighbours = nb;
    }
  }
  return best;
}

// Body A's point I in A's frame and its unit inward normal: deformed by Q through DPS when DPS
// is given (the corrected normal of sec. 4.1, as body-export writes them), else S's own.
inline std::pair<Eigen::Vector3d, Eigen::Vector3d> ReferencePoint(const Pointshell& s, const DeformablePointshell* dps,
                                                                  const double* q, int i) {
  if (dps != nullptr && q != nullptr) return {dps->points().Position(i, q), dps->points().CorrectedNormal(i, q)};
  const Eigen::Vector3d n(s.nx[i], s.ny[i], s.nz[i]);
  return {Eigen::Vector3d(s.x[i], s.y[i], s.z[i]), n.normalized()};
}

// What the reference sum needs of the two bodies; B is the rigid FIELD or, when DEFORMED is
// given, the deformed field at Q_B (FIELD then unused).
struct ReferenceBodies {
  const Pointshell* shell = nullptr;             // A's points (rest), the deepest level summed
  const DeformablePointshell* dps = nullptr;     // A deformable, or null
  const double* q_A = nullptr;                   // A's reduced coordinates (with DPS), or null: rest
  const DistanceField* field = nullptr;          // B rigid
  const DeformedDistanceField* deformed = nullptr;  // B deformable, or null
  const double* q_B = nullptr;                   // B's reduced coordinates (with DEFORMED), or null: rest
  bool weighted = false;                         // B's reduced force over the k proxies (force_at: weighted)
};

struct ReferenceSum {
  Wrench on_B;                   // world frame, torque about B's origin
  int count = 0;                 // points with d < 0
  double k = 0;                  // the stiffness applied to each (L / l scaling included)
  std::vector<double> d;         // (#points of the deepest level) each point's d, metres
  double sum_force = 0;          // sum over points in contact of k |d| (a scale for tolerances)
  Eigen::VectorXd f_A, f_B;      // reduced forces, sum U^T F at the place each force acts
};

// Eq. (1) over every point of A's deepest level placed in the world by X_WA and looked up in B
// (posed by X_WB): F_i = -k d_i N_i on A, +k d_i N_i on B, k = PENALTY.StiffnessFor(count).
// A's reduced force sum_i U_i^T (-k d_i N_A) (A's frame, A deformable); B's sum U_p^T (k d_i N_B)
// at the nearest proxy p, or sum_j w_j U_j^T (k d_i N_B) over its k proxies (B deformable).
inline ReferenceSum ReferenceEq1Sum(const ReferenceBodies& b, const Pose& X_WA, const Pose& X_WB,
                                    const PenaltyParams& penalty) {
  const Pointshell& s = *b.shell;
  const int n = s.level_point_end.back();
  const Pose X_BA = X_WB.Inverse() * X_WA;
  ReferenceSum out;
  out.d.resize(n);
  struct Contact {
    int i;
    int nearest;
    ProxyNeighbours neighbours;
    Eigen::Vector3d p_W, N_A;
  };
  std::vector<Contact> contacts;
  for (int i = 0; i < n; ++i) {
    const auto [x_A, N_A] = ReferencePoint(s, b.dps, b.q_A, i);
    const Eigen::Vector3d x_B = X_BA * x_A;
    int nearest = -1;
    ProxyNeighbours nb;
    const double d = b.deformed != nullptr ? ReferenceDeformedDistance(*b.deformed, b.q_B, x_B, &nearest, &nb)
                                           : b.field->DistanceAndGradient(x_B, nullptr);
    out.d[i] = d;
    if (d < 0) contacts.push_back({i, nearest, std::move(nb), X_WA * x_A, N_A});
  }
  out.count = int(contacts.size());
  out.k = penalty.StiffnessFor(out.count);
  if (b.dps != nullptr) out.f_A = Eigen::VectorXd::Zero(b.dps->r());
  if (b.deformed != nullptr) out.f_B = Eigen::VectorXd::Zero(b.deformed->r());
  for (const Contact& c : contacts) {
    const double d = out.d[c.i];
    const Eigen::Vector3d F_W = out.k * d * (X_WA.R() * c.N_A);  // on B
    out.on_B.force += F_W;
    out.on_B.torque += (c.p_W - X_WB.translation).cross(F_W);
    out.sum_force += out.k * std::abs(d);
    if (b.dps != nullptr) out.f_A += b.dps->points().Basis(c.i).transpose() * (-out.k * d * c.N_A);
    if (b.deformed != nullptr) {
      const Eigen::Vector3d F_B = out.k * d * (X_BA.R() * c.N_A);
      const EmbeddedPoints& P = b.deformed->proxies();
      if (!b.weighted) {
        out.f_B += P.Basis(c.nearest).transpose() * F_B;
      } else {
        for (std::size_t j = 0; j < c.neighbours.slots.size(); ++j) {
          out.f_B += c.neighbours.weights[j] * (P.Basis(c.neighbours.slots[j]).transpose() * F_B);
        }
      }
    }
  }
  return out;
}

// How many of the reference's points have |d| < EPS: those whose side of the surface float
// rounding may flip.
inline int NearZero(const ReferenceSum& ref, double eps) {
  int n = 0;
  for (double d : ref.d) n += std::abs(d) < eps;
  return n;
}

}  // namespace contactlab::testing
