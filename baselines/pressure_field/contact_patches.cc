// Connected pieces of the contact surface by union-find over its cells (contact_patches.h).
#include "baselines/pressure_field/contact_patches.h"

#include <algorithm>
#include <cstddef>

namespace contactlab {

int CountPatches(std::int64_t* cells, std::int64_t n, std::int64_t stride_j, std::int64_t stride_k,
                 std::int32_t* parent) {
  if (n == 0) return 0;
  std::sort(cells, cells + n);
  for (std::int64_t i = 0; i < n; ++i) parent[std::size_t(i)] = std::int32_t(i);
  auto find = [&](std::int32_t x) {
    while (parent[std::size_t(x)] != x) {
      parent[std::size_t(x)] = parent[std::size_t(parent[std::size_t(x)])];
      x = parent[std::size_t(x)];
    }
    return x;
  };
  int patches = int(n);
  for (std::int64_t a = 0; a < n; ++a) {
    // The 13 neighbours sharing a face, edge or corner that come later in index order.
    for (int dk = 0; dk <= 1; ++dk) {
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          if (dk == 0 && (dj < 0 || (dj == 0 && di <= 0))) continue;
          const std::int64_t key = cells[a] + di + stride_j * dj + stride_k * dk;
          const std::int64_t* it = std::lower_bound(cells, cells + n, key);
          if (it == cells + n || *it != key) continue;
          const std::int32_t ra = find(std::int32_t(a)), rb = find(std::int32_t(it - cells));
          if (ra != rb) {
            parent[std::size_t(std::max(ra, rb))] = std::min(ra, rb);
            --patches;
          }
        }
      }
    }
  }
  return patches;
}

}  // namespace contactlab
