#include "view/display_points.h"

#include <algorithm>
#include <numeric>
#include <string>

#include "util/error.h"

namespace contactlab {

std::vector<std::int32_t> PointsPerLevel(const Pointshell& shell) {
  std::vector<std::int32_t> counts(shell.num_levels());
  for (int l = 0; l < shell.num_levels(); ++l) {
    counts[l] = shell.level_point_end[l] - (l > 0 ? shell.level_point_end[l - 1] : 0);
  }
  return counts;
}

std::vector<std::int32_t> DisplayBudget(const std::vector<std::int32_t>& counts, int max_points) {
  const int nonempty = int(std::count_if(counts.begin(), counts.end(), [](std::int32_t c) { return c > 0; }));
  if (max_points < nonempty) {
    Fail("display points", "a cap of " + std::to_string(max_points) + " points cannot show each of the " +
                               std::to_string(nonempty) + " pointshell levels");
  }
  // Water-filling: levels in order of size; each takes min(size, equal share of what is left).
  std::vector<int> order(counts.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return counts[a] < counts[b]; });
  std::vector<std::int32_t> budget(counts.size(), 0);
  long long left = max_points;
  int levels_left = nonempty;
  for (int l : order) {
    if (counts[l] <= 0) continue;
    const long long share = left / levels_left;
    budget[l] = std::int32_t(std::max<long long>(1, std::min<long long>(counts[l], share)));
    left -= budget[l];
    --levels_left;
  }
  return budget;
}

DisplayPoints DecimatePointshell(const Pointshell& shell, int max_points) {
  DisplayPoints out;
  out.total = PointsPerLevel(shell);
  out.kept = shell.num_points() <= max_points ? out.total : DisplayBudget(out.total, max_points);
  const int kept = std::accumulate(out.kept.begin(), out.kept.end(), 0);
  out.xyz.reserve(std::size_t(kept) * 3);
  out.level.reserve(std::size_t(kept));
  out.index.reserve(std::size_t(kept));
  int begin = 0;
  for (int l = 0; l < shell.num_levels(); ++l) {
    const int n = out.total[l], m = out.kept[l];
    // Evenly spaced picks i = floor(k n / m), k = 0..m-1: distinct because n >= m.
    for (int k = 0; k < m; ++k) {
      const int i = begin + int((long long)k * n / m);
      out.xyz.insert(out.xyz.end(), {shell.x[i], shell.y[i], shell.z[i]});
      out.level.push_back(std::uint8_t(l));
      out.index.push_back(i);
    }
    begin += n;
  }
  return out;
}

}  // namespace contactlab
