// A bounding-volume hierarchy over triangles for exact closest-triangle queries (Barbič & James
// 2008, sec. 2.3: exact distances where the field must be exact, e.g. its boundary samples).
// Flat arrays: nodes in depth-first order (left child follows its parent), triangles reordered
// so that each leaf holds a contiguous range.
#pragma once

#include <cstdint>
#include <vector>

namespace contactlab {

class TriangleBvh {
 public:
  // CORNERS: 9 doubles per triangle (a, b, c), metres (see FlattenTriangles).
  explicit TriangleBvh(const std::vector<double>& corners);

  // Smallest squared distance from P (3 doubles) to a triangle when it is below BOUND2; the
  // index of that triangle goes to *TRIANGLE. Returns BOUND2 (TRIANGLE untouched) when no
  // triangle is closer. Exact (double arithmetic); never allocates or throws.
  double ClosestSquared(const double* p, double bound2, std::int32_t* triangle) const;

  int num_triangles() const { return int(ids_.size()); }

 private:
  struct Node {
    double lo[3], hi[3];
    std::int32_t first;  // leaf: first triangle slot; inner: index of the right child
    std::int32_t count;  // leaf: triangle count (> 0); inner: 0
  };
  int Build(std::vector<std::int32_t>& ids, const std::vector<double>& corners, int begin, int end);

  std::vector<Node> nodes_;
  std::vector<double> tri_;         // corners in leaf order, 9 per slot
  std::vector<std::int32_t> ids_;   // original triangle index per slot
};

}  // namespace contactlab
