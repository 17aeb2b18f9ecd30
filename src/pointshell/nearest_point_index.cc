// nanoflann k-d tree over float positions (Barbič & James 2008, sec. 2.4: parent search).
#include "pointshell/nearest_point_index.h"

#include <nanoflann.hpp>

namespace contactlab {
namespace {

struct PointCloudAdaptor {
  const float* x;
  const float* y;
  const float* z;
  std::size_t count;
  std::size_t kdtree_get_point_count() const { return count; }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const { return dim == 0 ? x[i] : dim == 1 ? y[i] : z[i]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointCloudAdaptor>,
                                                 PointCloudAdaptor, 3, std::uint32_t>;

}  // namespace

struct NearestPointIndex::Impl {
  PointCloudAdaptor cloud;
  Tree tree;
  explicit Impl(const PointCloudAdaptor& c)
      : cloud(c), tree(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(12)) {}
};

NearestPointIndex::NearestPointIndex(const float* x, const float* y, const float* z, std::int32_t count)
    : impl_(std::make_unique<Impl>(PointCloudAdaptor{x, y, z, std::size_t(count)})) {}

NearestPointIndex::~NearestPointIndex() = default;

int NearestPointIndex::Nearest(const float q[3], int k, std::int32_t* index, float* dist2) const {
  std::uint32_t idx[2];
  float d2[2];
  nanoflann::KNNResultSet<float, std::uint32_t> result{std::size_t(k)};
  result.init(idx, d2);
  impl_->tree.findNeighbors(result, q, nanoflann::SearchParams());
  const int found = int(result.size());
  for (int i = 0; i < found; ++i) {
    index[i] = std::int32_t(idx[i]);
    dist2[i] = d2[i];
  }
  return found;
}

}  // namespace contactlab
