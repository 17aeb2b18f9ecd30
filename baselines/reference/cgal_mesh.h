// Internal to the CGAL references (baselines/reference): our TriangleMesh as a CGAL
// Surface_mesh over the exact-predicates, inexact-constructions kernel. Include only from .cc
// files of contactlab_reference (it pulls in CGAL, GPL-3.0-or-later).
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <string>

#include "geometry/pose.h"
#include "geometry/triangle_mesh.h"

namespace contactlab::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

// MESH (body frame) as a Surface_mesh, the soup made a polygon mesh (non-manifold vertices
// duplicated) and, when closed, oriented to bound a volume. Throws Error naming WHERE and the
// mesh when it is empty or (REQUIRE_CLOSED) not closed.
Mesh ToSurfaceMesh(const TriangleMesh& mesh, const std::string& where, bool require_closed);

// A copy of MESH with every vertex mapped by X.
Mesh Transformed(const Mesh& mesh, const Pose& X);

}  // namespace contactlab::cgal
