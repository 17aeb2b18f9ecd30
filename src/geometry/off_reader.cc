// Object File Format (OFF) reader: the "OFF" header (COFF, NOFF, CNOFF, STOFF... accepted, their
// extra per-vertex values ignored), '#' comments, counts, vertices, then polygons
// fan-triangulated (trailing per-face colours ignored). Binary OFF is not supported.
#include <algorithm>
#include <climits>
#include <string>
#include <vector>

#include "geometry/line_scanner.h"
#include "geometry/mesh_readers.h"

namespace contactlab::internal {
namespace {

// OFF, COFF, NOFF, CNOFF, STOFF, STCNOFF, ...: three or more-dimensional variants
// ("4OFF", "nOFF") have other vertex layouts and are rejected.
bool IsOffKeyword(std::string_view token) {
  if (token.size() < 3 || token.substr(token.size() - 3) != "OFF") return false;
  const std::string_view prefix = token.substr(0, token.size() - 3);
  return std::all_of(prefix.begin(), prefix.end(), [](char c) { return c == 'C' || c == 'N' || c == 'S' || c == 'T'; });
}

}  // namespace

TriangleMesh ReadOff(std::string_view text, std::string_view file) {
  LineScanner scanner(text, file);
  // Header keyword.
  if (!scanner.NextContentLine()) Fail(file, "empty file: expected an OFF header");
  const std::string_view keyword = scanner.NextToken();
  if (!IsOffKeyword(keyword)) {
    scanner.Fail("not an OFF file: expected the header 'OFF', found '" +
                 QuoteToken(keyword) + "'");
  }
  if (scanner.AtLineEnd()) {
    if (!scanner.NextContentLine()) scanner.Fail("file ends before the vertex and face counts");
  } else {
    // Counts may follow the keyword on the same line ("OFF 8 6 12"), unless "OFF BINARY".
    long long dummy = 0;
    LineScanner peek = scanner;
    if (!LineScanner::ParseInt(peek.NextToken(), &dummy)) {
      scanner.Fail("unsupported OFF variant (only ASCII OFF is read): '" + QuoteToken(scanner.line()) + "'");
    }
  }

  // Counts: vertices, faces, edges (the last is optional and ignored).
  const long long num_vertices = scanner.ReadInt("vertex count");
  const long long num_faces = scanner.ReadInt("face count");
  if (num_vertices < 0 || num_faces < 0) scanner.Fail("negative vertex or face count");
  if (num_vertices >= INT_MAX || num_faces >= INT_MAX) scanner.Fail("vertex or face count too large");

  // Vertices: x y z, then anything (colour, normal) ignored. Reserve no more than the text
  // could hold, so a corrupt count cannot allocate without bound.
  TriangleMesh mesh;
  mesh.vertices.reserve(std::min<std::size_t>(num_vertices, text.size() / 6 + 1));
  for (long long i = 0; i < num_vertices; ++i) {
    if (!scanner.NextContentLine()) {
      scanner.Fail("truncated: file ends after " + std::to_string(i) + " of " +
                   std::to_string(num_vertices) + " vertices");
    }
    const double x = scanner.ReadDouble("vertex x coordinate");
    const double y = scanner.ReadDouble("vertex y coordinate");
    const double z = scanner.ReadDouble("vertex z coordinate");
    mesh.vertices.emplace_back(x, y, z);
  }

  // Faces: n i_1 ... i_n (0-based), then anything (colour) ignored.
  mesh.triangles.reserve(std::min<std::size_t>(num_faces, text.size() / 8 + 1));
  std::vector<int> polygon;
  for (long long f = 0; f < num_faces; ++f) {
    if (!scanner.NextContentLine()) {
      scanner.Fail("truncated: file ends after " + std::to_string(f) + " of " +
                   std::to_string(num_faces) + " faces");
    }
    const long long n = scanner.ReadInt("face vertex count");
    if (n < 3) scanner.Fail("face with " + std::to_string(n) + " vertices (at least 3 needed)");
    polygon.clear();
    for (long long k = 0; k < n; ++k) {
      const long long index = scanner.ReadInt("face vertex index");
      if (index < 0 || index >= num_vertices) {
        scanner.Fail("face vertex index " + std::to_string(index) + " out of range [0, " +
                     std::to_string(num_vertices) + ")");
      }
      polygon.push_back(static_cast<int>(index));
    }
    AppendFan(polygon.data(), static_cast<int>(polygon.size()), &mesh);
  }
  if (mesh.triangles.empty()) Fail(file, "no faces: the mesh has no triangles");
  return mesh;
}

}  // namespace contactlab::internal
