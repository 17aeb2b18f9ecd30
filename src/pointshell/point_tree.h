// The nested point tree of a multiresolution pointshell (Barbič & James 2008, sec. 2.4, Fig.
// 6): tree level L_i holds an instance of every point of repulsion levels 0..i; each node of
// L_{i+1} has as parent the nearest node of L_i (a point's own earlier instance for points
// already in L_i); every non-leaf node gets a bounding-sphere radius covering its subtree.
#pragma once

#include "pointshell/pointshell.h"

namespace contactlab {

// Fills the tree fields of SHELL (level_node_begin, node_point, node_radius, child_begin,
// node_parent) from its positions x, y, z and level_point_end, replacing any previous tree.
// Within each level nodes are ordered by (parent node, point index), so children are
// contiguous. Each radius is the exact largest distance from the node's point to the points
// of its subtree's leaves (which include the positions of every descendant, since each
// point's instance chain reaches the deepest level), rounded up to float; leaves get 0.
// Parents use nanoflann nearest-point search, in parallel, deterministic.
// Precondition: level_point_end strictly increasing, ending at num_points() (Error otherwise).
void BuildPointTree(Pointshell* shell);

// The first node above the deepest level whose first child is not its own point one level
// down, or -1 when there is none (as BuildPointTree makes every tree). The breadth-first
// traversal relies on it: a first child inherits its parent's distance.
std::int32_t NodeWithoutOwnFirstChild(const Pointshell& shell);

}  // namespace contactlab
