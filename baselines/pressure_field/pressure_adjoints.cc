// Reverse-mode derivatives of the pressure-field surface's wrench (pressure_adjoints.h).
#include "baselines/pressure_field/pressure_adjoints.h"

#include <Eigen/Geometry>

#include "baselines/pressure_field/cell_surface.h"

namespace contactlab {

void PolygonAdjoints(const PolyVertex* poly, int m, double sign, const PressureLaw& law,
                     VertexAdjoint* out) {
  // The orientation is IntegratePolygon's (constant under a small motion).
  const double c = 0.5 * sign;
  double p[kMaxPolygon];
  Eigen::Matrix<double, 6, 1> by_p[kMaxPolygon];  // the derivative in each vertex's pressure
  for (int t = 0; t < m; ++t) {
    p[t] = law.Pressure(poly[t]);
    out[t].x.setZero();
    by_p[t].setZero();
  }
  for (int t = 1; t + 1 < m; ++t) {
    const int v[3] = {0, t, t + 1};
    const Eigen::Vector3d &x0 = poly[0].x, &x1 = poly[t].x, &x2 = poly[t + 1].x;
    const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0;
    // IntegratePolygon's triangle: av = c e1 x e2, F = (psum / 3) av, T = xp x av with
    // xp = (psum X + sum p_j x_j) / 12, X = x0 + x1 + x2.
    const Eigen::Vector3d av = c * e1.cross(e2);
    const double psum = p[0] + p[t] + p[t + 1];
    const Eigen::Vector3d X = x0 + x1 + x2;
    const Eigen::Vector3d xp = (psum * X + p[0] * x0 + p[t] * x1 + p[t + 1] * x2) / 12;
    // d av / d x_j = [a_j]x / (psum / 3) with a_0 = c (e2 - e1), a_1 = -c e2, a_2 = c e1 (times
    // psum / 3, the force's). The torque's: [xp]x [a_j]x - ((psum + p_j) / 12) [av]x, where
    // [xp]x [a]x = a xp^T - (xp . a) I.
    const double f = psum / 3;
    const Eigen::Vector3d a[3] = {c * (e2 - e1), -c * e2, c * e1};
    for (int j = 0; j < 3; ++j) {
      Eigen::Matrix<double, 6, 3>& G = out[v[j]].x;
      const Eigen::Vector3d& aj = a[j];
      const double beta = (psum + p[v[j]]) / 12;
      const Eigen::Vector3d fa = f * aj, bav = beta * av;
      // Force rows: f [a_j]x.
      G(0, 1) -= fa.z(); G(0, 2) += fa.y();
      G(1, 0) += fa.z(); G(1, 2) -= fa.x();
      G(2, 0) -= fa.y(); G(2, 1) += fa.x();
      // Torque rows: a_j xp^T - (xp . a_j) I - beta [av]x.
      G.bottomRows<3>().noalias() += aj * xp.transpose();
      const double d = xp.dot(aj);
      G(3, 0) -= d; G(4, 1) -= d; G(5, 2) -= d;
      G(3, 1) += bav.z(); G(3, 2) -= bav.y();
      G(4, 0) -= bav.z(); G(4, 2) += bav.x();
      G(5, 0) += bav.y(); G(5, 1) -= bav.x();
      by_p[v[j]].head<3>() += av / 3;
      by_p[v[j]].tail<3>() += ((X + poly[v[j]].x) / 12).cross(av);
    }
  }
  // p = max(0, -k s).
  for (int t = 0; t < m; ++t) out[t].s = p[t] > 0 ? Eigen::Matrix<double, 6, 1>(-law.k * by_p[t]) : by_p[t] * 0.0;
}

void CutPolygonAdjoints(const LatticeCell& cell, const PolyVertex* poly, int m, double sign, const PressureLaw& law,
                        const VertexOrigin* origin, CornerSensitivity* b) {
  using Vector6 = Eigen::Matrix<double, 6, 1>;
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
    // PolygonAdjoints' triangle, its 6x3 sensitivity G_j of each vertex applied to the edge e:
    // force f a_j x e; torque a_j (xp . e) - (xp . a_j) e - beta av x e.
    const int v[3] = {0, t, t + 1};
    const Eigen::Vector3d &x0 = poly[0].x, &x1 = poly[t].x, &x2 = poly[t + 1].x;
    const Eigen::Vector3d e1 = x1 - x0, e2 = x2 - x0;
    const Eigen::Vector3d av = c * e1.cross(e2);
    const double psum = p[0] + p[t] + p[t + 1];
    const Eigen::Vector3d X = x0 + x1 + x2;
    const Eigen::Vector3d xp = (psum * X + p[0] * x0 + p[t] * x1 + p[t + 1] * x2) / 12;
    const double f = psum / 3;
    const Eigen::Vector3d a[3] = {c * (e2 - e1), -c * e2, c * e1};
    for (int j = 0; j < 3; ++j) {
      const int i = v[j];
      const Eigen::Vector3d& e = edge[i];
      const double beta = (psum + p[i]) / 12;
      along[i].head<3>() += f * a[j].cross(e);
      along[i].tail<3>() += xp.dot(e) * a[j] - xp.dot(a[j]) * e - beta * av.cross(e);
      by_p[i].head<3>() += av / 3;
      by_p[i].tail<3>() += ((X + poly[i].x) / 12).cross(av);
    }
  }
  // CutAdjoints with the position's part along the edge as formed.
  for (int i = 0; i < m; ++i) {
    const Vector6 s_adj = p[i] > 0 ? Vector6(-law.k * by_p[i]) : Vector6::Zero();
    const int P = origin[i].a, Q = origin[i].b;
    const double t = origin[i].t;
    const double gp = cell.g[P], gq = cell.g[Q], dg = gp - gq;
    const double sp = cell.corner[P].phi_M + cell.corner[P].phi_L, sq = cell.corner[Q].phi_M + cell.corner[Q].phi_L;
    const Vector6 by_t = along[i] + s_adj * (sq - sp);
    b->col(P) += (1 - t) * s_adj + (law.w_M * gq / (dg * dg)) * by_t;
    b->col(Q) += t * s_adj - (law.w_M * gp / (dg * dg)) * by_t;
  }
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
    const Eigen::Matrix<double, 6, 1> by_t = g.x * (in[o.b].x - in[o.a].x) + g.s * (sb - sa);
    A.x += (1 - o.t) * g.x;
    B.x += o.t * g.x;
    A.s += (1 - o.t) * g.s - (sb / (d * d)) * by_t;
    B.s += o.t * g.s + (sa / (d * d)) * by_t;
  }
}

void CutAdjoints(const LatticeCell& cell, const PressureLaw& law, const VertexOrigin* origin, const VertexAdjoint* adj,
                 int n, CornerSensitivity* b) {
  for (int i = 0; i < n; ++i) {
    const int p = origin[i].a, q = origin[i].b;
    const double t = origin[i].t;
    const PolyVertex &P = cell.corner[p], &Q = cell.corner[q];
    // x = x_p + t (x_q - x_p), s = s_p + t (s_q - s_p), t = g_p / (g_p - g_q) with
    // g = -w_M phi_M + w_L phi_L; only phi_M moves, and s with it.
    const double gp = cell.g[p], gq = cell.g[q], dg = gp - gq;
    const double sp = P.phi_M + P.phi_L, sq = Q.phi_M + Q.phi_L;
    const Eigen::Matrix<double, 6, 1> by_t = adj[i].x * (Q.x - P.x) + adj[i].s * (sq - sp);
    b->col(p) += (1 - t) * adj[i].s + (law.w_M * gq / (dg * dg)) * by_t;
    b->col(q) += t * adj[i].s - (law.w_M * gp / (dg * dg)) * by_t;
  }
}

}  // namespace contactlab
