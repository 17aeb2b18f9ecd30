// Generalized winding number by solid angles (Barbič & James 2008, sec. 2.3, soup pipeline).
#include "sdf/winding_number.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace contactlab {

double TriangleSolidAngle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                          const Eigen::Vector3d& c) {
  const Eigen::Vector3d x = a - p, y = b - p, z = c - p;
  const double lx = x.norm(), ly = y.norm(), lz = z.norm();
  const double num = x.dot(y.cross(z));
  const double den = lx * ly * lz + x.dot(y) * lz + y.dot(z) * lx + z.dot(x) * ly;
  return 2 * std::atan2(num, den);
}

double WindingNumber(const TriangleMesh& mesh, const Eigen::Vector3d& p) {
  double sum = 0;
  for (const auto& t : mesh.triangles) {
    sum += TriangleSolidAngle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
  }
  return sum / (4 * std::numbers::pi);
}

}  // namespace contactlab
