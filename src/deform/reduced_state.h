// The reduced deformation state of one deformable body: reduced coordinates q and their rates
// (Barbič & James 2008, sec. 4: u = U q for every surface point).
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

}  // namespace contactlab
