// Nested multiresolution pointshells by particle repulsion and by the alternative samplings
// (Barbič & James 2008, sec. 2.2 and 2.4).
#include "pointshell/build_pointshell.h"

#include "util/isolated_parallel.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "pointshell/level_set_sampling.h"
#include "pointshell/point_tree.h"
#include "pointshell/random_stream.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Deterministic Fisher-Yates shuffle from SEED.
void Shuffle(std::vector<Eigen::Vector3d>* points, std::uint64_t seed) {
  RandomStream rng(seed, 0x5eed5eedull);
  for (std::size_t i = points->size(); i > 1; --i) {
    const std::size_t j = std::size_t(rng.Next() % i);
    std::swap((*points)[i - 1], (*points)[j]);
  }
}

// VPS-style points: centres of the voxels (side V, grid from the field box's lower corner)
// whose eight corner values bracket DELTA.
// Spreads the low 10 bits of V to every third bit (for a 30-bit Morton code).
std::uint32_t SpreadBits(std::uint32_t v) {
  v &= 0x3ffu;
  v = (v | (v << 16)) & 0x030000ffu;
  v = (v | (v << 8)) & 0x0300f00fu;
  v = (v | (v << 4)) & 0x030c30c3u;
  v = (v | (v << 2)) & 0x09249249u;
  return v;
}

// Orders the points of each level band [ends[i-1], ends[i]) along a Morton curve over the
// field box, so a traversal that walks a level in order touches nearby field cells one after
// another (cache locality in the haptic cycle). Levels keep their points; only the order
// within a band changes, so nesting and determinism are unaffected.
void SortLevelsAlongMortonCurve(std::vector<Eigen::Vector3d>* points, const std::vector<std::int32_t>& ends,
                                const DistanceField& field) {
  const Aabb box = field.box();
  const Eigen::Vector3d scale = Eigen::Vector3d::Constant(1023.0).cwiseQuotient(box.size().cwiseMax(1e-300));
  std::vector<std::pair<std::uint32_t, std::int32_t>> keys;
  std::int32_t begin = 0;
  for (const std::int32_t end : ends) {
    keys.clear();
    for (std::int32_t i = begin; i < end; ++i) {
      const Eigen::Vector3d q = ((*points)[i] - box.min).cwiseProduct(scale).cwiseMax(0.0).cwiseMin(1023.0);
      const std::uint32_t code =
          SpreadBits(std::uint32_t(q.x())) | (SpreadBits(std::uint32_t(q.y())) << 1) | (SpreadBits(std::uint32_t(q.z())) << 2);
      keys.emplace_back(code, i);
    }
    std::sort(keys.begin(), keys.end());
    std::vector<Eigen::Vector3d> band;
    band.reserve(keys.size());
    for (const auto& [code, i] : keys) band.push_back((*points)[i]);
    std::copy(band.begin(), band.end(), points->begin() + begin);
    begin = end;
  }
}

std::vector<Eigen::Vector3d> VoxelCentres(const DistanceField& field, double delta, double v) {
  const Aabb box = field.box();
  const Eigen::Vector3i n = (box.size() / v).array().floor().cast<int>().max(1);
  std::vector<std::vector<Eigen::Vector3d>> slabs(n.z());
  tbb::parallel_for(0, n.z(), [&](int k) {
    const int cx = n.x() + 1, cy = n.y() + 1;
    std::vector<float> corner(std::size_t(cx) * cy * 2);
    for (int dk = 0; dk < 2; ++dk)
      for (int j = 0; j < cy; ++j)
        for (int i = 0; i < cx; ++i) {
          const Eigen::Vector3d q = box.min + v * Eigen::Vector3d(i, j, k + dk);
          corner[i + std::size_t(cx) * (j + std::size_t(cy) * dk)] = float(field.Distance(q));
        }
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        float lo = INFINITY, hi = -INFINITY;
        for (int c = 0; c < 8; ++c) {
          const float d = corner[(i + (c & 1)) + std::size_t(cx) * ((j + ((c >> 1) & 1)) + std::size_t(cy) * (c >> 2))];
          lo = std::min(lo, d);
          hi = std::max(hi, d);
        }
        if (lo <= delta && delta <= hi && lo < hi) {
          slabs[k].push_back(box.min + v * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5));
        }
      }
  });
  std::vector<Eigen::Vector3d> points;
  for (const auto& slab : slabs) points.insert(points.end(), slab.begin(), slab.end());
  return points;
}

// Unique mesh vertices used by triangles, projected onto the level set (failures dropped).
std::vector<Eigen::Vector3d> ProjectedVertices(const DistanceField& field, double delta, const TriangleMesh& mesh) {
  std::vector<Eigen::Vector3d> used;
  used.reserve(std::size_t(mesh.num_triangles()) * 3);
  for (const auto& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) used.push_back(mesh.vertices[t[c]]);
  auto less = [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::sort(used.begin(), used.end(), less);
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::vector<char> ok(used.size(), 0);
  const double tolerance = LevelSetTolerance(field);
  tbb::parallel_for(std::size_t(0), used.size(), [&](std::size_t i) {
    ok[i] = ProjectOntoLevelSet(field, delta, tolerance, 30, &used[i], nullptr) ? 1 : 0;
  });
  std::vector<Eigen::Vector3d> points;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (ok[i]) points.push_back(used[i]);
  return points;
}

}  // namespace

namespace {

// N as an integer when it fits, else "%.3g" (100 levels need 4^99 points: no overflowed integer).
std::string NeededPoints(double n) {
  if (n < 9e15) return std::to_string(std::int64_t(std::llround(n)));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", n);
  return buf;
}

}  // namespace

std::vector<std::int32_t> NestedLevelEnds(std::int32_t num_points, int num_levels, int branching,
                                          const std::string& where) {
  if (num_points < 1) Fail(where, "the number of points must be at least 1 (got " + std::to_string(num_points) + ")");
  if (num_levels < 1) Fail(where, "the number of levels must be at least 1 (got " + std::to_string(num_levels) + ")");
  if (branching < 2) Fail(where, "the branching factor must be at least 2 (got " + std::to_string(branching) + ")");
  std::vector<std::int32_t> ends(num_levels);
  double divisor = 1;
  for (int i = num_levels - 1; i >= 0; --i) {
    ends[i] = std::int32_t(std::floor(double(num_points) / divisor));
    divisor *= branching;
  }
  if (ends[0] < 1) {
    Fail(where, std::to_string(num_points) + " points cannot fill " + std::to_string(num_levels) +
                    " levels with branching factor " + std::to_string(branching) + ": level 0 would be empty (need at least " +
                    NeededPoints(divisor / branching) + " points, or fewer levels)");
  }
  return ends;
}

namespace {

Pointshell BuildPointshellImpl(const DistanceField& field, const PointshellOptions& options, const TriangleMesh* mesh,
                           PointshellBuildReport* report) {
  const auto start = std::chrono::steady_clock::now();
  const std::string where =
      "pointshell of " + (field.info().source.empty() ? std::string("distance field") : field.info().source);
  const double delta = options.offset.value_or(DefaultPointshellOffset(field));
  if (options.method == PointshellMethod::kVertices && mesh == nullptr) {
    Fail(where, "the vertices method needs the triangle mesh");
  }
  if (options.method != PointshellMethod::kVoxel) {
    NestedLevelEnds(options.num_points, options.num_levels, options.branching, where);  // checks counts
  }
  const LevelSetCells cells = FindLevelSetCells(field, delta, where);  // checks the offset
  PointshellBuildReport local_report;
  PointshellBuildReport& rep = report ? *report : local_report;
  rep = {};
  rep.area = cells.area();

  std::vector<Eigen::Vector3d> positions;
  std::vector<std::int32_t> ends;
  switch (options.method) {
    case PointshellMethod::kRepulsion: {
      // Level by level: inject random points, relax only them (earlier levels frozen).
      ends = NestedLevelEnds(options.num_points, options.num_levels, options.branching, where);
      std::unique_ptr<Progress> progress;
      if (options.show_progress) {
        progress = std::make_unique<Progress>("pointshell repulsion",
                                              std::int64_t(options.num_levels) * options.repulsion.max_iterations);
      }
      for (int i = 0; i < options.num_levels; ++i) {
        const std::int32_t lo = i == 0 ? 0 : ends[i - 1];
        positions.resize(ends[i]);
        SampleLevelSet(field, cells, options.seed, lo, ends[i] - lo, positions.data() + lo, where);
        const double spacing = std::sqrt(rep.area / ends[i]);
        rep.levels.push_back(
            RepelOnLevelSet(field, delta, spacing, options.repulsion, lo, &positions, progress.get()));
      }
      break;
    }
    case PointshellMethod::kRandom: {
      // Independent samples: any prefix is itself a random subset.
      ends = NestedLevelEnds(options.num_points, options.num_levels, options.branching, where);
      positions.resize(options.num_points);
      SampleLevelSet(field, cells, options.seed, 0, options.num_points, positions.data(), where);
      break;
    }
    case PointshellMethod::kVoxel: {
      double side = options.voxel_size;
      if (!(side > 0)) {
        if (options.num_points < 1) Fail(where, "the number of points must be at least 1");
        side = std::sqrt(1.5 * rep.area / options.num_points);
      }
      positions = VoxelCentres(field, delta, side);
      if (positions.empty()) Fail(where, "no voxel of side " + std::to_string(side) + " m crosses the level set");
      Shuffle(&positions, options.seed);
      ends = NestedLevelEnds(std::int32_t(positions.size()), options.num_levels, options.branching, where);
      break;
    }
    case PointshellMethod::kVertices: {
      positions = ProjectedVertices(field, delta, *mesh);
      if (positions.empty()) Fail(where, "no vertex of " + mesh->name + " could be projected onto the level set");
      Shuffle(&positions, options.seed);
      if (std::int32_t(positions.size()) > options.num_points) positions.resize(options.num_points);
      ends = NestedLevelEnds(std::int32_t(positions.size()), options.num_levels, options.branching, where);
      break;
    }
  }

  SortLevelsAlongMortonCurve(&positions, ends, field);

  // Float positions, inward normals from the field gradient at the stored positions.
  Pointshell shell;
  const std::int32_t n = std::int32_t(positions.size());
  shell.x.resize(n);
  shell.y.resize(n);
  shell.z.resize(n);
  shell.nx.resize(n);
  shell.ny.resize(n);
  shell.nz.resize(n);
  std::atomic<bool> zero_gradient{false};
  tbb::parallel_for(std::int32_t(0), n, [&](std::int32_t i) {
    // The normal is evaluated at the stored float position (the gradient may jump across
    // grid cell faces, so a one-ulp difference can matter there).
    shell.x[i] = float(positions[i].x());
    shell.y[i] = float(positions[i].y());
    shell.z[i] = float(positions[i].z());
    const Eigen::Vector3d stored(double(shell.x[i]), double(shell.y[i]), double(shell.z[i]));
    Eigen::Vector3d g;
    field.DistanceAndGradient(stored, &g);
    const double len = g.norm();
    if (!(len > 0)) {
      zero_gradient = true;
      return;
    }
    const Eigen::Vector3f nrm = (-g / len).cast<float>();
    shell.nx[i] = nrm.x();
    shell.ny[i] = nrm.y();
    shell.nz[i] = nrm.z();
  });
  if (zero_gradient) Fail(where, "the field gradient vanishes at a pointshell point: no normal can be set");
  shell.level_point_end = ends;
  shell.method = PointshellMethodName(options.method);
  shell.source = field.info().source;
  shell.offset = delta;
  shell.seed = options.seed;
  BuildPointTree(&shell);
  rep.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return shell;
}

}  // namespace

Pointshell BuildPointshell(const DistanceField& field, const PointshellOptions& options, const TriangleMesh* mesh,
                           PointshellBuildReport* report) {
  return RunIsolatedFromCancellation([&] { return BuildPointshellImpl(field, options, mesh, report); });
}


PointshellMethod ParsePointshellMethod(const std::string& text, const std::string& where) {
  if (text == "repulsion") return PointshellMethod::kRepulsion;
  if (text == "voxel") return PointshellMethod::kVoxel;
  if (text == "vertices") return PointshellMethod::kVertices;
  if (text == "random") return PointshellMethod::kRandom;
  Fail(where, "unknown pointshell method \"" + text + "\" (expected repulsion, voxel, vertices or random)");
}

std::string PointshellMethodName(PointshellMethod method) {
  switch (method) {
    case PointshellMethod::kRepulsion: return "repulsion";
    case PointshellMethod::kVoxel: return "voxel";
    case PointshellMethod::kVertices: return "vertices";
    case PointshellMethod::kRandom: return "random";
  }
  return "unknown";
}

}  // namespace contactlab
