// Decimates a triangle mesh with CGAL's edge collapse (Lindstrom-Turk cost and placement),
// never collapsing a boundary edge, so holes and boundary edge counts stay as they are.
// Used by scripts/make-mesh-data.sh to make the decimated meshes of data/meshes.
//   decimate_mesh IN.obj OUT.obj TARGET_EDGES
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Constrained_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>

namespace SMS = CGAL::Surface_mesh_simplification;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Edge = boost::graph_traits<Mesh>::edge_descriptor;

// Marks the boundary edges of the mesh as constrained.
struct BorderIsConstrained {
  using key_type = Edge;
  using value_type = bool;
  using reference = bool;
  using category = boost::readable_property_map_tag;
  const Mesh* mesh;
  friend bool get(const BorderIsConstrained& m, const Edge& e) { return CGAL::is_border(e, *m.mesh); }
};

int main(int argc, char** argv) {
  if (argc != 4) {
    std::cerr << "usage: decimate_mesh IN.obj OUT.obj TARGET_EDGES\n";
    return 2;
  }
  Mesh mesh;
  if (!CGAL::IO::read_polygon_mesh(argv[1], mesh) || mesh.is_empty()) {
    std::cerr << argv[1] << ": cannot read as a polygon mesh\n";
    return 1;
  }
  const BorderIsConstrained constrained{&mesh};
  SMS::Count_stop_predicate<Mesh> stop(std::strtoul(argv[3], nullptr, 10));
  SMS::Constrained_placement<SMS::LindstromTurk_placement<Mesh>, BorderIsConstrained> placement(constrained);
  const int removed = SMS::edge_collapse(mesh, stop,
                                         CGAL::parameters::edge_is_constrained_map(constrained)
                                             .get_cost(SMS::LindstromTurk_cost<Mesh>())
                                             .get_placement(placement));
  mesh.collect_garbage();
  // OBJ with 7 significant digits (single precision is ample for these test meshes).
  std::FILE* out = std::fopen(argv[2], "w");
  if (out == nullptr) {
    std::cerr << argv[2] << ": cannot write\n";
    return 1;
  }
  for (const auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    std::fprintf(out, "v %.7g %.7g %.7g\n", p.x(), p.y(), p.z());
  }
  for (const auto f : mesh.faces()) {
    std::fprintf(out, "f");
    for (const auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) std::fprintf(out, " %u", unsigned(v) + 1);
    std::fprintf(out, "\n");
  }
  std::fclose(out);
  std::cerr << argv[1] << ": removed " << removed << " edges; " << mesh.number_of_faces() << " triangles, "
            << mesh.number_of_vertices() << " vertices\n";
  return 0;
}
