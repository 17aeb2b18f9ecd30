// Which vertices of a simulation mesh are fixed (Barbič & James 2008, sec. 4: anchored reduced
// deformable models such as the bridge of Fig. 2), or none for a free-flying body.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "deform/tet_mesh.h"
#include "geometry/aabb.h"

namespace contactlab {

struct Anchoring {
  enum class Kind { kFree, kBelowPlane, kInBox, kOutsideBox };
  Kind kind = Kind::kFree;
  // kBelowPlane: vertices with normal . p <= offset are fixed (e.g. normal (0,1,0): y <= c).
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();
  double offset = 0;
  Aabb box;  // kInBox: vertices inside BOX are fixed; kOutsideBox: those outside (a bridge's ends)
  // Where it was given ("scene.yaml:14: bodies[0].deformable.anchor"), for errors; empty when it
  // was not read from a file. Not part of what it anchors (neither hashed nor saved).
  std::string source;

  static Anchoring Free() { return {}; }
  static Anchoring BelowY(double y);
  static Anchoring BelowPlane(const Eigen::Vector3d& normal, double offset);
  static Anchoring InBox(const Aabb& box);
  static Anchoring OutsideBox(const Aabb& box);
  bool anchored() const { return kind != Kind::kFree; }
  // "free", "below plane n=(...) c=...", "in box [...]".
  std::string Describe() const;
};

// Per-vertex flags (1 = fixed) of MESH. Throws Error (naming ANCHORING.source, the file and line
// it was given at, and WHERE) when anchoring is asked for and no vertex is fixed, or when every
// vertex is fixed.
std::vector<std::uint8_t> FindFixedVertices(const TetMesh& mesh, const Anchoring& anchoring,
                                            const std::string& where = "anchoring");

}  // namespace contactlab
