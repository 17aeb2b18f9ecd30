// The connected pieces of the pressure-field contact surface (the `patches` stat): cells that
// carry surface, joined when they share a face, an edge or a corner.
#pragma once

#include <cstdint>

namespace contactlab {

// The number of connected groups among the N cells CELLS (linear lattice indices
// i + STRIDE_J j + STRIDE_K k, with a margin so a neighbour's index never wraps). Sorts CELLS
// in place; PARENT (N entries) is union-find scratch. Allocation-free.
int CountPatches(std::int64_t* cells, std::int64_t n, std::int64_t stride_j, std::int64_t stride_k,
                 std::int32_t* parent);

}  // namespace contactlab
