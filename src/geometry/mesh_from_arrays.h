// A triangle mesh from another tool's arrays (NumPy, trimesh, Open3D): row-major vertex and
// index arrays, checked as LoadMesh (geometry/mesh_io.h) checks what a file reader returns.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "geometry/triangle_mesh.h"

namespace contactlab {

// The mesh named NAME of VERTICES, #V*3 doubles (x, y, z per row, metres), and TRIANGLES,
// #T*3 zero-based vertex indices (counter-clockwise seen from outside), both row-major.
// Polygon soups pass, as from the readers. Throws Error("WHERE: ...") naming the row for what a
// reader refuses (CheckMeshContent), and for an array whose length is no multiple of 3.
TriangleMesh MeshFromArrays(std::span<const double> vertices, std::span<const std::int64_t> triangles,
                            std::string name, std::string_view where);

// Throws Error("WHERE: ...") naming the vertex or triangle for what every mesh reader refuses:
// a vertex that is not finite or beyond kMaxCoordinate, a negative or out-of-range index, no
// triangles. What a mesh built in memory passes before it stands for a file.
void CheckMeshContent(const TriangleMesh& mesh, std::string_view where);

}  // namespace contactlab
