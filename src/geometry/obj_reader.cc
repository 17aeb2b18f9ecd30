// Wavefront OBJ reader: "v" and "f" records (v, v/vt, v//vn, v/vt/vn; negative indices count
// back from the last vertex); every other record is ignored. Polygons are fan-triangulated.
#include <climits>
#include <string>
#include <vector>

#include "geometry/line_scanner.h"
#include "geometry/mesh_readers.h"

namespace contactlab::internal {

TriangleMesh ReadObj(std::string_view text, std::string_view file) {
  TriangleMesh mesh;
  LineScanner scanner(text, file);
  std::vector<int> polygon;
  while (scanner.NextLine()) {
    const std::string_view key = scanner.NextToken();
    if (key == "v") {
      // A vertex: x y z, then an optional w or colour that we ignore.
      const double x = scanner.ReadDouble("vertex x coordinate");
      const double y = scanner.ReadDouble("vertex y coordinate");
      const double z = scanner.ReadDouble("vertex z coordinate");
      if (mesh.vertices.size() >= std::size_t(INT_MAX)) scanner.Fail("too many vertices");
      mesh.vertices.emplace_back(x, y, z);
    } else if (key == "f") {
      // A face: the vertex index is the part of each token before the first '/'.
      polygon.clear();
      const long long n = static_cast<long long>(mesh.vertices.size());
      for (std::string_view token = scanner.NextToken(); !token.empty(); token = scanner.NextToken()) {
        const std::string_view index_text = token.substr(0, token.find('/'));
        long long index = 0;
        if (!LineScanner::ParseInt(index_text, &index)) {
          scanner.Fail("bad face vertex '" + QuoteToken(token) + "' (expected an integer index)");
        }
        if (index == 0) scanner.Fail("face vertex index 0 (OBJ indices start at 1)");
        const long long k = index > 0 ? index - 1 : n + index;
        if (k < 0 || k >= n) {
          scanner.Fail("face vertex index " + std::to_string(index) + " out of range (" +
                       std::to_string(n) + " vertices defined so far)");
        }
        polygon.push_back(static_cast<int>(k));
      }
      if (polygon.size() < 3) {
        scanner.Fail("face with " + std::to_string(polygon.size()) + " vertices (at least 3 needed)");
      }
      AppendFan(polygon.data(), static_cast<int>(polygon.size()), &mesh);
    }
    // Anything else (vt, vn, g, o, s, usemtl, mtllib, l, comments, blank lines) is ignored.
  }
  if (mesh.triangles.empty()) Fail(file, "no faces: the mesh has no triangles");
  return mesh;
}

}  // namespace contactlab::internal
