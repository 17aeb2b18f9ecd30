// The pressure-field lattice: fitting, octree culling and block sampling (lattice_blocks.h).
#include "baselines/pressure_field/lattice_blocks.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sdf/batch_distance.h"

namespace contactlab {

bool FitLattice(const Aabb& box_M, const Aabb& box_L, const Eigen::Vector3d& o_L, const Pose& X_LM, double h,
                Eigen::Vector3d* origin, Eigen::Vector3i* cells) {
  // The overlap of M's box (in L's frame) and L's box.
  const Aabb& a = box_M;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner((c & 1) ? a.max.x() : a.min.x(), (c & 2) ? a.max.y() : a.min.y(),
                                 (c & 4) ? a.max.z() : a.min.z());
    const Eigen::Vector3d p = X_LM * corner;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo = lo.cwiseMax(box_L.min);
  hi = hi.cwiseMin(box_L.max);
  if ((lo.array() >= hi.array()).any()) return false;
  // Aligned with L's grid, at least one cell per axis.
  for (int d = 0; d < 3; ++d) {
    (*origin)[d] = o_L[d] + h * std::floor((lo[d] - o_L[d]) / h);
    (*cells)[d] = std::max(1, int(std::ceil((hi[d] - (*origin)[d]) / h)));
  }
  return true;
}

std::int64_t CullBlocks(const DistanceField& field_L, const DistanceField& field_M, const Pose& X_ML,
                        const PressureLaw& law, const Eigen::Vector3d& origin, const Eigen::Vector3i& cells,
                        double h, int root, double lipschitz, std::array<std::int32_t, 3>* blocks,
                        std::int64_t capacity, std::int64_t* nodes, std::int64_t limit) {
  const double margin = kCullMargin * h;
  struct Node {
    std::int32_t i, j, k, size;
  };
  Node stack[512];
  int top = 0;
  stack[top++] = {0, 0, 0, root};
  std::int64_t kept = 0;
  while (top > 0) {
    const Node n = stack[--top];
    if (n.i >= cells.x() || n.j >= cells.y() || n.k >= cells.z()) continue;
    ++*nodes;
    // Both fields at the node's centre, against the reach of its bounding sphere.
    const double half = 0.5 * n.size;
    const Eigen::Vector3d c = origin + h * Eigen::Vector3d(n.i + half, n.j + half, n.k + half);
    const double r = h * half * std::sqrt(3.0);
    const double phi_L = field_L.Distance(c);
    const double phi_M = field_M.Distance(X_ML * c);
    const double reach = lipschitz * r + margin;
    if (phi_M > reach || phi_L > reach) continue;
    if (std::abs(law.Gap(phi_M, phi_L)) > lipschitz * (r + margin)) continue;  // the gap is as steep as a field
    // Larger than a block: its eight octants.
    if (n.size > kBlock) {
      const std::int32_t s = n.size / 2;
      for (int q = 0; q < 8; ++q) {
        stack[top++] = {n.i + ((q & 1) ? s : 0), n.j + ((q & 2) ? s : 0), n.k + ((q & 4) ? s : 0), s};
      }
      continue;
    }
    if (limit > 0 && kept >= limit) return limit + 1;
    if (kept >= capacity) continue;  // over capacity: not rendered
    blocks[kept++] = {n.i, n.j, n.k};
  }
  return kept;
}

void SampleBlock(const DistanceField& field, const Eigen::Vector3d& origin, double h,
                 const std::array<std::int32_t, 3>& blk, float* phi) {
  // The lattice lies on the field's grid (FitLattice): inside the grid a vertex's value is its
  // grid sample, read directly.
  const double cells_per_step = h / field.spacing();
  const int step = int(std::lround(cells_per_step));
  std::int64_t first[3];
  bool inside = !field.sparse() && step >= 1;
  for (int d = 0; d < 3 && inside; ++d) {
    first[d] = std::llround((origin[d] - field.origin()[d]) / field.spacing()) + std::int64_t(step) * blk[d];
    inside = first[d] >= 0 && first[d] + std::int64_t(step) * kBlock < field.dims()[d];
  }
  if (inside) {
    const float* values = field.values().data();
    for (int k = 0; k < kVerts; ++k) {
      for (int j = 0; j < kVerts; ++j) {
        const float* row = values + field.Index(int(first[0]), int(first[1] + step * j), int(first[2] + step * k));
        for (int i = 0; i < kVerts; ++i) phi[VertexIndex(i, j, k)] = row[step * i];
      }
    }
    return;
  }
  for (int k = 0; k < kVerts; ++k) {
    for (int j = 0; j < kVerts; ++j) {
      for (int i = 0; i < kVerts; ++i) {
        const Eigen::Vector3d x = origin + h * Eigen::Vector3d(blk[0] + i, blk[1] + j, blk[2] + k);
        phi[VertexIndex(i, j, k)] = float(field.Distance(x));
      }
    }
  }
}

LatticeInOther::LatticeInOther(const Pose& X_ML_in, double h) : X_ML(X_ML_in) {
  const Eigen::Matrix3d R_ML = X_ML.R();
  step_i = R_ML.col(0) * h;
  step_j = R_ML.col(1) * h;
  step_k = R_ML.col(2) * h;
}

void SampleBlockInOther(const DistanceField& field, const LatticeInOther& lattice, const Eigen::Vector3d& x0,
                        float* phi) {
  // The vertices in M's frame, placed in double and rounded once to float, then looked up a
  // vector at a time (the batch's transform the identity: the points as they are, bit for bit).
  float x[kBlockVerts], y[kBlockVerts], z[kBlockVerts];
  const Eigen::Vector3d a0 = lattice.X_ML * x0;
  for (int k = 0; k < kVerts; ++k) {
    for (int j = 0; j < kVerts; ++j) {
      Eigen::Vector3d a = a0 + double(j) * lattice.step_j + double(k) * lattice.step_k;
      for (int i = 0; i < kVerts; ++i, a += lattice.step_i) {
        const int v = VertexIndex(i, j, k);
        x[v] = float(a.x());
        y[v] = float(a.y());
        z[v] = float(a.z());
      }
    }
  }
  BatchDistances(field, kIdentityTransform, x, y, z, nullptr, kBlockVerts, phi);
}

}  // namespace contactlab
