// Pointshell files and validation (Barbič & James 2008, sec. 2.4).
#include "pointshell/pointshell_io.h"

#include <cmath>

#include "pointshell/point_tree.h"
#include "util/binary_io.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr char kMagic[] = "CLPS";
constexpr std::uint32_t kVersion = 1;

}  // namespace

void ValidatePointshell(const Pointshell& s, const std::string& where) {
  const std::size_t np = s.x.size();
  if (np == 0) Fail(where, "the pointshell has no points");
  if (np > std::size_t(INT32_MAX)) Fail(where, "too many points");
  if (s.y.size() != np || s.z.size() != np || s.nx.size() != np || s.ny.size() != np || s.nz.size() != np) {
    Fail(where, "position and normal arrays differ in length");
  }
  for (std::size_t i = 0; i < np; ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || !std::isfinite(s.z[i])) {
      Fail(where, "point " + std::to_string(i) + " is not finite");
    }
    const double len = std::sqrt(double(s.nx[i]) * s.nx[i] + double(s.ny[i]) * s.ny[i] + double(s.nz[i]) * s.nz[i]);
    if (!(std::abs(len - 1) <= 1e-3)) Fail(where, "normal " + std::to_string(i) + " is not a unit vector");
  }
  // Levels.
  const int levels = s.num_levels();
  if (levels < 1) Fail(where, "the pointshell has no levels");
  for (int i = 0; i < levels; ++i) {
    const std::int32_t lo = i == 0 ? 0 : s.level_point_end[i - 1];
    if (s.level_point_end[i] <= lo) Fail(where, "level point counts are not strictly increasing at level " + std::to_string(i));
  }
  if (std::size_t(s.level_point_end.back()) != np) Fail(where, "the last level does not hold every point");
  if (s.level_node_begin.size() != std::size_t(levels) + 1 || s.level_node_begin[0] != 0) {
    Fail(where, "level node ranges have the wrong length or do not start at 0");
  }
  for (int i = 0; i < levels; ++i) {
    if (std::int64_t(s.level_node_begin[i + 1]) - s.level_node_begin[i] != s.level_point_end[i]) {
      Fail(where, "level " + std::to_string(i) + " node count differs from its point count");
    }
  }
  const std::size_t nn = std::size_t(s.level_node_begin[levels]);
  if (s.node_point.size() != nn || s.node_radius.size() != nn || s.node_parent.size() != nn ||
      s.child_begin.size() != nn + 1) {
    Fail(where, "node arrays differ in length from the level node ranges");
  }
  // Nodes, level by level.
  std::vector<int> seen(np, -1);
  for (int i = 0; i < levels; ++i) {
    const std::int32_t b = s.level_node_begin[i], e = s.level_node_begin[i + 1];
    for (std::int32_t n = b; n < e; ++n) {
      const std::string node = "node " + std::to_string(n) + " (level " + std::to_string(i) + ")";
      const std::int32_t p = s.node_point[n];
      if (p < 0 || p >= s.level_point_end[i]) Fail(where, node + ": point index out of range");
      if (seen[p] == i) Fail(where, node + ": point " + std::to_string(p) + " appears twice on the level");
      seen[p] = i;
      const std::int32_t parent = s.node_parent[n];
      if (i == 0) {
        if (parent != -1) Fail(where, node + ": a level-0 node has a parent");
      } else {
        if (parent < s.level_node_begin[i - 1] || parent >= b) Fail(where, node + ": parent not on the previous level");
        if (n < s.child_begin[parent] || n >= s.child_begin[parent + 1]) {
          Fail(where, node + ": not inside its parent's child range");
        }
      }
      const std::int32_t cb = s.child_begin[n], ce = s.child_begin[n + 1];
      const std::int32_t next_b = i + 1 < levels ? s.level_node_begin[i + 1] : std::int32_t(nn);
      const std::int32_t next_e = i + 1 < levels ? s.level_node_begin[i + 2] : std::int32_t(nn);
      if (cb > ce || cb < next_b || ce > next_e) Fail(where, node + ": child range is invalid");
      const float r = s.node_radius[n];
      if (!std::isfinite(r) || r < 0) Fail(where, node + ": radius is negative or not finite");
      if (i + 1 == levels && r != 0) Fail(where, node + ": a leaf has a non-zero radius");
    }
  }
  if (s.child_begin[nn] != std::int32_t(nn)) Fail(where, "the child range sentinel is wrong");
  if (const std::int32_t n = NodeWithoutOwnFirstChild(s); n >= 0) {
    Fail(where, "node " + std::to_string(n) + ": its first child is not its own point one level down");
  }
}

void SavePointshell(const Pointshell& s, const std::filesystem::path& path) {
  ValidatePointshell(s, path.string());
  BinaryWriter w;
  w.PutString(s.method);
  w.PutString(s.source);
  w.Put<double>(s.offset);
  w.Put<std::uint64_t>(s.seed);
  w.PutArray(s.x);
  w.PutArray(s.y);
  w.PutArray(s.z);
  w.PutArray(s.nx);
  w.PutArray(s.ny);
  w.PutArray(s.nz);
  w.PutArray(s.level_point_end);
  w.PutArray(s.level_node_begin);
  w.PutArray(s.node_point);
  w.PutArray(s.node_radius);
  w.PutArray(s.child_begin);
  w.PutArray(s.node_parent);
  w.Save(path, kMagic, kVersion);
}

Pointshell LoadPointshell(const std::filesystem::path& path) {
  BinaryReader r(path, kMagic, kVersion);
  Pointshell s;
  s.method = r.GetString("method");
  s.source = r.GetString("source");
  s.offset = r.Get<double>("offset");
  s.seed = r.Get<std::uint64_t>("seed");
  s.x = r.GetArray<float>("x");
  s.y = r.GetArray<float>("y");
  s.z = r.GetArray<float>("z");
  s.nx = r.GetArray<float>("nx");
  s.ny = r.GetArray<float>("ny");
  s.nz = r.GetArray<float>("nz");
  s.level_point_end = r.GetArray<std::int32_t>("level_point_end");
  s.level_node_begin = r.GetArray<std::int32_t>("level_node_begin");
  s.node_point = r.GetArray<std::int32_t>("node_point");
  s.node_radius = r.GetArray<float>("node_radius");
  s.child_begin = r.GetArray<std::int32_t>("child_begin");
  s.node_parent = r.GetArray<std::int32_t>("node_parent");
  r.ExpectEnd();
  if (!std::isfinite(s.offset)) r.Corrupt("offset is not finite");
  ValidatePointshell(s, path.string());
  return s;
}

}  // namespace contactlab
