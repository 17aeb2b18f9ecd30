#include "view/display_points.h"

#include <gtest/gtest.h>

#include <numeric>
#include <random>
#include <set>

#include "util/error.h"
#include "view/field_slice.h"

namespace contactlab {
namespace {

// A pointshell whose points of level l have x = l and y = their index within the level, as
// the nested shells have them: 4 points on level 0, then 4x more per level.
Pointshell LayeredShell(std::vector<int> per_level) {
  Pointshell s;
  int end = 0;
  for (int l = 0; l < int(per_level.size()); ++l) {
    for (int i = 0; i < per_level[l]; ++i) {
      s.x.push_back(float(l));
      s.y.push_back(float(i));
      s.z.push_back(0);
      s.nx.push_back(0);
      s.ny.push_back(0);
      s.nz.push_back(1);
    }
    end += per_level[l];
    s.level_point_end.push_back(end);
  }
  return s;
}

TEST(DisplayPoints, SmallShellIsDrawnWhole) {
  const Pointshell s = LayeredShell({4, 12, 48});
  const DisplayPoints d = DecimatePointshell(s, 1000);
  EXPECT_EQ(d.num_kept(), 64);
  EXPECT_EQ(d.kept, (std::vector<std::int32_t>{4, 12, 48}));
  EXPECT_EQ(d.total, (std::vector<std::int32_t>{4, 12, 48}));
  for (int i = 0; i < d.num_kept(); ++i) EXPECT_EQ(d.xyz[3 * i], float(d.level[i]));
}

TEST(DisplayPoints, LargeShellRespectsTheCapAndKeepsEveryLevel) {
  const Pointshell s = LayeredShell({4, 12, 48, 192, 768, 3072, 12288});
  for (int cap : {16, 50, 100, 1000, 5000}) {
    const DisplayPoints d = DecimatePointshell(s, cap);
    EXPECT_LE(d.num_kept(), cap);
    EXPECT_GE(d.num_kept(), cap - int(s.num_levels()));  // the budget is used up to rounding
    std::vector<std::set<float>> seen(s.num_levels());
    for (int i = 0; i < d.num_kept(); ++i) {
      // Each kept point comes from its own level's run, and none twice.
      ASSERT_EQ(d.xyz[3 * i], float(d.level[i])) << "cap " << cap;
      // Its index names the shell point it was taken from.
      const std::int32_t k = d.index[i];
      ASSERT_TRUE(k >= 0 && k < s.num_points());
      EXPECT_EQ(d.xyz[3 * i + 1], s.y[k]);
      EXPECT_EQ(d.xyz[3 * i], s.x[k]);
      EXPECT_TRUE(seen[d.level[i]].insert(d.xyz[3 * i + 1]).second) << "cap " << cap;
    }
    for (int l = 0; l < s.num_levels(); ++l) {
      EXPECT_GE(seen[l].size(), 1u) << "level " << l << " lost at cap " << cap;
      EXPECT_EQ(int(seen[l].size()), d.kept[l]);
    }
  }
}

TEST(DisplayPoints, CoarseLevelsKeepAllTheirPoints) {
  // 50,000 points over 5 levels: the first three (4 + 12 + 48) are far under their share.
  const Pointshell s = LayeredShell({4, 12, 48, 20000, 60000});
  const DisplayPoints d = DecimatePointshell(s, 50000);
  EXPECT_EQ(d.kept[0], 4);
  EXPECT_EQ(d.kept[1], 12);
  EXPECT_EQ(d.kept[2], 48);
  EXPECT_EQ(d.kept[3], 20000);  // its share of the rest is larger than the level
  EXPECT_EQ(d.kept[4], 50000 - 4 - 12 - 48 - 20000);
}

TEST(DisplayPoints, KeptPointsSpreadOverTheLevel) {
  const Pointshell s = LayeredShell({1000});
  const DisplayPoints d = DecimatePointshell(s, 100);
  ASSERT_EQ(d.num_kept(), 100);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(d.xyz[3 * i + 1], float(10 * i));  // every 10th
}

TEST(DisplayPoints, BudgetIsMaxMinFairOnRandomShells) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::int32_t> counts(1 + rng() % 12);
    for (auto& c : counts) c = std::int32_t(rng() % 5000);
    const int cap = 12 + int(rng() % 20000);
    const std::vector<std::int32_t> b = DisplayBudget(counts, cap);
    const long long sum = std::accumulate(b.begin(), b.end(), 0LL);
    EXPECT_LE(sum, cap);
    const long long total = std::accumulate(counts.begin(), counts.end(), 0LL);
    EXPECT_GE(sum, std::min<long long>(total, cap - static_cast<long long>(counts.size())));
    std::int32_t largest_cut = 0;
    for (std::size_t l = 0; l < counts.size(); ++l) {
      EXPECT_LE(b[l], counts[l]);
      if (counts[l] > 0) {
        EXPECT_GE(b[l], 1);
      }
      if (b[l] < counts[l]) largest_cut = std::max(largest_cut, b[l]);
    }
    // A level that keeps everything is no larger than a cut level's share, up to rounding.
    for (std::size_t l = 0; l < counts.size(); ++l) {
      if (b[l] == counts[l] && largest_cut > 0) {
        EXPECT_LE(b[l], largest_cut + 1);
      }
    }
  }
}

TEST(DisplayPoints, CapBelowTheLevelCountIsAnError) {
  const Pointshell s = LayeredShell({4, 12, 48, 192});
  EXPECT_THROW(DecimatePointshell(s, 3), Error);
}

// The signed distance of a sphere of radius R at the origin on a grid.
DistanceField SphereField(double radius, int n, double half) {
  const double h = 2 * half / (n - 1);
  std::vector<float> v;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) v.push_back(float(Eigen::Vector3d(-half + i * h, -half + j * h, -half + k * h).norm() - radius));
  return DistanceField(Eigen::Vector3d::Constant(-half), h, Eigen::Vector3i::Constant(n), v);
}

TEST(FieldSlice, SamplesThePlaneOfTheField) {
  const DistanceField f = SphereField(0.3, 41, 1.0);
  const FieldSlice s = SliceField(f, 1, 0.0);
  EXPECT_EQ(s.width, 41);
  EXPECT_EQ(s.height, 41);
  EXPECT_DOUBLE_EQ(s.corner.y(), 0.0);
  // U is z (the axis after y), V is x.
  EXPECT_GT(s.u.z(), 0);
  EXPECT_GT(s.v.x(), 0);
  for (int j = 0; j < s.height; ++j) {
    for (int i = 0; i < s.width; ++i) {
      const Eigen::Vector3d p = s.corner + i * s.u + j * s.v;
      EXPECT_NEAR(s.values[j * s.width + i], p.norm() - 0.3, 1e-5);
    }
  }
}

TEST(FieldSlice, ClampsThePlaneAndThinsLargeGrids) {
  const DistanceField f = SphereField(0.3, 41, 1.0);
  const FieldSlice s = SliceField(f, 2, 5.0, 16);
  EXPECT_DOUBLE_EQ(s.at, 1.0);
  EXPECT_LE(s.width, 16);
  EXPECT_LE(s.height, 16);
  EXPECT_THROW(SliceField(f, 3, 0.0), Error);
}

}  // namespace
}  // namespace contactlab
