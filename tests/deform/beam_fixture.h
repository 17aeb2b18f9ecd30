// Shared small models for the deform tests: a voxelised cantilever beam (a few hundred tets).
#pragma once

#include <Eigen/Core>
#include <random>

#include "deform/reduced_model.h"
#include "deform/tet_mesh.h"

namespace contactlab::testing {

// Beam [0, 1] x [0, 0.25] x [0, 0.25] m in 12 x 3 x 3 cubes (648 tets with 6 per cube).
inline TetMesh MakeBeam(TetSplit split = TetSplit::kSix, int nx = 12) {
  return MakeBoxTetMesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0.25, 0.25), nx, nx / 4, nx / 4, split);
}

// Rubber-like material with no special values (E, nu, rho).
inline StVKMaterial BeamMaterial() {
  StVKMaterial m;
  m.youngs_modulus = 1.0e6 / 3.0;
  m.poisson_ratio = 0.3;
  m.density = 1000;
  return m;
}

// Anchored at the x = 0 face.
inline Anchoring BeamAnchoring() { return Anchoring::BelowPlane(Eigen::Vector3d::UnitX(), 1e-9); }

inline ReducedModelOptions BeamOptions(int r, ReducedModelKind kind) {
  ReducedModelOptions o;
  o.modes = r;
  o.kind = kind;
  o.material = BeamMaterial();
  o.anchoring = BeamAnchoring();
  o.show_progress = false;
  return o;
}

inline Eigen::VectorXd RandomVector(int n, double scale, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = u(*rng);
  return v;
}

}  // namespace contactlab::testing
