// Building signed distance fields from triangle meshes (Barbič & James 2008, sec. 2.3).
//
// Two pipelines: "closed" (a watertight mesh: exact point-triangle distances, robust sign)
// and "soup" (any triangle set: unsigned field, marching-cubes isosurface at a small offset,
// removal of components enclosed by others, signed field of the remaining closed surface).
#pragma once

#include <filesystem>
#include <string>

#include "geometry/triangle_mesh.h"
#include "sdf/distance_field.h"

namespace contactlab {

enum class FieldMode { kAuto, kClosed, kSoup };

struct DistanceFieldOptions {
  int resolution = 128;        // grid cells along the longest side of the padded box
  FieldMode mode = FieldMode::kAuto;  // auto: closed when the mesh validates as watertight
  double padding = 0.1;        // box margin on each side, as a fraction of the largest extent
  double soup_offset = -1;     // soup iso-offset in metres; < 0: 1.5 voxel spacings
  bool show_progress = true;   // progress on a terminal (util/progress.h)
};

// Builds the field of MESH (metres). Throws Error naming MESH.name for an empty mesh, a
// resolution outside [8, 1024], or (forced closed mode) a mesh that is not watertight.
DistanceField BuildDistanceField(const TriangleMesh& mesh, const DistanceFieldOptions& options = {});

// Parses "auto" | "closed" | "soup"; throws Error naming WHERE.
FieldMode ParseFieldMode(const std::string& text, const std::string& where);

// Versioned binary file with a checksum (util/binary_io.h), magic "CLSDF".
void SaveDistanceField(const DistanceField& field, const std::filesystem::path& path);
DistanceField LoadDistanceField(const std::filesystem::path& path);

// A few lines: source, mode, offset, dims, spacing, box, value range, memory, build time.
std::string DescribeDistanceField(const DistanceField& field);

}  // namespace contactlab
