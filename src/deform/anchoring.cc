// Fixed vertices of anchored reduced deformable models (Barbič & James 2008, sec. 4).
#include "deform/anchoring.h"

#include <sstream>

#include "util/error.h"

namespace contactlab {

Anchoring Anchoring::BelowY(double y) { return BelowPlane(Eigen::Vector3d::UnitY(), y); }

Anchoring Anchoring::BelowPlane(const Eigen::Vector3d& normal, double offset) {
  Anchoring a;
  a.kind = Kind::kBelowPlane;
  a.normal = normal;
  a.offset = offset;
  return a;
}

Anchoring Anchoring::InBox(const Aabb& box) {
  Anchoring a;
  a.kind = Kind::kInBox;
  a.box = box;
  return a;
}

Anchoring Anchoring::OutsideBox(const Aabb& box) {
  Anchoring a = InBox(box);
  a.kind = Kind::kOutsideBox;
  return a;
}

std::string Anchoring::Describe() const {
  std::ostringstream s;
  switch (kind) {
    case Kind::kFree: s << "free"; break;
    case Kind::kBelowPlane:
      s << "fixed where n.p <= c, n = (" << normal.x() << ", " << normal.y() << ", " << normal.z()
        << "), c = " << offset;
      break;
    case Kind::kInBox:
      s << "fixed inside box [" << box.min.transpose() << "] .. [" << box.max.transpose() << "]";
      break;
    case Kind::kOutsideBox:
      s << "fixed outside box [" << box.min.transpose() << "] .. [" << box.max.transpose() << "]";
      break;
  }
  return s.str();
}

std::vector<std::uint8_t> FindFixedVertices(const TetMesh& mesh, const Anchoring& anchoring,
                                            const std::string& where) {
  std::vector<std::uint8_t> fixed(mesh.vertices.size(), 0);
  if (!anchoring.anchored()) return fixed;
  const std::string where_given = anchoring.source.empty() ? where : anchoring.source + " (" + where + ")";
  if (anchoring.kind == Anchoring::Kind::kBelowPlane && !(anchoring.normal.norm() > 0)) {
    Fail(where_given, "the anchoring plane normal is zero");
  }
  int count = 0;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Eigen::Vector3d& p = mesh.vertices[i];
    bool f = false;
    switch (anchoring.kind) {
      case Anchoring::Kind::kFree: break;
      case Anchoring::Kind::kBelowPlane: f = anchoring.normal.dot(p) <= anchoring.offset; break;
      case Anchoring::Kind::kInBox: f = anchoring.box.Contains(p); break;
      case Anchoring::Kind::kOutsideBox: f = !anchoring.box.Contains(p); break;
    }
    fixed[i] = f ? 1 : 0;
    count += f;
  }
  if (count == 0) {
    const Aabb b = mesh.Bounds();
    std::ostringstream s;
    s << "no vertex of the simulation mesh is anchored (" << anchoring.Describe()
      << "; mesh box [" << b.min.transpose() << "] .. [" << b.max.transpose() << "])";
    Fail(where_given, s.str());
  }
  if (count == mesh.num_vertices()) Fail(where_given, "every vertex is anchored (" + anchoring.Describe() + "); nothing can move");
  return fixed;
}

}  // namespace contactlab
