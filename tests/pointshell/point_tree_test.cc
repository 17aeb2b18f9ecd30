#include "pointshell/point_tree.h"

#include <gtest/gtest.h>

#include <cmath>

#include "pointshell/analytic_fields.h"
#include "pointshell/build_pointshell.h"
#include "pointshell/pointshell_io.h"

namespace contactlab {
namespace {

// An ellipsoid-like field (not a true distance, but a smooth level-set function with
// gradient norm near 1 at the surface), 41^3 samples.
const DistanceField& Blob() {
  static const DistanceField field = testing::SampledField(
      [](const Eigen::Vector3d& p) {
        const Eigen::Vector3d q(p.x() / 0.35, p.y() / 0.25, p.z() / 0.2);
        return 0.25 * (q.norm() - 1.0);
      },
      0.5, 41, "ellipsoid");
  return field;
}

Pointshell Build(PointshellMethod method, int points, int levels) {
  PointshellOptions o;
  o.method = method;
  o.num_points = points;
  o.num_levels = levels;
  o.seed = 3;
  o.show_progress = false;
  return BuildPointshell(Blob(), o);
}

double Distance(const Pointshell& s, int a, int b) {
  return std::sqrt(std::pow(double(s.x[a]) - s.x[b], 2) + std::pow(double(s.y[a]) - s.y[b], 2) +
                   std::pow(double(s.z[a]) - s.z[b], 2));
}

int LevelOfNode(const Pointshell& s, int node) {
  int level = 0;
  while (node >= s.level_node_begin[level + 1]) ++level;
  return level;
}

class PointTreeTest : public ::testing::TestWithParam<PointshellMethod> {};

// Exhaustive: every node lies inside the bounding sphere of each of its ancestors, and each
// radius is tight (equal, up to float rounding, to its farthest descendant).
TEST_P(PointTreeTest, DescendantsLieInsideEveryAncestorsBoundingSphere) {
  const Pointshell s = Build(GetParam(), 3000, 4);
  std::vector<double> farthest(s.num_nodes(), 0.0);
  std::int64_t checks = 0;
  for (int n = 0; n < s.num_nodes(); ++n) {
    for (int a = s.node_parent[n]; a >= 0; a = s.node_parent[a]) {
      const double d = Distance(s, s.node_point[a], s.node_point[n]);
      ASSERT_LE(d, double(s.node_radius[a])) << "node " << n << " ancestor " << a;
      farthest[a] = std::max(farthest[a], d);
      ++checks;
    }
  }
  EXPECT_GT(checks, 3 * 3000);
  for (int n = 0; n < s.num_nodes(); ++n) {
    EXPECT_NEAR(s.node_radius[n], farthest[n], 1e-6 * (1 + farthest[n])) << n;
    if (LevelOfNode(s, n) == s.num_levels() - 1) {
      EXPECT_EQ(s.node_radius[n], 0.f);
    }
  }
}

// Brute force: a point already on level i has its own instance as parent; a new point has as
// parent the nearest point of level i.
TEST_P(PointTreeTest, ParentIsTheNearestNodeOfTheCoarserLevel) {
  const Pointshell s = Build(GetParam(), 2000, 3);
  for (int level = 1; level < s.num_levels(); ++level) {
    const int coarse = s.level_point_end[level - 1];
    for (int n = s.level_node_begin[level]; n < s.level_node_begin[level + 1]; ++n) {
      const int p = s.node_point[n], parent_point = s.node_point[s.node_parent[n]];
      ASSERT_EQ(LevelOfNode(s, s.node_parent[n]), level - 1);
      if (p < coarse) {
        ASSERT_EQ(parent_point, p) << "node " << n;
        continue;
      }
      double best = INFINITY;
      for (int q = 0; q < coarse; ++q) best = std::min(best, Distance(s, p, q));
      ASSERT_LE(Distance(s, p, parent_point), best * (1 + 1e-6)) << "node " << n;
    }
  }
}

// Tree level L_i is exactly the point prefix [0, level_point_end[i]), children are contiguous
// and ordered by parent, and every node of a deeper level has exactly one parent range.
TEST_P(PointTreeTest, LevelsArePointPrefixesAndChildrenAreContiguous) {
  const Pointshell s = Build(GetParam(), 2000, 3);
  EXPECT_NO_THROW(ValidatePointshell(s, "test"));
  for (int level = 0; level < s.num_levels(); ++level) {
    std::vector<int> seen(s.num_points(), 0);
    for (int n = s.level_node_begin[level]; n < s.level_node_begin[level + 1]; ++n) ++seen[s.node_point[n]];
    for (int p = 0; p < s.num_points(); ++p) ASSERT_EQ(seen[p], p < s.level_point_end[level] ? 1 : 0) << p;
  }
  for (int n = 0; n < s.num_nodes(); ++n) {
    for (int c = s.child_begin[n]; c < s.child_begin[n + 1]; ++c) ASSERT_EQ(s.node_parent[c], n);
    if (n > 0 && s.node_parent[n] >= 0 && s.node_parent[n - 1] >= 0) {
      ASSERT_LE(s.node_parent[n - 1], s.node_parent[n]);
    }
    // A non-leaf node's first child is its own instance.
    if (s.child_begin[n] < s.child_begin[n + 1]) {
      ASSERT_EQ(s.node_point[s.child_begin[n]], s.node_point[n]);
    }
  }
  // Leaves have empty child ranges ending at the node count.
  for (int n = s.level_node_begin[s.num_levels() - 1]; n <= s.num_nodes(); ++n) ASSERT_EQ(s.child_begin[n], s.num_nodes());
}

INSTANTIATE_TEST_SUITE_P(Methods, PointTreeTest,
                         ::testing::Values(PointshellMethod::kRepulsion, PointshellMethod::kRandom),
                         [](const auto& info) { return PointshellMethodName(info.param); });

// A hand-checked tree: five points on a line, levels {0, 1} and {2, 3, 4}.
TEST(PointTree, SmallExampleMatchesHandComputedTree) {
  Pointshell s;
  s.x = {0, 10, 1, 9, 4};
  s.y = s.z = std::vector<float>(5, 0.f);
  s.nx = s.ny = std::vector<float>(5, 0.f);
  s.nz = std::vector<float>(5, 1.f);
  s.level_point_end = {2, 5};
  BuildPointTree(&s);
  EXPECT_EQ(s.level_node_begin, (std::vector<std::int32_t>{0, 2, 7}));
  // Level 1 ordered by parent: parent node 0 (x=0) gets points 0, 2, 4; node 1 (x=10) gets 1, 3.
  EXPECT_EQ(s.node_point, (std::vector<std::int32_t>{0, 1, 0, 2, 4, 1, 3}));
  EXPECT_EQ(s.node_parent, (std::vector<std::int32_t>{-1, -1, 0, 0, 0, 1, 1}));
  EXPECT_EQ(s.child_begin, (std::vector<std::int32_t>{2, 5, 7, 7, 7, 7, 7, 7}));
  EXPECT_EQ(s.node_radius, (std::vector<float>{4, 1, 0, 0, 0, 0, 0}));
  EXPECT_NO_THROW(ValidatePointshell(s, "small"));
}

}  // namespace
}  // namespace contactlab
