// Welding of vertices at exactly the same position: STL readers use it to recover shared
// vertices, and validation (geometry/mesh_validation.h) analyses edges on the welded mesh.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "geometry/triangle_mesh.h"

namespace contactlab {

// For each vertex i of P (#P positions, finite), the smallest index j with P[j] == P[i]
// exactly (+0 and -0 are equal); rep[i] == i for the first vertex at each position.
// O(#P log #P).
std::vector<int> FindExactDuplicateVertices(const std::vector<Eigen::Vector3d>& p);

// MESH with vertices at exactly equal positions merged into one (the first), unreferenced
// vertices kept, triangle indices remapped; vertex order otherwise preserved.
TriangleMesh WeldExactDuplicateVertices(const TriangleMesh& mesh);

}  // namespace contactlab
