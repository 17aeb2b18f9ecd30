// Exact integration of a linear pressure over the contact surface's polygons
// (pressure_integration.h; Elandt et al. 2019).
#include "baselines/pressure_field/pressure_integration.h"

#include <Eigen/Geometry>
#include <algorithm>

namespace contactlab {

double IntegratePolygon(const PolyVertex* poly, int m, const Eigen::Vector3d& toward, const PressureLaw& law,
                      PressureSums* sums, double* area, SurfaceRecord* record) {
  // The polygon's orientation against the direction of decreasing gap.
  Eigen::Vector3d area_vector = Eigen::Vector3d::Zero();
  for (int t = 1; t + 1 < m; ++t) area_vector += (poly[t].x - poly[0].x).cross(poly[t + 1].x - poly[0].x);
  const double sign = area_vector.dot(toward) < 0 ? -1.0 : 1.0;
  // The pressure at each vertex, and the deepest overlap.
  double p[kMaxPolygon];
  for (int t = 0; t < m; ++t) {
    p[t] = law.Pressure(poly[t]);
    sums->max_penetration = std::max(sums->max_penetration, -(poly[t].phi_M + poly[t].phi_L));
  }
  // Each fan triangle (0, t, t + 1): force, moment and area; and for a kept contact the
  // polygon's area-weighted centroid, pressure and overlap (each linear on the polygon).
  double poly_area = 0, poly_pressure = 0, poly_depth = 0;
  Eigen::Vector3d poly_centroid = Eigen::Vector3d::Zero();
  for (int t = 1; t + 1 < m; ++t) {
    const Eigen::Vector3d av = 0.5 * sign * (poly[t].x - poly[0].x).cross(poly[t + 1].x - poly[0].x);  // area times n
    const double psum = p[0] + p[t] + p[t + 1];
    sums->force += (psum / 3) * av;
    // ∫ x p dA over the triangle (p linear): (A/12) [(Σp)(Σx) + Σ p_i x_i].
    const Eigen::Vector3d xp =
        (psum * (poly[0].x + poly[t].x + poly[t + 1].x) + p[0] * poly[0].x + p[t] * poly[t].x +
         p[t + 1] * poly[t + 1].x) / 12;
    sums->torque += xp.cross(av);
    const double a = av.norm();
    *area += a;
    poly_area += a;
    poly_pressure += a * psum / 3;
    poly_centroid += (a / 3) * (poly[0].x + poly[t].x + poly[t + 1].x);
    poly_depth -= (a / 3) * (poly[0].phi_M + poly[0].phi_L + poly[t].phi_M + poly[t].phi_L + poly[t + 1].phi_M +
                             poly[t + 1].phi_L);
    if (record && int(record->pressure->size()) < 3 * record->capacity) {
      for (const int v : {0, t, t + 1}) {
        record->corners->push_back(poly[v].x.cast<float>());
        record->pressure->push_back(float(p[v]));
      }
    }
  }
  if (record && record->contacts && poly_area > 0) {
    record->contacts->Add(poly_centroid / poly_area, sign * area_vector.normalized(), poly_depth / poly_area, poly_area,
                          poly_pressure / poly_area);
  }
  return sign;
}

}  // namespace contactlab
