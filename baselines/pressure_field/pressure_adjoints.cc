// Reverse-mode derivatives of the pressure-field surface's wrench (pressure_adjoints.h).
#include "baselines/pressure_field/pressure_adjoints.h"

#include <Eigen/Geometry>

#include "baselines/pressure_field/cell_surface.h"

namespace contactlab {
namespace {

using Vector6 = Eigen::Matrix<double, 6, 1>;

// IntegratePolygon's fan triangle (0, t, t + 1) of a polygon with the pressures P at its
// vertices and orientation factor C = sign / 2: av = c e1 x e2, F = (psum / 3) av, T = xp x av
// with xp = (psum X + sum p_j x_j) / 12, X = x0 + x1 + x2. The derivatives in its corner j's
// position: d av / d x_j = [a_j]x with a_0 = c (e2 - e1), a_1 = -c e2, a_2 = c e1, so the force's
// is f [a_j]x (f = psum / 3) and the torque's [xp]x [a_j]x - beta_j [av]x, where [xp]x [a]x =
// a xp^T - (xp . a) I and beta_j = (psum + p_j) / 12.
struct FanTriangle {
  FanTriangle(const PolyVertex* poly, const double* p, int t, double c) : v{0, t, t + 1} {
    const Eigen::Vector3d &x0 = poly[0].x, &x1 = poly[t].x, &x2 = poly[t + 1].x;
    const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0;
    av = c * e1.cross(e2);
    psum = p[0] + p[t] + p[t + 1];
    f = psum / 3;
    X = x0 + x1 + x2;
    xp = (psum * X + p[0] * x0 + p[t] * x1 + p[t + 1] * x2) / 12;
    a[0] = c * (e2 - e1);
    a[1] = -c * e2;
    a[2] = c * e1;
  }
  double beta(const double* p, int j) const { return (psum + p[v[j]]) / 12; }
  // The derivative of its force and torque in corner J's pressure, added to *BY_P.
  void AddPressureSensitivity(const PolyVertex* poly, int j, Vector6* by_p) const {
    by_p->head<3>() += av / 3;
    by_p->tail<3>() += ((X + poly[v[j]].x) / 12).cross(av);
  }

  int v[3];
  Eigen::Vector3d av, X, xp, a[3];
  double psum = 0, f = 0;
};

// A vertex's sensitivity in its overlap s from that in its pressure BY_P: p = max(0, -k s).
Vector6 OverlapSensitivity(double p, const PressureLaw& law, const Vector6& by_p) {
  return p > 0 ? Vector6(-law.k * by_p) : Vector6(by_p * 0.0);
}

// Through one cut vertex, origin O on CELL's edge from corner p to q: its sensitivities in its
// position along the edge, ALONG = (dW/dx) (x_q - x_p), and in its overlap, BY_S, added to the
// corners' sensitivities *B. x = x_p + t (x_q - x_p), s = s_p + t (s_q - s_p), t = g_p / (g_p -
// g_q) with g = -w_M phi_M + w_L phi_L; only phi_M moves, and s with it.
void AddThroughCut(const LatticeCell& cell, const PressureLaw& law, const VertexOrigin& o, const Vector6& along,
                   const Vector6& by_s, CornerSensitivity* b) {
  const int p = o.a, q = o.b;
  const PolyVertex &P = cell.corner[p], &Q = cell.corner[q];
  const double gp = cell.g[p], gq = cell.g[q], dg = gp - gq;
  const double sp = P.phi_M + P.phi_L, sq = Q.phi_M + Q.phi_L;
  const Vector6 by_t = along + by_s * (sq - sp);
  b->col(p) += (1 - o.t) * by_s + (law.w_M * gq / (dg * dg)) * by_t;
  b->col(q) += o.t * by_s - (law.w_M * gp / (dg * dg)) * by_t;
}

}  // namespace

void PolygonAdjoints(const PolyVertex* poly, int m, double sign, const PressureLaw& law,
                     VertexAdjoint* out) {
  // The orientation is IntegratePolygon's (constant under a small motion).
  const double c = 0.5 * sign;
  double p[kMaxPolygon];
  Vector6 by_p[kMaxPolygon];  // the derivative in each vertex's pressure
  for (int t = 0; t < m; ++t) {
    p[t] = law.Pressure(poly[t]);
    out[t].x.setZero();
    by_p[t].setZero();
  }
  for (int t = 1; t + 1 < m; ++t) {
    const FanTriangle tri(poly, p, t, c);
    for (int j = 0; j < 3; ++j) {
      Eigen::Matrix<double, 6, 3>& G = out[tri.v[j]].x;
      const Eigen::Vector3d& aj = tri.a[j];
      const Eigen::Vector3d fa = tri.f * aj, bav = tri.beta(p, j) * tri.av;
      // Force rows: f [a_j]x.
      G(0, 1) -= fa.z(); G(0, 2) += fa.y();
      G(1, 0) += fa.z(); G(1, 2) -= fa.x();
      G(2, 0) -= fa.y(); G(2, 1) += fa.x();
      // Torque rows: a_j xp^T - (xp . a_j) I - beta [av]x.
      G.bottomRows<3>().noalias() += aj * tri.xp.transpose();
      const double d = tri.xp.dot(aj);
      G(3, 0) -= d; G(4, 1) -= d; G(5, 2) -= d;
      G(3, 1) += bav.z(); G(3, 2) -= bav.y();
      G(4, 0) -= bav.z(); G(4, 2) += bav.x();
      G(5, 0) += bav.y(); G(5, 1) -= bav.x();
      tri.AddPressureSensitivity(poly, j, &by_p[tri.v[j]]);
    }
  }
  for (int t = 0; t < m; ++t) out[t].s = OverlapSensitivity(p[t], law, by_p[t]);
}

void CutPolygonAdjoints(const LatticeCell& cell, const PolyVertex* poly, int m, double sign, const PressureLaw& law,
                        const VertexOrigin* origin, CornerSensitivity* b) {
  const double c = 0.5 * sign;
  double p[kMaxPolygon];
  Eigen::Vector3d edge[kMaxPolygon];
  Vector6 along[kMaxPolygon], by_p[kMaxPolygon];  // the derivative along the edge, in the pressure
  for (int t = 0; t < m; ++t) {
    p[t] = law.Pressure(poly[t]);
    edge[t] = cell.corner[origin[t].b].x - cell.corner[origin[t].a].x;
    along[t].setZero();
    by_p[t].setZero();
  }
  for (int t = 1; t + 1 < m; ++t) {
    // Each corner's 6x3 sensitivity G_j applied to its edge e: force f a_j x e; torque
    // a_j (xp . e) - (xp . a_j) e - beta av x e.
    const FanTriangle tri(poly, p, t, c);
    for (int j = 0; j < 3; ++j) {
      const int i = tri.v[j];
      const Eigen::Vector3d& e = edge[i];
      const Eigen::Vector3d& aj = tri.a[j];
      along[i].head<3>() += tri.f * aj.cross(e);
      along[i].tail<3>() += tri.xp.dot(e) * aj - tri.xp.dot(aj) * e - tri.beta(p, j) * tri.av.cross(e);
      tri.AddPressureSensitivity(poly, j, &by_p[i]);
    }
  }
  // CutAdjoints with the position's part along the edge as formed.
  for (int i = 0; i < m; ++i) AddThroughCut(cell, law, origin[i], along[i], OverlapSensitivity(p[i], law, by_p[i]), b);
}

void ClipAdjoints(const PolyVertex* in, const VertexOrigin* origin, const VertexAdjoint* out_adj, int m,
                  VertexAdjoint* in_adj) {
  for (int i = 0; i < m; ++i) {
    const VertexOrigin& o = origin[i];
    const VertexAdjoint& g = out_adj[i];
    VertexAdjoint& A = in_adj[o.a];
    if (o.b < 0) {
      A.x += g.x;
      A.s += g.s;
      continue;
    }
    VertexAdjoint& B = in_adj[o.b];
    // x = x_a + t (x_b - x_a), s likewise, t = s_a / (s_a - s_b).
    const double sa = in[o.a].phi_M + in[o.a].phi_L, sb = in[o.b].phi_M + in[o.b].phi_L, d = sa - sb;
    const Vector6 by_t = g.x * (in[o.b].x - in[o.a].x) + g.s * (sb - sa);
    A.x += (1 - o.t) * g.x;
    B.x += o.t * g.x;
    A.s += (1 - o.t) * g.s - (sb / (d * d)) * by_t;
    B.s += o.t * g.s + (sa / (d * d)) * by_t;
  }
}

void CutAdjoints(const LatticeCell& cell, const PressureLaw& law, const VertexOrigin* origin, const VertexAdjoint* adj,
                 int n, CornerSensitivity* b) {
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d edge = cell.corner[origin[i].b].x - cell.corner[origin[i].a].x;
    AddThroughCut(cell, law, origin[i], adj[i].x * edge, adj[i].s, b);
  }
}

}  // namespace contactlab
