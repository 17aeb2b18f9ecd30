// OpenVDB's narrow-band signed distance field of a closed mesh (openvdb::tools::
// meshToSignedDistanceField, OpenVDB 10, MPL-2.0) on voxels aligned with a dense field's grid
// points: an independent reference for our field builder (Barbič & James 2008, sec. 2.3) and
// the sparse layout a narrow-band field would take. Not part of the contactlab library.
#pragma once

#include <openvdb/openvdb.h>

#include <Eigen/Core>
#include <cstdint>

#include "geometry/triangle_mesh.h"
#include "sdf/distance_field.h"

namespace contactlab {

// The field of MESH (closed, metres) on the voxels whose centre (i, j, k) sits at
// ORIGIN + VOXEL_SIZE * (i, j, k), active within BAND_VOXELS voxels on each side of the
// surface (inactive: +-BAND_VOXELS * VOXEL_SIZE). Negative inside, world units. Throws Error
// naming MESH for an empty mesh or a non-positive voxel size or band.
openvdb::FloatGrid::Ptr BuildOpenVdbField(const TriangleMesh& mesh, const Eigen::Vector3d& origin,
                                          double voxel_size, float band_voxels = 3);

// |FIELD - GRID| at GRID's active voxels whose centre lies in FIELD's box (FIELD trilinear
// there), in GRID's voxels.
struct FieldDifference {
  double max_voxels = 0, rms_voxels = 0;
  std::int64_t compared = 0;            // active voxels inside FIELD's box
  std::int64_t sign_disagreements = 0;  // of those with |GRID| >= one voxel
};
FieldDifference CompareWithOpenVdb(const DistanceField& field, const openvdb::FloatGrid& grid);

}  // namespace contactlab
