// Mesh readers: OBJ, OFF, STL (ASCII and binary), PLY (ASCII and binary little/big endian).
// Quads and n-gons are fan-triangulated. Polygon soups are accepted as they are.
#pragma once

#include <Eigen/Core>
#include <filesystem>

#include "geometry/triangle_mesh.h"

namespace contactlab {

struct MeshLoadOptions {
  double scale = 1.0;                                      // file units -> metres
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // applied after scaling
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();   // metres, applied last
  bool center = false;  // translate the bounding-box centre to the origin before rotating
};

// Reads PATH (format from its extension, case-insensitive: .obj .off .stl .ply) and applies
// p <- rotation * (scale * p - c) + translation, c the box centre when CENTER is set, else 0.
// Throws Error naming the file and the line (text formats) or record (binary formats) for: a
// missing or unreadable file, an unknown extension, a malformed or truncated file, NaN or Inf
// coordinates, out-of-range or negative indices, and a mesh with no triangles.
TriangleMesh LoadMesh(const std::filesystem::path& path, const MeshLoadOptions& options = {});

// Writes MESH as OBJ, OFF, STL (binary) or PLY (binary) by extension, atomically.
void SaveMesh(const TriangleMesh& mesh, const std::filesystem::path& path);

}  // namespace contactlab
