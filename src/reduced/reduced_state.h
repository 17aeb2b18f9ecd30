// The reduced deformation state of one deformable body: reduced coordinates q and their rates
// (Barbič & James 2008, sec. 4: u = U q for every surface point), and what a contact query
// reads and writes of it. Header only, below contact/ and deform/.
#pragma once

#include <Eigen/Core>

namespace contactlab {

// Largest number of reduced coordinates a model may have; run-time scratch uses Eigen types of
// this maximum size so a time step never allocates.
inline constexpr int kMaxReducedModes = 40;

using ReducedVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxReducedModes, 1>;
using ReducedMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxReducedModes, kMaxReducedModes>;

struct ReducedState {
  ReducedVector q;     // r reduced displacements (mass-normalised coordinates)
  ReducedVector qdot;  // r reduced velocities, per second

  ReducedState() = default;
  explicit ReducedState(int r) : q(ReducedVector::Zero(r)), qdot(ReducedVector::Zero(r)) {}
  int size() const { return int(q.size()); }
};

// One deformable body's part of a contact query (sec. 4): its reduced coordinates in, its reduced
// contact force (and that force's stiffness, for a linearly implicit step) out.
struct BodyDeformation {
  const ReducedState* q = nullptr;  // r entries; null: at rest
  // Out: the reduced contact force on the body, sum_i U_i^T F_i over the contact forces F_i
  // (body frame) at the places they act on it (r entries). Null: not wanted.
  ReducedVector* force = nullptr;
  // Out, with FORCE: -d(force)/dq (r x r, symmetric positive semidefinite) under the sec. 5
  // halfspace rule, k sum_i w_i w_i^T with w_i = U_i^T N_i. Null: not wanted.
  ReducedMatrix* stiffness = nullptr;
};

}  // namespace contactlab
