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
  // The 13 neighbours sharing a face, edge or corner that come later in index order, as index
  // offsets (all positive). CELLS is sorted, so each offset's neighbour keys rise with the cell:
  // one cursor per offset walks CELLS once.
  std::int64_t offsets[13];
  int m = 0;
  for (int dk = 0; dk <= 1; ++dk) {
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        if (dk == 0 && (dj < 0 || (dj == 0 && di <= 0))) continue;
        offsets[m++] = di + stride_j * dj + stride_k * dk;
      }
    }
  }
  std::int64_t cursor[13] = {};
  int patches = int(n);
  for (std::int64_t a = 0; a < n; ++a) {
    for (int o = 0; o < 13; ++o) {
      const std::int64_t key = cells[a] + offsets[o];
      std::int64_t b = cursor[o];
      while (b < n && cells[b] < key) ++b;
      cursor[o] = b;
      if (b == n || cells[b] != key) continue;
      const std::int32_t ra = find(std::int32_t(a)), rb = find(std::int32_t(b));
      if (ra != rb) {
        parent[std::size_t(std::max(ra, rb))] = std::min(ra, rb);
        --patches;
      }
    }
  }
  return patches;
}

}  // namespace contactlab
