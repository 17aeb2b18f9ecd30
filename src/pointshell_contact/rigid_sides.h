// The rigid sides of the paper's contact model (Barbič & James 2008, sec. 2.1, 3): a rigid
// pointshell (points at their rest positions in A, rest radii) and a grid distance field
// (trilinear lookups, many points per instruction). PointshellFieldModel combines a shell side
// with a field side; the deformable sides (contact/deformable_sides.h) answer the same calls.
//
// A shell side answers:
//   kDeforms                 false: positions and normals are the pointshell's own arrays
//   shell()                  the pointshell whose tree the traversals walk
//   Begin(q)                 this query's deformation (null: none); false when Q does not fit
//                            the body
//   Radius(node)             the node's bounding radius at this query
// A field side answers:
//   kDeforms, rest_field()   the field at rest (checks, gradient step)
//   Begin(q)                 as the shell side's, for the field body
//   Distances(X_BA, x, y, z, index, n, d, nearest)
//                            d[k] of point (x, y, z)[i], i = index[k] (k when null), placed in
//                            B by X_BA; NEAREST[k] the proxy its force acts through (deformed
//                            only)
//   Gradient(p_B)            the field's gradient at p_B (ContactGradient::kField)
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>

#include "contact/float_transform.h"
#include "pointshell/pointshell.h"
#include "reduced/reduced_state.h"
#include "sdf/batch_distance.h"
#include "sdf/distance_field.h"

namespace contactlab {

// What both rigid sides answer about deformation: there is none. Only an empty deformation
// fits a rigid body.
struct RigidSide {
  static constexpr bool kDeforms = false;
  int r() const { return 0; }
  bool Begin(const ReducedState* q) const { return q == nullptr || q->size() == 0; }
};

class RigidShell : public RigidSide {
 public:
  using Source = std::shared_ptr<const Pointshell>;
  static constexpr const char* kWhat = "pointshell";

  RigidShell() = default;
  explicit RigidShell(Source shell) : shell_(std::move(shell)) {}
  const Pointshell* get() const { return shell_.get(); }
  const Pointshell& shell() const { return *shell_; }
  float Radius(int node) const { return shell_->node_radius[node]; }

 private:
  Source shell_;
};

class GridField : public RigidSide {
 public:
  using Source = std::shared_ptr<const DistanceField>;
  static constexpr const char* kWhat = "distance field";

  GridField() = default;
  explicit GridField(Source field) : field_(std::move(field)) {}
  const DistanceField* rest_field_ptr() const { return field_.get(); }
  const DistanceField& rest_field() const { return *field_; }

  void Distances(const FloatTransform& X_BA, const float* x, const float* y, const float* z,
                 const std::int32_t* index, int n, float* d, std::int32_t* nearest) const {
    BatchDistances(*field_, X_BA, x, y, z, index, n, d);
  }
  Eigen::Vector3d Gradient(const Eigen::Vector3d& p_B) const {
    Eigen::Vector3d g_B;
    field_->DistanceAndGradient(p_B, &g_B);
    return g_B;
  }

 private:
  Source field_;
};

}  // namespace contactlab
