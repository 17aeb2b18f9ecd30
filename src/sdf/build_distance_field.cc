// Building signed distance fields from closed meshes and polygon soups (Barbič & James 2008,
// sec. 2.3).
#include "sdf/build_distance_field.h"

#include "util/isolated_parallel.h"

#include <chrono>
#include <cmath>

#include "geometry/mesh_validation.h"
#include "sdf/enclosed_components.h"
#include "sdf/field_grid.h"
#include "sdf/marching_cubes.h"
#include "sdf/mesh_signed_distance.h"
#include "sdf/signed_distance_grid.h"
#include "sdf/sparse_field.h"
#include "sdf/unsigned_distance_grid.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr int kClosedBandVoxels = 3;

std::string MeshWhere(const TriangleMesh& mesh) { return mesh.name.empty() ? std::string("mesh") : mesh.name; }

void CheckInputs(const TriangleMesh& mesh, const DistanceFieldOptions& options) {
  const std::string where = MeshWhere(mesh);
  if (mesh.empty()) Fail(where, "has no triangles; cannot build a distance field");
  if (options.resolution < 8 || options.resolution > 1024) {
    Fail(where, "distance-field resolution " + std::to_string(options.resolution) + " is outside [8, 1024]");
  }
  if (!(options.padding >= 0 && options.padding <= kMaxFieldPadding)) {
    Fail(where, "distance-field padding must lie in [0, 4] (a fraction of the largest extent per side)");
  }
  if (!std::isfinite(options.soup_offset)) Fail(where, "soup offset must be finite");
  for (const auto& t : mesh.triangles) {
    if ((t.array() < 0).any() || (t.array() >= mesh.num_vertices()).any()) {
      Fail(where, "a triangle refers to a vertex that does not exist");
    }
  }
  for (const auto& v : mesh.vertices) {
    if (!v.allFinite()) Fail(where, "a vertex coordinate is not finite");
  }
  // All triangles' vertices at one point: no extent to size the grid by (the resolution would
  // be meaningless).
  if (!(mesh.Bounds().size().maxCoeff() > 0)) {
    Fail(where, "has zero extent (every vertex of its triangles is at the same point); cannot build a distance field");
  }
}

}  // namespace

FieldStorage ParseFieldStorage(const std::string& text, const std::string& where) {
  if (text == "dense") return FieldStorage::kDense;
  if (text == "sparse") return FieldStorage::kSparse;
  Fail(where, "unknown distance-field storage '" + text + "' (expected dense or sparse)");
}

FieldMode ParseFieldMode(const std::string& text, const std::string& where) {
  if (text == "auto") return FieldMode::kAuto;
  if (text == "closed") return FieldMode::kClosed;
  if (text == "soup") return FieldMode::kSoup;
  Fail(where, "unknown distance-field mode '" + text + "' (expected auto, closed or soup)");
}

namespace {

DistanceField BuildDistanceFieldImpl(const TriangleMesh& mesh, const DistanceFieldOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  CheckInputs(mesh, options);
  const std::string where = MeshWhere(mesh);

  // Pipeline: closed meshes get the exact signed field, everything else the soup pipeline.
  FieldMode mode = options.mode;
  if (mode != FieldMode::kSoup) {
    const MeshReport report = ValidateMesh(mesh);
    if (mode == FieldMode::kClosed && !report.watertight) {
      Fail(where, "is not watertight (" + std::to_string(report.boundary_edges) + " boundary edges, " +
                      std::to_string(report.nonmanifold_edges) + " non-manifold edges, " +
                      std::to_string(report.inconsistent_edges) +
                      " inconsistently oriented edges); the closed pipeline needs a watertight mesh, "
                      "use mode soup or auto");
    }
    mode = report.watertight ? FieldMode::kClosed : FieldMode::kSoup;
  }
  if (options.storage == FieldStorage::kSparse) {
    if (mode != FieldMode::kClosed) {
      Fail(where, "a sparse distance field needs a watertight mesh (the closed pipeline); use storage dense");
    }
    if (!SparseFieldStorage::ResolutionFits(options.resolution)) {
      Fail(where, "a sparse distance field needs a resolution that is a multiple of 8 and at least " +
                      std::to_string(SparseFieldStorage::kMinResolution) + ", not " + std::to_string(options.resolution));
    }
    if (options.band_voxels < 1 || options.band_voxels > SparseFieldStorage::kMaxBand) {
      Fail(where, "the sparse field's band of " + std::to_string(options.band_voxels) + " voxels is outside [1, " +
                      std::to_string(SparseFieldStorage::kMaxBand) + "]");
    }
    const FieldGrid coarse_grid =
        MakeFieldGrid(mesh.Bounds(), options.resolution / SparseFieldStorage::kBrick, options.padding);
    const MeshSignedDistance sign(mesh, where);
    SparseFieldStorage storage =
        BuildSparseStorage(mesh, sign, coarse_grid,
                           ComputeSignedDistance(mesh, coarse_grid, kClosedBandVoxels, options.show_progress),
                           options.band_voxels);
    DistanceFieldInfo info;
    info.source = mesh.name;
    info.mode = "closed";
    info.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return DistanceField(coarse_grid.origin, coarse_grid.spacing / SparseFieldStorage::kBrick, std::move(storage),
                         std::move(info));
  }
  const FieldGrid grid = MakeFieldGrid(mesh.Bounds(), options.resolution, options.padding);

  DistanceFieldInfo info;
  info.source = mesh.name;
  std::vector<float> values;
  if (mode == FieldMode::kClosed) {
    info.mode = "closed";
    values = ComputeSignedDistance(mesh, grid, kClosedBandVoxels, options.show_progress);
  } else {
    // Soup: unsigned field, offset isosurface, drop enclosed components, signed field of the rest.
    info.mode = "soup";
    const double offset = options.soup_offset < 0 ? 1.5 * grid.spacing : options.soup_offset;
    if (!(offset > 0)) Fail(where, "soup offset must be positive (or negative for the default 1.5 voxels)");
    info.offset = offset;
    const int band = std::max(kClosedBandVoxels, int(std::ceil(offset / grid.spacing)) + 2);
    std::vector<float> unsigned_distance =
        ComputeUnsignedDistance(mesh, grid, band, options.show_progress).distance;
    const TriangleMesh iso = ExtractIsosurface(unsigned_distance, grid, offset, /*close_at_boundary=*/true,
                                               where + " offset surface");
    unsigned_distance = {};
    if (iso.empty()) Fail(where, "the offset surface of the soup is empty; increase the soup offset");
    const TriangleMesh outer = RemoveEnclosedComponents(iso);
    values = ComputeSignedDistance(outer, grid, kClosedBandVoxels, options.show_progress);
  }
  info.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return DistanceField(grid.origin, grid.spacing, grid.dims, std::move(values), std::move(info));
}

}  // namespace

DistanceField BuildDistanceField(const TriangleMesh& mesh, const DistanceFieldOptions& options) {
  return RunIsolatedFromCancellation([&] { return BuildDistanceFieldImpl(mesh, options); });
}

}  // namespace contactlab
