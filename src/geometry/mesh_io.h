// Mesh readers: OBJ, OFF, STL (ASCII and binary), PLY (ASCII and binary little/big endian),
// each also read gzip-compressed (.obj.gz, .off.gz, .stl.gz, .ply.gz) through zlib.
// Quads and n-gons are fan-triangulated. Polygon soups are accepted as they are.
// Format details (readers in obj_reader.cc, off_reader.cc, stl_reader.cc, ply_reader.cc):
//  - OBJ: "v" and "f" records only (v, v/vt, v//vn, v/vt/vn; negative indices relative to the
//    vertices read so far; a face may only use vertices defined before it).
//  - OFF: optional '#' comments; OFF/COFF/NOFF/CNOFF/STOFF headers (extra values ignored);
//    counts on the header line or the next one; ASCII only.
//  - STL: binary when the size is 84 + 50 n (also under a "solid" header), else ASCII when it
//    starts with "solid" and is text. Vertices are welded by exact position (shared vertices).
//  - PLY: vertex x, y, z of any scalar type; face list "vertex_indices" or "vertex_index" with
//    any integer count and index types; other properties, lists and elements are skipped.
//    ASCII PLY holds one element record per line.
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

// Reads PATH (format from its extension, case-insensitive: .obj .off .stl .ply, each also
// gzip-compressed as .obj.gz etc.; the mesh is named without ".gz") and applies
// p <- rotation * (scale * p - c) + translation, c the box centre when CENTER is set, else 0.
// Throws Error naming the file and the line (text formats) or record (binary formats) for: a
// missing or unreadable file, an unknown extension, a malformed or truncated file, NaN or Inf
// coordinates, out-of-range or negative indices, a corrupt or truncated .gz, and a mesh with
// no triangles.
TriangleMesh LoadMesh(const std::filesystem::path& path, const MeshLoadOptions& options = {});

// Writes MESH as OBJ, OFF, STL (binary) or PLY (binary) by extension, atomically (temporary
// file renamed onto PATH). OBJ, OFF and PLY (double) keep positions exactly; STL rounds them
// to float. Throws Error naming PATH for an unknown extension, an index out of range, a
// coordinate that is not finite or beyond kMaxCoordinate (what LoadMesh refuses), or a failed
// write; nothing is written then.
void SaveMesh(const TriangleMesh& mesh, const std::filesystem::path& path);

}  // namespace contactlab
