// Narrow-band exact distances plus closest-triangle propagation (Barbič & James 2008, sec. 2.3).
#include "sdf/unsigned_distance_grid.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "sdf/point_triangle_distance.h"
#include "sdf/triangle_bvh.h"
#include "util/progress.h"

namespace contactlab {

std::vector<double> FlattenTriangles(const TriangleMesh& mesh) {
  std::vector<double> corners(std::size_t(mesh.num_triangles()) * 9);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d& v = mesh.vertices[mesh.triangles[t][c]];
      for (int a = 0; a < 3; ++a) corners[std::size_t(t) * 9 + 3 * c + a] = v[a];
    }
  }
  return corners;
}

namespace {

// The grid being filled: its size and placement, the flattened triangles (FlattenTriangles),
// and per sample the squared distance so far (D2) and the triangle behind it (CLOSEST, -1: none).
struct DistanceSamples {
  int nx, ny, nz;
  std::int64_t sy, sz;    // index strides of y and z (x fastest)
  double h, ox, oy, oz;   // spacing and origin, metres
  const std::vector<double>& tri;
  std::vector<float>& d2;
  std::vector<std::int32_t>& closest;
};

// Index box of every triangle's bounding box grown by the band (lo > hi: misses the grid):
// (i, j, k) lo then (i, j, k) hi per triangle.
std::vector<std::array<int, 6>> BandBoxes(const std::vector<double>& tri, int num_tri, const FieldGrid& grid,
                                          double band) {
  const double h = grid.spacing;
  std::vector<std::array<int, 6>> boxes(num_tri);
  for (int t = 0; t < num_tri; ++t) {
    const double* c = &tri[std::size_t(t) * 9];
    for (int a = 0; a < 3; ++a) {
      const double mn = std::min({c[a], c[3 + a], c[6 + a]}), mx = std::max({c[a], c[3 + a], c[6 + a]});
      const double lo = std::ceil((mn - band - grid.origin[a]) / h - 1e-9);
      const double hi = std::floor((mx + band - grid.origin[a]) / h + 1e-9);
      boxes[t][a] = int(std::clamp(lo, 0.0, double(grid.dims[a])));
      boxes[t][3 + a] = int(std::clamp(hi, -1.0, double(grid.dims[a] - 1)));
    }
  }
  return boxes;
}

// Triangles bucketed by the z-slabs (SLAB planes each) their boxes reach, in CSR form: slab s
// holds bucket[start[s]] .. bucket[start[s + 1] - 1].
struct SlabBuckets {
  std::vector<std::int64_t> start;
  std::vector<std::int32_t> bucket;
};

SlabBuckets BucketBySlab(const std::vector<std::array<int, 6>>& boxes, int num_slabs, int slab) {
  const int num_tri = int(boxes.size());
  SlabBuckets out;
  std::vector<std::int64_t>& start = out.start;
  start.assign(num_slabs + 1, 0);
  for (int t = 0; t < num_tri; ++t) {
    const auto& b = boxes[t];
    if (b[0] > b[3] || b[1] > b[4] || b[2] > b[5]) continue;
    for (int s = b[2] / slab; s <= b[5] / slab; ++s) ++start[s + 1];
  }
  for (int s = 0; s < num_slabs; ++s) start[s + 1] += start[s];
  out.bucket.resize(start[num_slabs]);
  std::vector<std::int64_t> fill(start.begin(), start.end() - 1);
  for (int t = 0; t < num_tri; ++t) {
    const auto& b = boxes[t];
    if (b[0] > b[3] || b[1] > b[4] || b[2] > b[5]) continue;
    for (int s = b[2] / slab; s <= b[5] / slab; ++s) out.bucket[fill[s]++] = t;
  }
  return out;
}

// Exact distances in the band: every triangle against the samples of its box, slab by slab in
// parallel (a slab's samples are written by its own task only).
void FillExactBand(DistanceSamples& g, const std::vector<std::array<int, 6>>& boxes, const SlabBuckets& slabs,
                   int slab, bool show_progress) {
  const int num_slabs = int(slabs.start.size()) - 1;
  const int nz = g.nz;
  const std::int64_t sy = g.sy, sz = g.sz;
  const double h = g.h, ox = g.ox, oy = g.oy, oz = g.oz;
  const std::vector<double>& tri = g.tri;
  std::vector<float>& d2 = g.d2;
  std::vector<std::int32_t>& closest = g.closest;
  std::optional<Progress> progress;
  if (show_progress) progress.emplace("distance field: exact band", num_slabs);
  tbb::parallel_for(tbb::blocked_range<int>(0, num_slabs), [&](const tbb::blocked_range<int>& r) {
    for (int s = r.begin(); s != r.end(); ++s) {
      const int k_begin = s * slab, k_end = std::min(nz, k_begin + slab);
      for (std::int64_t e = slabs.start[s]; e < slabs.start[s + 1]; ++e) {
        const int t = slabs.bucket[e];
        const auto& b = boxes[t];
        const double* c = &tri[std::size_t(t) * 9];
        for (int k = std::max(b[2], k_begin); k <= std::min(b[5], k_end - 1); ++k) {
          for (int j = b[1]; j <= b[4]; ++j) {
            double p[3] = {0, oy + h * j, oz + h * k};
            std::int64_t idx = b[0] + sy * j + sz * k;
            for (int i = b[0]; i <= b[3]; ++i, ++idx) {
              p[0] = ox + h * i;
              const double dd = PointTriangleDistanceSquared(p, c, c + 3, c + 6);
              if (dd < d2[idx]) {
                d2[idx] = float(dd);
                closest[idx] = t;
              }
            }
          }
        }
      }
      if (progress) progress->Advance();
    }
  });
  if (progress) progress->Finish();
}

// Closest-triangle propagation: a point tries the triangle of its predecessor along the pass,
// ROUNDS times forward and backward along x, y and z.
void PropagateClosest(DistanceSamples& g, int rounds, bool show_progress) {
  const int nx = g.nx, ny = g.ny, nz = g.nz;
  const std::int64_t sy = g.sy, sz = g.sz;
  const double h = g.h, ox = g.ox, oy = g.oy, oz = g.oz;
  const std::vector<double>& tri = g.tri;
  std::vector<float>& d2 = g.d2;
  std::vector<std::int32_t>& closest = g.closest;
  auto relax = [&](std::int64_t idx, std::int64_t from, int i, int j, int k) {
    const std::int32_t t = closest[from];
    if (t < 0 || t == closest[idx]) return;
    const double p[3] = {ox + h * i, oy + h * j, oz + h * k};
    const double* c = &tri[std::size_t(t) * 9];
    const double dd = PointTriangleDistanceSquared(p, c, c + 3, c + 6);
    if (dd < d2[idx]) {
      d2[idx] = float(dd);
      closest[idx] = t;
    }
  };
  std::optional<Progress> progress;
  if (show_progress) progress.emplace("distance field: propagation", std::int64_t(rounds) * (2 * nz + ny));
  for (int round = 0; round < rounds; ++round) {
    // Along x: rows are independent.
    tbb::parallel_for(0, nz, [&](int k) {
      for (int j = 0; j < ny; ++j) {
        const std::int64_t row = sy * j + sz * k;
        for (int i = 1; i < nx; ++i) relax(row + i, row + i - 1, i, j, k);
        for (int i = nx - 2; i >= 0; --i) relax(row + i, row + i + 1, i, j, k);
      }
      if (progress) progress->Advance();
    });
    // Along y: each z-plane is independent.
    tbb::parallel_for(0, nz, [&](int k) {
      for (int j = 1; j < ny; ++j)
        for (int i = 0; i < nx; ++i) relax(i + sy * j + sz * k, i + sy * (j - 1) + sz * k, i, j, k);
      for (int j = ny - 2; j >= 0; --j)
        for (int i = 0; i < nx; ++i) relax(i + sy * j + sz * k, i + sy * (j + 1) + sz * k, i, j, k);
      if (progress) progress->Advance();
    });
    // Along z: each y-row-plane (fixed j) is independent.
    tbb::parallel_for(0, ny, [&](int j) {
      for (int k = 1; k < nz; ++k)
        for (int i = 0; i < nx; ++i) relax(i + sy * j + sz * k, i + sy * j + sz * (k - 1), i, j, k);
      for (int k = nz - 2; k >= 0; --k)
        for (int i = 0; i < nx; ++i) relax(i + sy * j + sz * k, i + sy * j + sz * (k + 1), i, j, k);
      if (progress) progress->Advance();
    });
  }
  if (progress) progress->Finish();
}

// Exact samples on the grid's boundary faces (the outside-box bound uses their minimum): BVH
// queries bounded by the propagated values.
void FillExactBoundary(DistanceSamples& g, bool show_progress) {
  const int nx = g.nx, ny = g.ny, nz = g.nz;
  const std::int64_t sy = g.sy, sz = g.sz;
  const double h = g.h, ox = g.ox, oy = g.oy, oz = g.oz;
  std::vector<float>& d2 = g.d2;
  std::vector<std::int32_t>& closest = g.closest;
  std::vector<std::int64_t> boundary;
  boundary.reserve(std::size_t(2) * (sz + sy * nz + std::int64_t(ny) * nz));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j) {
      const bool face = k == 0 || k == nz - 1 || j == 0 || j == ny - 1;
      for (int i = 0; i < nx; i += face ? 1 : std::max(1, nx - 1)) boundary.push_back(i + sy * j + sz * k);
    }
  const TriangleBvh bvh(g.tri);
  std::optional<Progress> progress;
  if (show_progress) progress.emplace("distance field: exact boundary", std::int64_t(boundary.size()));
  tbb::parallel_for(std::size_t(0), boundary.size(), std::size_t(1024), [&](std::size_t b) {
    const std::size_t e = std::min(b + 1024, boundary.size());
    for (std::size_t n = b; n < e; ++n) {
      const std::int64_t idx = boundary[n];
      const int k = int(idx / sz), j = int((idx % sz) / sy), i = int(idx % sy);
      const double p[3] = {ox + h * i, oy + h * j, oz + h * k};
      std::int32_t t = closest[idx];
      const double dd = bvh.ClosestSquared(p, double(d2[idx]), &t);
      if (dd < d2[idx]) {
        d2[idx] = float(dd);
        closest[idx] = t;
      }
    }
    if (progress) progress->Advance(std::int64_t(e - b));
  });
  if (progress) progress->Finish();
}

}  // namespace

UnsignedDistanceGrid ComputeUnsignedDistance(const TriangleMesh& mesh, const FieldGrid& grid,
                                             int band_voxels, bool show_progress) {
  const int nx = grid.dims.x(), ny = grid.dims.y(), nz = grid.dims.z();
  const std::vector<double> tri = FlattenTriangles(mesh);
  UnsignedDistanceGrid out;
  std::vector<float> d2(grid.num_points(), std::numeric_limits<float>::infinity());
  out.closest_triangle.assign(grid.num_points(), -1);
  DistanceSamples samples{nx, ny, nz, nx, std::int64_t(nx) * ny, grid.spacing, grid.origin.x(), grid.origin.y(),
                          grid.origin.z(), tri, d2, out.closest_triangle};

  // Exact in the band around each triangle, z-slabs of two planes in parallel.
  const int slab = 2;
  const std::vector<std::array<int, 6>> boxes = BandBoxes(tri, mesh.num_triangles(), grid, band_voxels * grid.spacing);
  const SlabBuckets slabs = BucketBySlab(boxes, (nz + slab - 1) / slab, slab);
  FillExactBand(samples, boxes, slabs, slab, show_progress);
  // Propagated beyond it, exact again on the boundary faces.
  PropagateClosest(samples, /*rounds=*/3, show_progress);
  FillExactBoundary(samples, show_progress);

  // Distances from their squares.
  out.distance.resize(d2.size());
  tbb::parallel_for(std::int64_t(0), std::int64_t(d2.size()), std::int64_t(1 << 16), [&](std::int64_t b) {
    const std::int64_t e = std::min<std::int64_t>(b + (1 << 16), d2.size());
    for (std::int64_t n = b; n < e; ++n) out.distance[n] = std::sqrt(d2[n]);
  });
  return out;
}

}  // namespace contactlab
