// Cross-check of our distance fields (Barbič & James 2008, sec. 2.3) against CGAL: exact
// distances from an AABB tree and the sign from Side_of_triangle_mesh, at every grid point
// (or every STRIDE-th along each axis). Prints max and RMS differences in voxels, overall and
// inside the exact band (|d| <= 3 voxels), and the number of sign disagreements.
//
// Usage: sdf_crosscheck [MESH ...] [--resolution N] [--stride S]   (default: dragon.obj spot.obj, 128, 1)
// GPL-3.0-or-later through CGAL: built only with CONTACTLAB_WITH_CGAL=ON.
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <tbb/combinable.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "geometry/mesh_io.h"
#include "sdf/build_distance_field.h"
#include "util/data_path.h"
#include "util/error.h"

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Side = CGAL::Side_of_triangle_mesh<Mesh, Kernel>;

struct Stats {
  double max_all = 0, sum2_all = 0, max_band = 0, sum2_band = 0;
  long count = 0, band = 0, sign_errors = 0;
  void Add(const Stats& o) {
    max_all = std::max(max_all, o.max_all);
    max_band = std::max(max_band, o.max_band);
    sum2_all += o.sum2_all;
    sum2_band += o.sum2_band;
    count += o.count;
    band += o.band;
    sign_errors += o.sign_errors;
  }
};

void CrossCheck(const std::string& name, int resolution, int stride) {
  using namespace contactlab;
  const auto path = RequireDataFile(name);
  const TriangleMesh mesh = LoadMesh(path);
  DistanceFieldOptions options;
  options.resolution = resolution;
  options.mode = FieldMode::kClosed;
  options.show_progress = false;
  const DistanceField field = BuildDistanceField(mesh, options);

  Mesh cgal;
  std::vector<Mesh::Vertex_index> v;
  for (const auto& p : mesh.vertices) v.push_back(cgal.add_vertex(Point(p.x(), p.y(), p.z())));
  for (const auto& t : mesh.triangles) cgal.add_face(v[t[0]], v[t[1]], v[t[2]]);
  if (cgal.number_of_faces() != std::size_t(mesh.num_triangles())) {
    std::cerr << name << ": CGAL rejected " << mesh.num_triangles() - cgal.number_of_faces()
              << " faces (non-manifold); comparing distances to the accepted ones only\n";
  }
  const auto start = std::chrono::steady_clock::now();
  Tree tree(faces(cgal).first, faces(cgal).second, cgal);
  tree.accelerate_distance_queries();
  tbb::enumerable_thread_specific<Side> sides([&] { return Side(cgal); });
  const double h = field.spacing();
  const Eigen::Vector3i& n = field.dims();
  tbb::combinable<Stats> stats;
  tbb::parallel_for(0, (n.z() + stride - 1) / stride, [&](int kk) {
    const int k = kk * stride;
    Stats& s = stats.local();
    Side& side = sides.local();
    for (int j = 0; j < n.y(); j += stride) {
      for (int i = 0; i < n.x(); i += stride) {
        const Eigen::Vector3d p = field.GridPoint(i, j, k);
        const Point q(p.x(), p.y(), p.z());
        double ref = std::sqrt(tree.squared_distance(q));
        if (side(q) == CGAL::ON_BOUNDED_SIDE) ref = -ref;
        const double ours = field.value(i, j, k);
        const bool boundary = i == 0 || j == 0 || k == 0 || i == n.x() - 1 || j == n.y() - 1 || k == n.z() - 1;
        if (std::abs(ref) > 1e-6 * h && (ours < 0) != (ref < 0)) ++s.sign_errors;
        if (boundary) continue;  // one boundary sample is lowered on purpose (signed_distance_grid.h)
        const double e = std::abs(std::abs(ours) - std::abs(ref)) / h;
        ++s.count;
        s.max_all = std::max(s.max_all, e);
        s.sum2_all += e * e;
        if (std::abs(ref) <= 3 * h) {
          ++s.band;
          s.max_band = std::max(s.max_band, e);
          s.sum2_band += e * e;
        }
      }
    }
  });
  Stats total;
  stats.combine_each([&](const Stats& s) { total.Add(s); });
  const double cgal_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("%s at %d^3 (%d x %d x %d points, stride %d): build %.2f s, CGAL check %.1f s\n", name.c_str(),
              resolution, n.x(), n.y(), n.z(), stride, field.info().build_seconds, cgal_seconds);
  std::printf("  |distance| difference in voxels: all %ld points max %.3g rms %.3g; band (|d| <= 3 voxels) %ld "
              "points max %.3g rms %.3g\n",
              total.count, total.max_all, std::sqrt(total.sum2_all / std::max(1L, total.count)), total.band,
              total.max_band, std::sqrt(total.sum2_band / std::max(1L, total.band)));
  std::printf("  sign disagreements: %ld\n", total.sign_errors);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> meshes;
  int resolution = 128, stride = 1;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--resolution" && a + 1 < argc) resolution = std::stoi(argv[++a]);
    else if (arg == "--stride" && a + 1 < argc) stride = std::max(1, std::stoi(argv[++a]));
    else meshes.push_back(arg);
  }
  if (meshes.empty()) meshes = {"dragon.obj", "spot.obj"};
  try {
    for (const auto& m : meshes) CrossCheck(m, resolution, stride);
  } catch (const contactlab::Error& e) {
    std::cerr << "sdf_crosscheck: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
