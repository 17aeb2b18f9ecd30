// The per-format mesh readers behind LoadMesh (geometry/mesh_io.h); internal to the geometry
// module. Each parses a whole file held in memory and throws Error naming FILE and the line
// (text) or record and byte offset (binary) of the first problem.
#pragma once

#include <string_view>

#include "geometry/triangle_mesh.h"

namespace contactlab::internal {

// Each returns a mesh with at least one triangle and all indices in range, or throws.
TriangleMesh ReadObj(std::string_view text, std::string_view file);
TriangleMesh ReadOff(std::string_view text, std::string_view file);
// ASCII or binary (told apart by the size check 84 + 50 n); vertices welded by exact position.
TriangleMesh ReadStl(std::string_view bytes, std::string_view file);
// ASCII, binary_little_endian or binary_big_endian.
TriangleMesh ReadPly(std::string_view bytes, std::string_view file);

// Appends the fan triangulation (p0, p_i, p_i+1) of polygon POLY (>= 3 indices).
inline void AppendFan(const int* poly, int n, TriangleMesh* mesh) {
  for (int i = 1; i + 1 < n; ++i) mesh->triangles.emplace_back(poly[0], poly[i], poly[i + 1]);
}

}  // namespace contactlab::internal
