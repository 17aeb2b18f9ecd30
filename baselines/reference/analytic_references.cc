// Analytic limits of eq. (2) of Barbič & James 2008 (see analytic_references.h).
#include "baselines/reference/analytic_references.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "util/error.h"

namespace contactlab {
namespace {

constexpr const char* kWhere = "analytic reference";

void CheckUnit(const Eigen::Vector3d& n) {
  if (!(std::abs(n.norm() - 1) < 1e-9)) Fail(kWhere, "the plane normal must have unit length");
}

void CheckL(int L) {
  if (L <= 0) Fail(kWhere, "the eq. (2) limit needs L > 0 (the L / l scaling enabled)");
}

}  // namespace

double SphereHalfspaceForceMagnitude(double R, double H, double k_C, int L) {
  CheckL(L);
  if (!(R > 0) || !(H > -R) || !(H < R)) Fail(kWhere, "sphere-halfspace needs R > 0 and -R < H < R");
  // R (R/3 - H/2 + H^3/(6 R^2)) / (R - H) with u = R - H, the depth: the numerator is
  // u^2/(2R) - u^3/(6R^2), so |F| = k_C L u (3R - u) / (6R). Evaluated in u: the textbook form
  // cancels catastrophically as the sphere just touches (250 N instead of 0 at u ~ 1e-17).
  const double u = R - H;
  return k_C * L * u * (3 * R - u) / (6 * R);
}

ForceLimit SphereHalfspaceLimit(const Eigen::Vector3d& c_WA, double R, const Eigen::Vector3d& q_W,
                                const Eigen::Vector3d& n_W, const Eigen::Vector3d& p_WB, double k_C, int L) {
  CheckUnit(n_W);
  ForceLimit out;
  const double H = n_W.dot(c_WA - q_W);
  if (H >= R) return out;
  const double F = SphereHalfspaceForceMagnitude(R, H, k_C, L);
  out.on_B.force = -F * n_W;
  out.on_B.torque = (c_WA - p_WB).cross(out.on_B.force);
  out.area_inside = 2 * M_PI * R * (R - H);
  out.max_penetration = R - H;
  return out;
}

ForceLimit SphereSphereLimit(const Eigen::Vector3d& c_WA, double R_A, const Eigen::Vector3d& c_WB, double R_B,
                             const Eigen::Vector3d& p_WB, double k_C, int L, int samples) {
  CheckL(L);
  if (!(R_A > 0) || !(R_B > 0) || samples < 2) Fail(kWhere, "sphere-sphere needs positive radii and samples >= 2");
  const double D = (c_WB - c_WA).norm();
  if (!(D > R_B)) Fail(kWhere, "sphere-sphere needs A's centre outside B");
  ForceLimit out;
  if (D >= R_A + R_B) return out;
  const Eigen::Vector3d u = (c_WB - c_WA) / D;  // axis from A's centre to B's
  // Polar angle θ of A's surface point from the axis: x = c_A + R_A (cos θ u + sin θ e).
  // Inside B while |x - c_B|^2 = R_A^2 + D^2 - 2 R_A D cos θ < R_B^2.
  const double cos_max = (R_A * R_A + D * D - R_B * R_B) / (2 * R_A * D);
  const double theta_max = std::acos(std::clamp(cos_max, -1.0, 1.0));
  // ∫ d(θ) (N·u) sin θ dθ and ∫ sin θ dθ over [0, θ_max]; N = -(cos θ u + ...), N·u = -cos θ.
  if (samples % 2) ++samples;
  const double h = theta_max / samples;
  double num = 0, den = 0;
  for (int i = 0; i <= samples; ++i) {
    const double t = i * h;
    const double w = (i == 0 || i == samples) ? 1 : (i % 2 ? 4 : 2);
    const double d = std::sqrt(std::max(0.0, R_A * R_A + D * D - 2 * R_A * D * std::cos(t))) - R_B;
    num += w * d * (-std::cos(t)) * std::sin(t);
    den += w * std::sin(t);
  }
  out.on_B.force = k_C * L * (num / den) * u;
  out.on_B.torque = (c_WA - p_WB).cross(out.on_B.force);
  out.area_inside = 2 * M_PI * R_A * R_A * (1 - std::cos(theta_max));
  out.max_penetration = R_A + R_B - D;
  return out;
}

ForceLimit PolyhedronHalfspaceLimit(const TriangleMesh& mesh_A, const Pose& X_WA, const Eigen::Vector3d& q_W,
                                    const Eigen::Vector3d& n_W, const Eigen::Vector3d& p_WB, double k_C, int L) {
  CheckUnit(n_W);
  CheckL(L);
  Eigen::Vector3d sum_dN = Eigen::Vector3d::Zero(), sum_torque = Eigen::Vector3d::Zero();
  double area = 0, max_pen = 0;
  auto dist = [&](const Eigen::Vector3d& x) { return n_W.dot(x - q_W); };
  for (int t = 0; t < mesh_A.num_triangles(); ++t) {
    const Eigen::Vector3i& tri = mesh_A.triangles[std::size_t(t)];
    const Eigen::Vector3d v[3] = {X_WA * mesh_A.vertices[std::size_t(tri[0])], X_WA * mesh_A.vertices[std::size_t(tri[1])],
                                  X_WA * mesh_A.vertices[std::size_t(tri[2])]};
    const Eigen::Vector3d cross = (v[1] - v[0]).cross(v[2] - v[0]);
    if (cross.norm() == 0) continue;
    const Eigen::Vector3d N = -cross.normalized();  // inward normal of A
    // Clip the triangle to d < 0 (Sutherland-Hodgman against one plane): at most 4 vertices.
    Eigen::Vector3d poly[4];
    int m = 0;
    for (int i = 0; i < 3; ++i) {
      const Eigen::Vector3d& a = v[i];
      const Eigen::Vector3d& b = v[(i + 1) % 3];
      const double da = dist(a), db = dist(b);
      if (da < 0) poly[m++] = a;
      if ((da < 0) != (db < 0)) poly[m++] = a + (da / (da - db)) * (b - a);
    }
    // Fan triangles; the edge-midpoint rule is exact for the quadratic torque integrand.
    for (int i = 1; i + 1 < m; ++i) {
      const Eigen::Vector3d& a = poly[0];
      const Eigen::Vector3d& b = poly[i];
      const Eigen::Vector3d& c = poly[i + 1];
      const double A = 0.5 * (b - a).cross(c - a).norm();
      const Eigen::Vector3d mids[3] = {0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)};
      for (const Eigen::Vector3d& x : mids) {
        const Eigen::Vector3d f = (A / 3) * dist(x) * N;
        sum_dN += f;
        sum_torque += (x - p_WB).cross(f);
      }
      area += A;
      max_pen = std::max({max_pen, -dist(a), -dist(b), -dist(c)});
    }
  }
  ForceLimit out;
  if (area <= 0) return out;
  out.on_B.force = k_C * L * sum_dN / area;
  out.on_B.torque = k_C * L * sum_torque / area;
  out.area_inside = area;
  out.max_penetration = max_pen;
  return out;
}

}  // namespace contactlab
