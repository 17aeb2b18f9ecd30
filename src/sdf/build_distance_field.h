// Building signed distance fields from triangle meshes (Barbič & James 2008, sec. 2.3).
//
// Two pipelines: "closed" (a watertight mesh: exact point-triangle distances, robust sign)
// and "soup" (any triangle set: unsigned field, marching-cubes isosurface at a small offset,
// removal of components enclosed by others, signed field of the remaining closed surface).
//
// Accuracy (see unsigned_distance_grid.h, ray_crossing_sign.h, signed_distance_grid.h):
//  * every sample is the exact distance from its grid point to some triangle, so |value| never
//    underestimates the distance; samples within 3 voxels of the surface, and the samples on
//    the grid's boundary faces, are exact (double arithmetic, stored as float); farther ones
//    come from closest-triangle propagation and are upper bounds, typically within a small
//    fraction of a voxel (measured by experiments/bench_sdf/sdf_crosscheck against CGAL);
//  * the sign comes from signed ray crossings along grid lines in x, y, z with a majority vote
//    (non-zero winding rule), so orientation does not matter for watertight meshes;
//  * the smallest boundary sample is lowered by ~h^2/(4 d) so that the outside-the-box bound
//    of distance_field.h never overestimates.
// Soup pipeline: the zero level set of the final field is NOT the input soup but the offset
// surface at distance `offset` from it (DistanceFieldInfo::offset; default 1.5 voxels), as
// extracted by marching cubes; holes narrower than about twice the offset are closed, inner
// sheets enclosed by outer ones are dropped, and the field is the signed distance to what
// remains (≈ unsigned distance to the soup minus the offset, outside it).
#pragma once

#include <filesystem>
#include <string>

#include "geometry/triangle_mesh.h"
#include "sdf/distance_field.h"

namespace contactlab {

enum class FieldMode { kAuto, kClosed, kSoup };
// Dense: every grid sample. Sparse: fine samples in a band around the surface over a coarse
// field at 1/8 the resolution (sdf/sparse_field.h), for resolutions a dense grid cannot hold.
enum class FieldStorage { kDense, kSparse };

// The largest padding: a margin of 4 largest extents on each side, so that the body still spans
// a ninth of the field's cells (a padding of 1e308 overflowed the grid and crashed the build, and
// one of 100 left contact finer than a cell, silently giving no force).
inline constexpr double kMaxFieldPadding = 4;

struct DistanceFieldOptions {
  int resolution = 128;        // grid cells along the longest side of the padded box
  FieldMode mode = FieldMode::kAuto;  // auto: closed when the mesh validates as watertight
  double padding = 0.1;        // box margin on each side, as a fraction of the largest extent
  double soup_offset = -1;     // soup iso-offset in metres; < 0: 1.5 voxel spacings
  bool show_progress = true;   // progress on a terminal (util/progress.h)
  FieldStorage storage = FieldStorage::kDense;
  int band_voxels = 3;         // sparse: the band of fine samples, |d| <= band_voxels spacings
};

// Builds the field of MESH (metres). Throws Error naming MESH.name for an empty mesh, a
// resolution outside [8, 1024], or (forced closed mode) a mesh that is not watertight
// (ValidateMesh, geometry/mesh_validation.h; auto mode uses it to pick the pipeline), a
// padding outside [0, kMaxFieldPadding], invalid triangle indices or non-finite vertices. A sparse
// field needs a closed mesh (mode auto or closed), a resolution that is a multiple of 8 and at
// least 64, and a band of 1 to 16 voxels.
// Parallel (TBB, all cores); show_progress draws stage progress on a terminal.
DistanceField BuildDistanceField(const TriangleMesh& mesh, const DistanceFieldOptions& options = {});

// The version of what BuildDistanceField produces. Raise it with any change that alters the output
// for the same inputs: cached results (scene/scene_assets.h) of an older version are then no
// longer found.
inline constexpr int kDistanceFieldBuilderVersion = 1;

// Parses "auto" | "closed" | "soup"; throws Error naming WHERE.
FieldMode ParseFieldMode(const std::string& text, const std::string& where);
// Parses "dense" | "sparse"; throws Error naming WHERE.
FieldStorage ParseFieldStorage(const std::string& text, const std::string& where);

// Versioned binary file with a checksum (util/binary_io.h), magic "CLSDF". Version 1 (dense):
// origin (3 doubles), spacing (double), dims (3 int32), samples (float array), info (source,
// mode, offset, build seconds). Version 2 (sparse, sdf/sparse_field.h): origin, spacing, bricks
// (3 int32), band (int32), quantum (float), coarse samples (float array), brick slots (int32
// array), brick samples (int16 array), info. Save writes atomically. Load throws Error naming PATH for a missing,
// truncated, corrupt (checksum), foreign or inconsistent file.
void SaveDistanceField(const DistanceField& field, const std::filesystem::path& path);
DistanceField LoadDistanceField(const std::filesystem::path& path);

// A few lines: source, mode, offset, dims, spacing, box, value range, memory, build time. For
// a soup field it states that the zero level set is the offset surface at distance `offset`.
std::string DescribeDistanceField(const DistanceField& field);

}  // namespace contactlab
