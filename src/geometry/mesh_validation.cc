// ValidateMesh: counts and topology (boundary, non-manifold and inconsistently oriented edges,
// components) on the mesh with coincident vertices welded; decides whether the closed-mesh
// pipeline of Barbič & James 2008 sec. 2.3 applies or the polygon-soup one is needed.
#include "geometry/mesh_validation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <numeric>
#include <sstream>
#include <vector>

#include "geometry/weld_vertices.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Relative zero-area threshold: |e1 x e2| <= kDegenerateTolerance * (longest edge)^2.
constexpr double kDegenerateTolerance = 1e-12;

// One use of an undirected edge by a triangle: endpoints sorted, FORWARD when the triangle
// traverses it from lo to hi.
struct EdgeUse {
  int lo;
  int hi;
  bool forward;
};

struct EdgeCounts {
  int edges = 0;
  int boundary = 0;
  int nonmanifold = 0;
  int inconsistent = 0;
};

// Groups the uses of each undirected edge; counts boundary (one use), non-manifold (three or
// more) and inconsistently oriented edges (more uses in one direction than the other can
// balance). Sorts USES.
EdgeCounts CountEdges(std::vector<EdgeUse>& uses) {
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi;
  });
  EdgeCounts counts;
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    int forward = 0;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) forward += uses[j++].forward;
    const int count = static_cast<int>(j - i);
    const int backward = count - forward;
    ++counts.edges;
    counts.boundary += count == 1;
    counts.nonmanifold += count >= 3;
    counts.inconsistent += count >= 2 && std::abs(forward - backward) > count % 2;
    i = j;
  }
  return counts;
}

int FindRoot(std::vector<int>& parent, int i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

std::string FormatDouble(double v) {
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), "%.9g", v);
  return buffer;
}

}  // namespace

MeshReport ValidateMesh(const TriangleMesh& mesh) {
  const std::string where = mesh.name.empty() ? std::string("ValidateMesh") : "ValidateMesh(" + mesh.name + ")";
  MeshReport report;
  report.vertices = mesh.num_vertices();
  report.triangles = mesh.num_triangles();
  const int nv = report.vertices;

  // Preconditions: finite positions and indices in range.
  for (int i = 0; i < nv; ++i) {
    if (!mesh.vertices[i].allFinite()) Fail(where, "vertex " + std::to_string(i) + " is not finite");
  }
  for (int t = 0; t < report.triangles; ++t) {
    const Eigen::Vector3i& f = mesh.triangles[t];
    if ((f.array() < 0).any() || (f.array() >= nv).any()) {
      Fail(where, "triangle " + std::to_string(t) + " has a vertex index out of range [0, " + std::to_string(nv) + ")");
    }
  }

  // Vertices: duplicates by exact position, unreferenced ones.
  const std::vector<int> rep = FindExactDuplicateVertices(mesh.vertices);
  std::vector<char> referenced(nv, 0);
  for (int i = 0; i < nv; ++i) report.duplicate_vertices += rep[i] != i;
  for (const Eigen::Vector3i& f : mesh.triangles) {
    for (int k = 0; k < 3; ++k) referenced[f[k]] = 1;
  }
  report.unreferenced_vertices = nv - static_cast<int>(std::count(referenced.begin(), referenced.end(), 1));

  // Triangles on welded indices: degenerate ones, duplicates (same sorted vertex set), edges.
  std::vector<Eigen::Vector3i> sorted_faces;
  std::vector<EdgeUse> uses;
  sorted_faces.reserve(report.triangles);
  uses.reserve(3 * std::size_t(report.triangles));
  std::vector<int> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  for (const Eigen::Vector3i& f : mesh.triangles) {
    const Eigen::Vector3i w(rep[f[0]], rep[f[1]], rep[f[2]]);
    const bool collapsed = w[0] == w[1] || w[1] == w[2] || w[2] == w[0];
    const Eigen::Vector3d& a = mesh.vertices[f[0]];
    const Eigen::Vector3d& b = mesh.vertices[f[1]];
    const Eigen::Vector3d& c = mesh.vertices[f[2]];
    const double longest2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const bool zero_area = (b - a).cross(c - a).norm() <= kDegenerateTolerance * longest2;
    report.degenerate_triangles += collapsed || zero_area;
    Eigen::Vector3i s = w;
    std::sort(s.data(), s.data() + 3);
    sorted_faces.push_back(s);
    // A triangle with a repeated (welded) vertex has no proper edges: left out of the topology.
    if (collapsed) continue;
    for (int k = 0; k < 3; ++k) {
      const int u = w[k];
      const int v = w[(k + 1) % 3];
      uses.push_back({std::min(u, v), std::max(u, v), u < v});
      parent[FindRoot(parent, u)] = FindRoot(parent, v);
    }
  }
  std::sort(sorted_faces.begin(), sorted_faces.end(), [](const Eigen::Vector3i& x, const Eigen::Vector3i& y) {
    return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
  });
  for (std::size_t i = 1; i < sorted_faces.size(); ++i) report.duplicate_triangles += sorted_faces[i] == sorted_faces[i - 1];

  // Edges on welded vertices, then (for comparison with tools that do not weld) on the
  // indices as stored.
  const EdgeCounts welded = CountEdges(uses);
  report.edges = welded.edges;
  report.boundary_edges = welded.boundary;
  report.nonmanifold_edges = welded.nonmanifold;
  report.inconsistent_edges = welded.inconsistent;
  {
    std::vector<EdgeUse> raw_uses;
    raw_uses.reserve(3 * std::size_t(report.triangles));
    for (const Eigen::Vector3i& f : mesh.triangles) {
      if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) continue;
      for (int k = 0; k < 3; ++k) {
        const int u = f[k];
        const int v = f[(k + 1) % 3];
        raw_uses.push_back({std::min(u, v), std::max(u, v), u < v});
      }
    }
    report.unwelded_boundary_edges = CountEdges(raw_uses).boundary;
  }

  // Components: connected sets of welded vertices used by proper triangles.
  std::vector<char> is_root(nv, 0);
  for (const EdgeUse& e : uses) is_root[FindRoot(parent, e.lo)] = 1;
  report.components = static_cast<int>(std::count(is_root.begin(), is_root.end(), 1));

  // Summary properties and measures.
  const bool has_faces = !uses.empty();
  report.closed = has_faces && report.boundary_edges == 0 && report.nonmanifold_edges == 0;
  report.consistently_oriented = has_faces && report.inconsistent_edges == 0;
  report.watertight = report.closed && report.consistently_oriented;
  report.surface_area = mesh.SurfaceArea();
  report.signed_volume = mesh.SignedVolume();
  report.bounds = mesh.Bounds();
  return report;
}

std::string MeshReport::ToText() const {
  std::ostringstream out;
  const auto yes_no = [](bool b) { return b ? "yes" : "no"; };
  out << "vertices:                " << vertices << "\n"
      << "triangles:               " << triangles << "\n"
      << "unreferenced vertices:   " << unreferenced_vertices << "\n"
      << "duplicate vertices:      " << duplicate_vertices << "\n"
      << "degenerate triangles:    " << degenerate_triangles << "\n"
      << "duplicate triangles:     " << duplicate_triangles << "\n"
      << "edges (welded):          " << edges << "\n"
      << "boundary edges:          " << boundary_edges << "\n"
      << "  without welding:       " << unwelded_boundary_edges << "\n"
      << "non-manifold edges:      " << nonmanifold_edges << "\n"
      << "inconsistent edges:      " << inconsistent_edges << "\n"
      << "components:              " << components << "\n"
      << "closed:                  " << yes_no(closed) << "\n"
      << "consistently oriented:   " << yes_no(consistently_oriented) << "\n"
      << "watertight:              " << yes_no(watertight) << "\n"
      << "surface area:            " << FormatDouble(surface_area) << "\n"
      << "signed volume:           " << FormatDouble(signed_volume) << (watertight ? "" : " (not meaningful: not watertight)") << "\n";
  if (bounds.empty()) {
    out << "bounds:                  empty\n";
  } else {
    out << "bounds min:              " << FormatDouble(bounds.min.x()) << " " << FormatDouble(bounds.min.y()) << " "
        << FormatDouble(bounds.min.z()) << "\n"
        << "bounds max:              " << FormatDouble(bounds.max.x()) << " " << FormatDouble(bounds.max.y()) << " "
        << FormatDouble(bounds.max.z()) << "\n"
        << "bounds size:             " << FormatDouble(bounds.size().x()) << " " << FormatDouble(bounds.size().y())
        << " " << FormatDouble(bounds.size().z()) << "\n";
  }
  return out.str();
}

std::string MeshReport::ToJson() const {
  nlohmann::ordered_json j;
  j["vertices"] = vertices;
  j["triangles"] = triangles;
  j["unreferenced_vertices"] = unreferenced_vertices;
  j["duplicate_vertices"] = duplicate_vertices;
  j["degenerate_triangles"] = degenerate_triangles;
  j["duplicate_triangles"] = duplicate_triangles;
  j["edges"] = edges;
  j["boundary_edges"] = boundary_edges;
  j["unwelded_boundary_edges"] = unwelded_boundary_edges;
  j["nonmanifold_edges"] = nonmanifold_edges;
  j["inconsistent_edges"] = inconsistent_edges;
  j["components"] = components;
  j["closed"] = closed;
  j["consistently_oriented"] = consistently_oriented;
  j["watertight"] = watertight;
  j["surface_area"] = surface_area;
  j["signed_volume"] = signed_volume;
  if (bounds.empty()) {
    j["bounds"] = nullptr;
  } else {
    j["bounds"] = {{"min", {bounds.min.x(), bounds.min.y(), bounds.min.z()}},
                   {"max", {bounds.max.x(), bounds.max.y(), bounds.max.z()}}};
  }
  return j.dump(2);
}

}  // namespace contactlab
