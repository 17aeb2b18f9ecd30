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

// What a PLY read cost, counted in records rather than time, so that a test can bound the
// work of a read (fuzz-found inputs that made the reader loop) without timing it.
struct PlyReadStats {
  long long records_visited = 0;  // records the body loops stepped through, one by one
  long long records_skipped = 0;  // records of binary elements without properties: no bytes, passed over whole
  // When >= 0, a budget: the read throws Error as soon as its loops would step through more
  // records than this (so a reader that steps through empty records fails at once).
  long long max_records_visited = -1;
};

// ASCII, binary_little_endian or binary_big_endian. With STATS, counts the records visited
// and skipped, and keeps to its budget.
TriangleMesh ReadPly(std::string_view bytes, std::string_view file, PlyReadStats* stats = nullptr);

// Appends the fan triangulation (p0, p_i, p_i+1) of polygon POLY (>= 3 indices).
inline void AppendFan(const int* poly, int n, TriangleMesh* mesh) {
  for (int i = 1; i + 1 < n; ++i) mesh->triangles.emplace_back(poly[0], poly[i], poly[i + 1]);
}

}  // namespace contactlab::internal
