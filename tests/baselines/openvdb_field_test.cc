// Our dense field builder (src/sdf/build_distance_field.h) against an independent one,
// OpenVDB's meshToSignedDistanceField (baselines/reference/openvdb_field.h), in the narrow band
// where both are exact distances: same values and the same sign convention (negative inside).
#include "baselines/reference/openvdb_field.h"

#include <gtest/gtest.h>

#include <vector>

#include "geometry/procedural_shapes.h"
#include "sdf/build_distance_field.h"

namespace contactlab {
namespace {

DistanceField DenseField(const TriangleMesh& mesh, int resolution) {
  DistanceFieldOptions o;
  o.resolution = resolution;
  o.mode = FieldMode::kClosed;
  o.show_progress = false;
  return BuildDistanceField(mesh, o);
}

std::vector<TriangleMesh> Meshes() {
  return {MakeSphere(1.0 / 3, 4), MakeTorus(0.3, 0.1), MakeBox(Eigen::Vector3d(0.3, 0.1, 0.7) / 3)};
}

// Convex, non-convex and flat-sided closed meshes, sizes not exact in binary, 48 cells, at
// OpenVDB's active voxels (the whole ±3-voxel band lies inside the padded box). Measured: max
// 0.16 voxel, RMS <= 0.01, all of it OpenVDB's (its outer band layers come from neighbours'
// closest triangles; our samples there are exact distances).
TEST(OpenVdbReference, DenseFieldMatchesOpenVdbInTheNarrowBandAtTheSameResolution) {
  for (const TriangleMesh& mesh : Meshes()) {
    SCOPED_TRACE(mesh.name);
    const DistanceField dense = DenseField(mesh, 48);
    const openvdb::FloatGrid::Ptr vdb = BuildOpenVdbField(mesh, dense.origin(), dense.spacing());
    const FieldDifference d = CompareWithOpenVdb(dense, *vdb);
    EXPECT_GT(d.compared, 10000);
    EXPECT_EQ(d.compared, std::int64_t(vdb->activeVoxelCount()));
    EXPECT_LT(d.max_voxels, 0.25);
    EXPECT_LT(d.rms_voxels, 0.02);
    EXPECT_EQ(d.sign_disagreements, 0);
  }
}

// A twice finer OpenVDB grid against the dense interpolant: the difference is the trilinear
// interpolation error (largest at the box's edges), within one fine voxel. Measured: max 0.57.
TEST(OpenVdbReference, DenseInterpolantMatchesATwiceFinerOpenVdbFieldWithinOneVoxel) {
  for (const TriangleMesh& mesh : Meshes()) {
    SCOPED_TRACE(mesh.name);
    const DistanceField dense = DenseField(mesh, 48);
    const openvdb::FloatGrid::Ptr vdb = BuildOpenVdbField(mesh, dense.origin(), dense.spacing() / 2);
    const FieldDifference d = CompareWithOpenVdb(dense, *vdb);
    EXPECT_GT(d.compared, 40000);
    EXPECT_LT(d.max_voxels, 1.0);
    EXPECT_LT(d.rms_voxels, 0.15);
    EXPECT_EQ(d.sign_disagreements, 0);
  }
}

}  // namespace
}  // namespace contactlab
