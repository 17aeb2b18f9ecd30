// OpenVDB's narrow-band signed distance field aligned with a dense field's grid, and the
// difference between the two.
#include "baselines/reference/openvdb_field.h"

#include <openvdb/tools/MeshToVolume.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "util/error.h"

namespace contactlab {

openvdb::FloatGrid::Ptr BuildOpenVdbField(const TriangleMesh& mesh, const Eigen::Vector3d& origin,
                                          double voxel_size, float band_voxels) {
  const std::string where = mesh.name.empty() ? std::string("mesh") : mesh.name;
  if (mesh.empty()) Fail(where, "has no triangles; cannot build an OpenVDB field");
  if (!(voxel_size > 0) || !(band_voxels > 0)) Fail(where, "OpenVDB voxel size and band must be positive");
  openvdb::initialize();
  // Index (i, j, k) at ORIGIN + h (i, j, k): voxel centres on the dense field's grid points.
  openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(voxel_size);
  xform->postTranslate(openvdb::Vec3d(origin.x(), origin.y(), origin.z()));
  std::vector<openvdb::Vec3s> points;
  points.reserve(mesh.vertices.size());
  for (const Eigen::Vector3d& v : mesh.vertices) points.emplace_back(float(v.x()), float(v.y()), float(v.z()));
  std::vector<openvdb::Vec3I> triangles;
  triangles.reserve(mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) triangles.emplace_back(t.x(), t.y(), t.z());
  return openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(*xform, points, triangles, {}, band_voxels,
                                                                       band_voxels);
}

FieldDifference CompareWithOpenVdb(const DistanceField& field, const openvdb::FloatGrid& grid) {
  const double h = grid.voxelSize()[0];
  FieldDifference d;
  double sum2 = 0;
  for (auto it = grid.cbeginValueOn(); it; ++it) {
    const openvdb::Vec3d p = grid.indexToWorld(it.getCoord());
    const Eigen::Vector3d p_F(p.x(), p.y(), p.z());
    if (!field.Inside(p_F)) continue;
    const double vdb = *it, dense = field.Distance(p_F);
    const double e = std::abs(dense - vdb) / h;
    d.max_voxels = std::max(d.max_voxels, e);
    sum2 += e * e;
    ++d.compared;
    if (std::abs(vdb) >= h && (vdb < 0) != (dense < 0)) ++d.sign_disagreements;
  }
  d.rms_voxels = d.compared > 0 ? std::sqrt(sum2 / double(d.compared)) : 0;
  return d;
}

}  // namespace contactlab
