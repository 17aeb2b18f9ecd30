#include "geometry/procedural_shapes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

#include "util/error.h"

namespace contactlab {
namespace {

constexpr double kPi = std::numbers::pi;

// Every directed edge appears once and its reverse once: closed, manifold, consistently oriented.
void ExpectClosedOriented(const TriangleMesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) directed[{t[k], t[(k + 1) % 3]}]++;
  }
  for (const auto& [e, n] : directed) {
    EXPECT_EQ(n, 1) << m.name << " edge " << e.first << "-" << e.second << " repeated";
    EXPECT_EQ(directed.count({e.second, e.first}), 1u) << m.name << " boundary edge";
  }
}

TEST(ProceduralShapes, SphereIsClosedAndItsVolumeConverges) {
  const double r = 1.0 / 3.0;
  const TriangleMesh m = MakeSphere(r, 5);
  ExpectClosedOriented(m);
  EXPECT_EQ(m.num_triangles(), 20 * 1024);
  const double exact = 4.0 / 3.0 * kPi * r * r * r;
  EXPECT_LT(m.SignedVolume(), exact);  // inscribed polyhedron
  EXPECT_NEAR(m.SignedVolume(), exact, 1e-3 * exact);
  for (const auto& v : m.vertices) EXPECT_NEAR(v.norm(), r, 1e-12);
}

TEST(ProceduralShapes, BoxVolumeIsExact) {
  const Eigen::Vector3d half(0.1, 0.2, 0.3);
  for (int cuts : {1, 3}) {
    const TriangleMesh m = MakeBox(half, cuts);
    ExpectClosedOriented(m);
    EXPECT_NEAR(m.SignedVolume(), 8 * half.prod(), 1e-12);
  }
}

// The bounding radius about the body origin is reached at the corner farthest from it: for a box
// of half-extents h shifted by t, |(|t_x| + h_x, |t_y| + h_y, |t_z| + h_z)|.
TEST(ProceduralShapes, MaxVertexRadiusIsTheFarthestCornerFromTheOrigin) {
  const Eigen::Vector3d half(0.1, 1.0 / 3.0, 0.3);
  TriangleMesh m = MakeBox(half, 3);
  EXPECT_NEAR(m.MaxVertexRadius(), half.norm(), 1e-15);
  const Eigen::Vector3d t(-0.25, 0.05, 0.7);
  m.Transform(1.0, Eigen::Matrix3d::Identity(), t);
  EXPECT_NEAR(m.MaxVertexRadius(), (t.cwiseAbs() + half).norm(), 1e-12);
  EXPECT_NEAR(MakeSphere(0.02, 3).MaxVertexRadius(), 0.02, 1e-15);
  EXPECT_EQ(TriangleMesh{}.MaxVertexRadius(), 0.0);
}

TEST(ProceduralShapes, TorusVolumeConverges) {
  const TriangleMesh m = MakeTorus(0.3, 0.1, 128, 64);
  ExpectClosedOriented(m);
  EXPECT_NEAR(m.SignedVolume(), 2 * kPi * kPi * 0.3 * 0.1 * 0.1, 0.01 * 2 * kPi * kPi * 0.003);
}

TEST(ProceduralShapes, CapsuleVolumeConverges) {
  const double r = 0.05, h = 0.1;
  const TriangleMesh m = MakeCapsule(r, h, 96, 32);
  ExpectClosedOriented(m);
  const double exact = kPi * r * r * 2 * h + 4.0 / 3.0 * kPi * r * r * r;
  EXPECT_NEAR(m.SignedVolume(), exact, 0.01 * exact);
}

TEST(ProceduralShapes, TubeIsClosedWithBothWallsOnTheirCircles) {
  const double ro = 0.006, ri = 0.0055, h = 0.015;
  const TriangleMesh m = MakeTube(ro, ri, h, 256);
  ExpectClosedOriented(m);
  // Inscribed polygons of 256 sides: area factor sin(2 pi/n) n / (2 pi).
  const double polygon = std::sin(2 * kPi / 256) * 256 / (2 * kPi);
  EXPECT_NEAR(m.SignedVolume(), polygon * kPi * (ro * ro - ri * ri) * 2 * h, 1e-12);
  int outer = 0, inner = 0;
  for (const auto& v : m.vertices) {
    const double r = std::hypot(v.x(), v.y());
    if (std::abs(r - ro) < 1e-15) ++outer;
    if (std::abs(r - ri) < 1e-15) ++inner;
    EXPECT_NEAR(std::abs(v.z()), h, 1e-15);
  }
  EXPECT_EQ(outer, 512);
  EXPECT_EQ(inner, 512);
  EXPECT_THROW(MakeTube(0.005, 0.006, h), Error);  // inner wider than outer
}

TEST(ProceduralShapes, BumpyPlateIsClosedWithPositiveVolume) {
  const TriangleMesh m = MakeBumpyPlate(0.2, 0.02, 4, 0.005, 64);
  ExpectClosedOriented(m);
  EXPECT_GT(m.SignedVolume(), 0.2 * 0.2 * 0.02);
  EXPECT_NEAR(m.Bounds().max.z(), 0.005, 1e-4);
}

}  // namespace
}  // namespace contactlab
