// A reduced deformable model: coarse tet mesh, anchoring, material, reduced basis and the
// reduced-force polynomial coefficients, built once and stored in a versioned binary file
// (Barbič & James 2008, sec. 4.1; precomputation of Barbič & James 2005, sec. 4).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "deform/anchoring.h"
#include "deform/reduced_forces.h"
#include "deform/stvk_fem.h"
#include "deform/tet_mesh.h"

namespace contactlab {

struct ReducedModelOptions {
  int modes = 15;            // r, reduced coordinates, in [1, kMaxReducedModes]
  int linear_modes = 0;      // linear modes whose derivatives enter the PCA; 0: automatic
  ReducedModelKind kind = ReducedModelKind::kStVK;  // kLinear: r linear modes, constant K
  StVKMaterial material;
  MassKind mass = MassKind::kLumped;
  Anchoring anchoring;       // free body when not anchored
  bool show_progress = true; // progress on a terminal (util/progress.h)
};

struct ReducedModel {
  std::string source;                 // mesh file or description
  TetMesh mesh;
  Anchoring anchoring;
  std::vector<std::uint8_t> fixed;    // #V flags, 1 = anchored vertex
  StVKMaterial material;
  MassKind mass = MassKind::kLumped;
  Eigen::MatrixXd basis;              // 3#V x r, mass-orthonormal (U^T M U = I)
  Eigen::VectorXd eigenvalues;        // lambda = omega^2 of the linear modes used, 1/s^2
  ReducedInternalForces forces;
  double eigen_residual = 0;          // largest relative residual of the linear modes
  double build_seconds = 0;

  int r() const { return int(basis.cols()); }
  ReducedModelKind kind() const { return forces.kind(); }
};

// Runs the precomputation on MESH. Throws Error naming SOURCE for bad material parameters,
// r outside [1, kMaxReducedModes] or beyond what the mesh allows, or anchoring that fixes no
// vertex.
ReducedModel BuildReducedModel(const TetMesh& mesh, const ReducedModelOptions& options, const std::string& source);

// The version of what BuildReducedModel (with the voxel tet mesh it is given) produces. Raise it
// with any change that alters the output for the same inputs: cached results
// (scene/scene_assets.h) of an older version are then no longer found.
inline constexpr int kReducedModelBuilderVersion = 1;

// Versioned binary file (util/binary_io.h), magic "CLRM", version 1, with a checksum.
void SaveReducedModel(const ReducedModel& model, const std::filesystem::path& path);
// Throws Error naming PATH for a missing, truncated, corrupt or inconsistent file.
ReducedModel LoadReducedModel(const std::filesystem::path& path);

// A few lines: source, mesh, anchoring, material, kind, r, frequencies, sizes, build time.
std::string DescribeReducedModel(const ReducedModel& model);

// Natural frequencies sqrt(lambda) / (2 pi) of the linear modes, hertz.
Eigen::VectorXd ModeFrequencies(const ReducedModel& model);

}  // namespace contactlab
