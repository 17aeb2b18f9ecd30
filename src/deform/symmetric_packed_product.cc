// SymmetricPackedProduct for each instruction set Highway compiles (this file is included once
// per target by foreach_target.h), and the run-time dispatch between them.
#include "deform/symmetric_packed_product.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "deform/symmetric_packed_product.cc"
#include <hwy/foreach_target.h>  // NOLINT: re-includes this file per target
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace contactlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Each stored entry S(p, k), k > p, is used twice: in row p's dot product (y_p += S(p, k) x_k)
// and for the mirrored entry S(k, p) (y_k += S(p, k) x_p). Rows are taken four at a time,
// so the loads of x_k and the load/store of y_k are shared by four rows, and the column loop
// is unrolled twice: eight independent dot-product accumulators hide the FMA latency, so the
// loop runs at the FMA throughput (two multiply-adds per stored entry).
// (Named registers, not arrays of vectors: GCC keeps arrays of vectors on the stack.)

// Rows P .. P + 3. ROW_A + k addresses S(p + a, k), k >= p + a.
HWY_INLINE void FourRows(const double* HWY_RESTRICT r0, const double* HWY_RESTRICT r1,
                         const double* HWY_RESTRICT r2, const double* HWY_RESTRICT r3, int p, int n,
                         const double* HWY_RESTRICT x, double* HWY_RESTRICT y) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const int lanes = int(hn::Lanes(d));
  const double* rows[4] = {r0, r1, r2, r3};
  // The 4 x 4 diagonal block, upper part, scalar.
  double dot[4] = {0, 0, 0, 0};
  for (int a = 0; a < 4; ++a) {
    dot[a] += rows[a][p + a] * x[p + a];
    for (int k = p + a + 1; k < p + 4; ++k) {
      dot[a] += rows[a][k] * x[k];
      y[k] += rows[a][k] * x[p + a];
    }
  }
  // Columns k >= p + 4: first the (n - p - 4) mod (2 lanes) nearest the diagonal, scalar,
  // then two vectors at a time up to n. Vector columns thus sit on one grid ending at n in
  // every row block, so each vector load of y reads exactly what an earlier vector store
  // wrote (a vector load over scalar stores cannot be forwarded and stalls).
  int k = p + 4;
  for (const int head = k + (n - k) % (2 * lanes); k < head; ++k) {
    dot[0] += r0[k] * x[k];
    dot[1] += r1[k] * x[k];
    dot[2] += r2[k] * x[k];
    dot[3] += r3[k] * x[k];
    y[k] += (r0[k] * x[p] + r1[k] * x[p + 1]) + (r2[k] * x[p + 2] + r3[k] * x[p + 3]);
  }
  const V x0s = hn::Set(d, x[p]), x1s = hn::Set(d, x[p + 1]), x2s = hn::Set(d, x[p + 2]), x3s = hn::Set(d, x[p + 3]);
  V a0 = hn::Zero(d), a1 = a0, a2 = a0, a3 = a0, b0 = a0, b1 = a0, b2 = a0, b3 = a0;
  for (; k < n; k += 2 * lanes) {
    const V xa = hn::LoadU(d, x + k), xb = hn::LoadU(d, x + k + lanes);
    const V s0a = hn::LoadU(d, r0 + k), s0b = hn::LoadU(d, r0 + k + lanes);
    const V s1a = hn::LoadU(d, r1 + k), s1b = hn::LoadU(d, r1 + k + lanes);
    const V s2a = hn::LoadU(d, r2 + k), s2b = hn::LoadU(d, r2 + k + lanes);
    const V s3a = hn::LoadU(d, r3 + k), s3b = hn::LoadU(d, r3 + k + lanes);
    a0 = hn::MulAdd(s0a, xa, a0);
    b0 = hn::MulAdd(s0b, xb, b0);
    a1 = hn::MulAdd(s1a, xa, a1);
    b1 = hn::MulAdd(s1b, xb, b1);
    a2 = hn::MulAdd(s2a, xa, a2);
    b2 = hn::MulAdd(s2b, xb, b2);
    a3 = hn::MulAdd(s3a, xa, a3);
    b3 = hn::MulAdd(s3b, xb, b3);
    // y_k += sum_a S(p + a, k) x_(p + a), as two independent pairs.
    const V ya = hn::Add(hn::MulAdd(s0a, x0s, hn::Mul(s1a, x1s)), hn::MulAdd(s2a, x2s, hn::Mul(s3a, x3s)));
    const V yb = hn::Add(hn::MulAdd(s0b, x0s, hn::Mul(s1b, x1s)), hn::MulAdd(s2b, x2s, hn::Mul(s3b, x3s)));
    hn::StoreU(hn::Add(hn::LoadU(d, y + k), ya), d, y + k);
    hn::StoreU(hn::Add(hn::LoadU(d, y + k + lanes), yb), d, y + k + lanes);
  }
  y[p] += dot[0] + hn::GetLane(hn::SumOfLanes(d, hn::Add(a0, b0)));
  y[p + 1] += dot[1] + hn::GetLane(hn::SumOfLanes(d, hn::Add(a1, b1)));
  y[p + 2] += dot[2] + hn::GetLane(hn::SumOfLanes(d, hn::Add(a2, b2)));
  y[p + 3] += dot[3] + hn::GetLane(hn::SumOfLanes(d, hn::Add(a3, b3)));
}

// Row P alone (the last N mod 4 rows), scalar: at most three short rows.
HWY_INLINE void OneRow(const double* HWY_RESTRICT r0, int p, int n, const double* HWY_RESTRICT x,
                       double* HWY_RESTRICT y) {
  double dot = r0[p] * x[p];
  for (int k = p + 1; k < n; ++k) {
    dot += r0[k] * x[k];
    y[k] += r0[k] * x[p];
  }
  y[p] += dot;
}

void SymmetricPackedProductImpl(const double* HWY_RESTRICT packed, int n, const double* HWY_RESTRICT x,
                                double* HWY_RESTRICT y) {
  for (int k = 0; k < n; ++k) y[k] = 0;
  // Row(p) + k addresses S(p, k): row p starts at PackedUpperRowStart(p) with column p.
  auto row = [&](int p) { return packed + PackedUpperRowStart(p, n) - p; };
  int p = 0;
  for (; p + 4 <= n; p += 4) FourRows(row(p), row(p + 1), row(p + 2), row(p + 3), p, n, x, y);
  for (; p < n; ++p) OneRow(row(p), p, n, x, y);
}

const char* SymmetricPackedTargetImpl() { return hwy::TargetName(HWY_TARGET); }

// NOLINTNEXTLINE(google-readability-namespace-comments)
}  // namespace HWY_NAMESPACE
}  // namespace contactlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace contactlab {
HWY_EXPORT(SymmetricPackedProductImpl);
HWY_EXPORT(SymmetricPackedTargetImpl);

void SymmetricPackedProduct(const double* packed, int n, const double* x, double* y) {
  HWY_DYNAMIC_DISPATCH(SymmetricPackedProductImpl)(packed, n, x, y);
}
const char* SymmetricPackedProductTarget() { return HWY_DYNAMIC_DISPATCH(SymmetricPackedTargetImpl)(); }
}  // namespace contactlab
#endif  // HWY_ONCE
