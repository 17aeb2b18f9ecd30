// The nested multiresolution pointshell (Barbič & James 2008, sec. 2.2 and 2.4): points with
// inward unit normals on an offset surface of the body, organised as a tree whose level L_i
// holds an instance of every point of repulsion levels 0..i (the paper numbers them from 1).
//
// Storage is flat (structure of arrays, index-based children) so a breadth-first traversal
// allocates nothing. Points are ordered by repulsion level, so the points of tree level i
// are exactly the prefix [0, level_point_end[i]) of the point arrays, and a "linear
// traversal of level i" walks that prefix.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace contactlab {

struct Pointshell {
  // --- Points (#P), body frame, metres; sorted by repulsion level.
  std::vector<float> x, y, z;     // (#P) positions
  std::vector<float> nx, ny, nz;  // (#P) inward unit normals
  std::vector<std::int32_t> level_point_end;  // (#levels) points of tree levels 0..i: [0, end[i])

  // --- Tree nodes (#N = sum over levels of level_point_end[i]). Nodes of tree level i are
  // [level_node_begin[i], level_node_begin[i+1]); within a level they are ordered by parent,
  // so each node's children are contiguous in the next level.
  std::vector<std::int32_t> level_node_begin;  // (#levels + 1)
  std::vector<std::int32_t> node_point;        // (#N) index of the node's point
  std::vector<float> node_radius;              // (#N) bounding radius of the subtree (0 at leaves)
  std::vector<std::int32_t> child_begin;       // (#N + 1) children of n: [child_begin[n], child_begin[n+1])
  std::vector<std::int32_t> node_parent;       // (#N) parent node, -1 on level 0

  // --- How it was made.
  std::string method;        // "repulsion", "voxel", "vertices", "random"
  std::string source;        // mesh or field it was made from
  double offset = 0;         // level-set offset delta (metres) the points sit on
  std::uint64_t seed = 0;

  int num_points() const { return static_cast<int>(x.size()); }
  int num_levels() const { return static_cast<int>(level_point_end.size()); }
  int num_nodes() const { return static_cast<int>(node_point.size()); }
  int points_in_level(int level) const { return level_point_end[level]; }
  // Bytes of the arrays above: positions and normals per point, the level table, and per node
  // its point, radius, children range and parent (the description strings not counted).
  std::int64_t memory_bytes() const {
    auto bytes = [](const auto& v) { return std::int64_t(v.size() * sizeof(v[0])); };
    return bytes(x) + bytes(y) + bytes(z) + bytes(nx) + bytes(ny) + bytes(nz) + bytes(level_point_end) +
           bytes(level_node_begin) + bytes(node_point) + bytes(node_radius) + bytes(child_begin) + bytes(node_parent);
  }
};

}  // namespace contactlab
