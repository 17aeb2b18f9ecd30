// y = S x for a symmetric matrix S held as its packed upper triangle, the contraction that
// dominates the reduced StVK force and stiffness (the cubic coefficients, Barbič & James 2005,
// sec. 3): reading only the upper half halves the memory streamed per evaluation. Highway,
// dispatched at run time to the best instruction set (AVX2 + FMA where present).
#pragma once

#include <cstddef>

namespace contactlab {

// Index of S(p, p) in the packed upper rows of an N x N symmetric matrix: row p holds
// S(p, p), S(p, p + 1), ..., S(p, N - 1), rows one after another.
inline std::size_t PackedUpperRowStart(int p, int n) {
  return std::size_t(p) * std::size_t(2 * n - p + 1) / 2;  // sum of the lengths n - i, i < p
}
// Entries in the packed upper triangle of an N x N matrix, N (N + 1) / 2.
inline std::size_t PackedUpperSize(int n) { return std::size_t(n) * std::size_t(n + 1) / 2; }

// Y (N) = S X for S (N x N, symmetric) given as PACKED upper rows (PackedUpperSize(N)
// entries, see PackedUpperRowStart); X (N). Y must not alias X or PACKED. Allocates nothing,
// throws nothing. Summation order differs from a plain row-by-row product (results agree to
// rounding).
void SymmetricPackedProduct(const double* packed, int n, const double* x, double* y);

// The instruction set the dispatcher chose ("AVX2", "SSE4", ...), for benchmark reports.
const char* SymmetricPackedProductTarget();

}  // namespace contactlab
