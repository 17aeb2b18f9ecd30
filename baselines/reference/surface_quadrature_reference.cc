// Dense-quadrature limit of eq. (2) with exact CGAL distances (see
// surface_quadrature_reference.h).
#include "baselines/reference/surface_quadrature_reference.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include <cmath>
#include <string>

#include "baselines/reference/cgal_mesh.h"
#include "contact/contact_accumulator.h"
#include "util/error.h"

namespace contactlab {

using cgal::Kernel;
using cgal::Mesh;
using cgal::Point;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

struct QuadratureReference::Distance {
  Mesh mesh;
  Tree tree;
  std::unique_ptr<CGAL::Side_of_triangle_mesh<Mesh, Kernel>> inside;
};

QuadratureReference::QuadratureReference(std::shared_ptr<const TriangleMesh> mesh_A,
                                         std::shared_ptr<const TriangleMesh> mesh_B,
                                         const QuadratureReferenceParams& params)
    : distance_(std::make_unique<Distance>()), params_(params), mesh_A_(std::move(mesh_A)), mesh_B_(std::move(mesh_B)) {
  const std::string where = "contact model reference";
  if (!mesh_A_ || !mesh_B_ || mesh_A_->empty()) Fail(where, "needs two non-empty meshes");
  CheckPenaltyParams(params.penalty, where);
  if (params.penalty.L <= 0) Fail(where, "the eq. (2) limit needs L > 0");
  if (!(params.target_edge > 0)) Fail(where, "target_edge must be positive");

  // B: closed surface mesh, AABB tree for closest points, ray-parity inside test on the tree.
  distance_->mesh = cgal::ToSurfaceMesh(*mesh_B_, where + " (body B)", /*require_closed=*/true);
  distance_->tree.insert(faces(distance_->mesh).first, faces(distance_->mesh).second, distance_->mesh);
  distance_->tree.build();
  distance_->tree.accelerate_distance_queries();
  distance_->inside = std::make_unique<CGAL::Side_of_triangle_mesh<Mesh, Kernel>>(distance_->tree);
  const Aabb box = mesh_B_->Bounds();
  box_min_B_ = box.min;
  box_max_B_ = box.max;

  // A: each triangle cut into n^2 similar sub-triangles (n = ceil(longest edge / target)).
  std::size_t total = 0;
  const double h = params.target_edge;
  for (int t = 0; t < mesh_A_->num_triangles(); ++t) {
    const Eigen::Vector3i& tri = mesh_A_->triangles[std::size_t(t)];
    const Eigen::Vector3d& a = mesh_A_->vertices[std::size_t(tri[0])];
    const Eigen::Vector3d& b = mesh_A_->vertices[std::size_t(tri[1])];
    const Eigen::Vector3d& c = mesh_A_->vertices[std::size_t(tri[2])];
    const double edge = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const std::size_t n = std::size_t(std::max(1.0, std::ceil(edge / h)));
    total += n * n;
    if (total > 50'000'000) Fail(where, "target_edge " + std::to_string(h) + " m gives more than 50 million samples");
  }
  point_A_.reserve(total);
  normal_A_.reserve(total);
  weight_.reserve(total);
  for (int t = 0; t < mesh_A_->num_triangles(); ++t) {
    const Eigen::Vector3i& tri = mesh_A_->triangles[std::size_t(t)];
    const Eigen::Vector3d& a = mesh_A_->vertices[std::size_t(tri[0])];
    const Eigen::Vector3d& b = mesh_A_->vertices[std::size_t(tri[1])];
    const Eigen::Vector3d& c = mesh_A_->vertices[std::size_t(tri[2])];
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double area = 0.5 * cross.norm();
    if (!(area > 0)) continue;
    const Eigen::Vector3d N = -cross.normalized();
    const double edge = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int n = int(std::max(1.0, std::ceil(edge / h)));
    const Eigen::Vector3d u = (b - a) / n, v = (c - a) / n;
    const double w = area / (double(n) * n);
    // Upward sub-triangles (i, j), (i+1, j), (i, j+1) and downward ones (i+1, j), (i+1, j+1), (i, j+1).
    for (int i = 0; i < n; ++i) {
      for (int j = 0; i + j < n; ++j) {
        point_A_.push_back(a + (i + 1.0 / 3) * u + (j + 1.0 / 3) * v);
        normal_A_.push_back(N);
        weight_.push_back(w);
        if (i + j + 1 < n) {
          point_A_.push_back(a + (i + 2.0 / 3) * u + (j + 2.0 / 3) * v);
          normal_A_.push_back(N);
          weight_.push_back(w);
        }
      }
    }
  }
}

QuadratureReference::~QuadratureReference() = default;

double QuadratureReference::SignedDistance(const Eigen::Vector3d& p_B) const {
  const Point q(p_B.x(), p_B.y(), p_B.z());
  const double d = std::sqrt(distance_->tree.squared_distance(q));
  return (*distance_->inside)(q) == CGAL::ON_BOUNDED_SIDE ? -d : d;
}

ContactResult QuadratureReference::Compute(const Pose& X_WA, const Pose& X_WB, double* area_inside) const {
  const Pose X_BA = X_WB.Inverse() * X_WA;
  const Eigen::Matrix3d R_BA = X_BA.R();
  // Pass 1: samples inside B, with their weighted d N terms (weights normalised at the end).
  ContactAccumulator acc;
  double area = 0, max_pen = 0;
  int inside = 0;
  std::int64_t examined = 0;
  // The accumulator adds d N and N g^T; feeding it (w d, N) and g = w N gives the weighted
  // sums, and dividing k by the inside area afterwards gives the area averages.
  for (std::size_t s = 0; s < weight_.size(); ++s) {
    const Eigen::Vector3d p_B = R_BA * point_A_[s] + X_BA.translation;
    if ((p_B.array() < box_min_B_.array()).any() || (p_B.array() > box_max_B_.array()).any()) continue;
    ++examined;
    const Point q(p_B.x(), p_B.y(), p_B.z());
    if ((*distance_->inside)(q) != CGAL::ON_BOUNDED_SIDE) continue;
    const double d = -std::sqrt(distance_->tree.squared_distance(q));
    const Eigen::Vector3d N_B = R_BA * normal_A_[s];
    acc.Add(p_B, N_B, weight_[s] * d, weight_[s] * N_B);
    area += weight_[s];
    max_pen = std::max(max_pen, -d);
    ++inside;
  }
  ContactResult out;
  if (area_inside) *area_inside = area;
  if (inside == 0) return out;
  acc.Finish(PenaltyParams{params_.penalty.k_C * params_.penalty.L / area, /*L=*/0}, X_WB, &out);
  out.stats.points_in_contact = inside;
  out.stats.nodes_visited = examined;
  out.stats.max_penetration = max_pen;
  out.stats.stiffness_scale = 1;
  return out;
}

ForceLimit QuadratureReference::Limit(const Pose& X_WA, const Pose& X_WB) const {
  ForceLimit out;
  const ContactResult r = Compute(X_WA, X_WB, &out.area_inside);
  out.on_B = r.on_B;
  out.max_penetration = r.stats.max_penetration;
  return out;
}

ContactResult QuadratureReference::Evaluate(const ContactQuery& query) { return Compute(query.X_WA, query.X_WB, nullptr); }

}  // namespace contactlab
