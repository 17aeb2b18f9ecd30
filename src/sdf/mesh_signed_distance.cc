#include "sdf/mesh_signed_distance.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "sdf/unsigned_distance_grid.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Closest point of segment A-B to P as (weight of A, weight of B) and its squared distance.
double SegmentClosest(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double* t) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  *t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + *t * ab)).squaredNorm();
}

// Barycentric weights (of A, B, C) of the point of triangle (A, B, C) closest to P (Ericson,
// Real-Time Collision Detection, sec. 5.1.5); a degenerate triangle is the union of its edges.
Eigen::Vector3d ClosestBarycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  if (!(ab.cross(ac).squaredNorm() > 1e-24 * ab.squaredNorm() * ac.squaredNorm())) {
    double t0, t1, t2;
    const double d0 = SegmentClosest(p, a, b, &t0), d1 = SegmentClosest(p, b, c, &t1), d2 = SegmentClosest(p, c, a, &t2);
    if (d0 <= d1 && d0 <= d2) return {1 - t0, t0, 0};
    if (d1 <= d2) return {0, 1 - t1, t1};
    return {t2, 0, 1 - t2};
  }
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = (d1 - d3) > 0 ? d1 / (d1 - d3) : 0.0;
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = (d2 - d6) > 0 ? d2 / (d2 - d6) : 0.0;
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double den = (d4 - d3) + (d5 - d6);
    const double w = den > 0 ? (d4 - d3) / den : 0.0;
    return {0, 1 - w, w};
  }
  const double den = va + vb + vc;
  const double v = vb / den, w = vc / den;
  return {1 - v - w, v, w};
}

// Angle at corner A of triangle (A, B, C), radians (0 for a degenerate corner).
double CornerAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d u = b - a, v = c - a;
  const double s = u.cross(v).norm(), co = u.dot(v);
  return (s > 0 || co != 0) ? std::atan2(s, co) : 0.0;
}

const TriangleMesh& RequireTriangles(const TriangleMesh& mesh, const std::string& where) {
  if (mesh.empty()) Fail(where, "the mesh '" + mesh.name + "' has no triangles");
  return mesh;
}

}  // namespace

MeshSignedDistance::MeshSignedDistance(const TriangleMesh& mesh, const std::string& where)
    : mesh_(RequireTriangles(mesh, where)), bvh_(FlattenTriangles(mesh)) {
  const int T = mesh.num_triangles();
  face_normal_.resize(T);
  edge_normal_.assign(3 * std::size_t(T), Eigen::Vector3d::Zero());
  vertex_normal_.assign(mesh.num_vertices(), Eigen::Vector3d::Zero());
  // Directed edges (a, b) -> 3 t + e; each must appear once, and its reverse once.
  std::unordered_map<std::uint64_t, int> directed;
  directed.reserve(3 * std::size_t(T));
  auto key = [](int a, int b) { return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b); };
  for (int t = 0; t < T; ++t) {
    const Eigen::Vector3i& f = mesh.triangles[t];
    face_normal_[t] = mesh.FaceNormal(t);
    for (int e = 0; e < 3; ++e) {
      const int a = f[e], b = f[(e + 1) % 3];
      if (!directed.emplace(key(a, b), 3 * t + e).second) {
        Fail(where, "the mesh '" + mesh.name + "' is not a consistently oriented 2-manifold: edge (" +
                        std::to_string(a) + ", " + std::to_string(b) + ") is used twice in the same direction");
      }
      const Eigen::Vector3d& A = mesh.vertices[f[e]];
      vertex_normal_[a] +=
          CornerAngle(A, mesh.vertices[f[(e + 1) % 3]], mesh.vertices[f[(e + 2) % 3]]) * face_normal_[t];
    }
  }
  for (const auto& [k, slot] : directed) {
    const int a = int(k >> 32), b = int(k & 0xffffffffu);
    const auto twin = directed.find(key(b, a));
    if (twin == directed.end()) {
      Fail(where, "the mesh '" + mesh.name + "' is not closed: edge (" + std::to_string(a) + ", " +
                      std::to_string(b) + ") has one face (an exact sign needs a closed mesh)");
    }
    edge_normal_[slot] = face_normal_[slot / 3] + face_normal_[twin->second / 3];
  }
}

double MeshSignedDistance::Distance(const Eigen::Vector3d& p, Eigen::Vector3d* closest) const {
  std::int32_t t = -1;
  const double d2 = bvh_.ClosestSquared(p.data(), std::numeric_limits<double>::infinity(), &t);
  const double d = std::sqrt(d2);
  return Inside(p, t, closest) ? -d : d;
}

bool MeshSignedDistance::Inside(const Eigen::Vector3d& p, std::int32_t t, Eigen::Vector3d* closest) const {
  const Eigen::Vector3i& f = mesh_.triangles[t];
  const Eigen::Vector3d &a = mesh_.vertices[f[0]], &b = mesh_.vertices[f[1]], &c = mesh_.vertices[f[2]];
  const Eigen::Vector3d w = ClosestBarycentric(p, a, b, c);
  const Eigen::Vector3d q = w[0] * a + w[1] * b + w[2] * c;
  if (closest != nullptr) *closest = q;
  // The closest feature: a vertex (two weights ~0), an edge (one) or the face.
  constexpr double kEps = 1e-9;
  int zeros = 0, zero = -1, one = 0;
  for (int i = 0; i < 3; ++i) {
    if (w[i] <= kEps) {
      ++zeros;
      zero = i;
    } else {
      one = i;
    }
  }
  const Eigen::Vector3d& n = zeros >= 2   ? vertex_normal_[f[one]]
                             : zeros == 1 ? edge_normal_[3 * std::size_t(t) + (zero + 1) % 3]
                                          : face_normal_[t];
  return (p - q).dot(n) < 0;
}

}  // namespace contactlab
