// DeformedPositions and AddReducedPointSums for each instruction set Highway compiles (this
// file is included once per target by foreach_target.h), and the run-time dispatch between
// them.
#include "deform/reduced_point_batch.h"

#include <algorithm>
#include <cmath>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "deform/reduced_point_batch.cc"
#include <hwy/foreach_target.h>  // NOLINT: re-includes this file per target
#include <hwy/cache_control.h>
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace contactlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// At most kBasisLanes lanes, so every basis stride is a whole number of vectors.
using DF = hn::CappedTag<float, EmbeddedPoints::kBasisLanes>;
constexpr int kLanes = int(hn::MaxLanes(DF()));
static_assert(kLanes == 1 || kLanes == 4 || kLanes == 8, "SumEachOf folds four or eight lanes");

// V[k] for k < kLanes into one vector whose lane k is the sum of V[k]'s lanes. Shuffles stay
// inside 128-bit blocks until the last step: four vectors fold into one holding each one's
// per-block sums (two interleaved additions), and with eight lanes the two blocks of two such
// vectors are added across once, 21 instructions for eight sums.
template <class V>
HWY_INLINE V SumEachOf(const V* v) {
#if HWY_TARGET == HWY_SCALAR
  return v[0];
#else
  const DF d;
  const hn::Repartition<double, DF> dd;
  auto fold2 = [&](V a, V b) HWY_ATTR { return hn::Add(hn::InterleaveLower(d, a, b), hn::InterleaveUpper(d, a, b)); };
  auto fold4 = [&](const V* w) HWY_ATTR {
    const auto p = hn::BitCast(dd, fold2(w[0], w[1])), q = hn::BitCast(dd, fold2(w[2], w[3]));
    return hn::BitCast(d, hn::InterleaveLower(dd, p, q)) + hn::BitCast(d, hn::InterleaveUpper(dd, p, q));
  };
  if constexpr (kLanes == 4) {
    return fold4(v);
  } else {
    const V lo = fold4(v), hi = fold4(v + 4);
    return hn::Add(hn::ConcatLowerLower(d, hi, lo), hn::ConcatUpperUpper(d, hi, lo));
  }
#endif
}

// OUT[c][k] = REST[c][i] + ROWS_i(c) . q for point i = INDEX[k] (BEGIN + k when INDEX is
// null), k < N: the three rows of point i at ROWS + 3 i STRIDE, STRIDE = KCHUNKS vectors,
// unrolled with q held in registers.
template <int kChunks>
void AffineRowsOf(const float* HWY_RESTRICT U, int stride, const float* HWY_RESTRICT const* rest,
                  const float* HWY_RESTRICT q, const std::int32_t* HWY_RESTRICT index, int begin, int n,
                  float* HWY_RESTRICT const* out) {
  const DF d;
  using V = hn::Vec<DF>;
  const std::size_t point_floats = 3 * std::size_t(stride);
  V qv[kChunks];
  for (int m = 0; m < kChunks; ++m) qv[m] = hn::LoadU(d, q + m * kLanes);
  auto rows_of = [&](int k) { return U + point_floats * std::size_t(index ? index[k] : begin + k); };
  // Row ROW . q: independent products summed pairwise.
  auto dot = [&](const float* HWY_RESTRICT row) HWY_ATTR {
    V a = hn::Mul(hn::Load(d, row), qv[0]);
    if constexpr (kChunks > 1) {
      V b = hn::Mul(hn::Load(d, row + kLanes), qv[1]);
      for (int m = 2; m < kChunks; m += 2) {
        a = hn::MulAdd(hn::Load(d, row + m * kLanes), qv[m], a);
        if (m + 1 < kChunks) b = hn::MulAdd(hn::Load(d, row + (m + 1) * kLanes), qv[m + 1], b);
      }
      a = hn::Add(a, b);
    }
    return a;
  };
  for (int k0 = 0; k0 < n; k0 += kLanes) {
    const int count = std::min(kLanes, n - k0);
    // Fetch rows ahead: a tree level's points are scattered (the next group's); contiguous
    // points stream, and the group two on is requested (measured best of 1-4 at 262k points:
    // the hardware prefetcher alone leaves U's stream 1.6x off its bound).
    if (index != nullptr) {
      for (int k = k0 + kLanes; k < std::min(n, k0 + 2 * kLanes); ++k) {
        const float* rows = rows_of(k);
        for (std::size_t f = 0; f < point_floats; f += 16) hwy::Prefetch(rows + f);
      }
    } else if (k0 + 3 * kLanes <= n) {
      const float* rows = rows_of(k0 + 2 * kLanes);
      for (std::size_t f = 0; f < kLanes * point_floats; f += 16) hwy::Prefetch(rows + f);
    }
    const float* group[kLanes];
    for (int k = 0; k < kLanes; ++k) group[k] = rows_of(k0 + std::min(k, count - 1));
    for (int c = 0; c < 3; ++c) {
      V acc[kLanes];
      for (int k = 0; k < kLanes; ++k) acc[k] = dot(group[k] + c * stride);
      const V u = SumEachOf(acc);
      if (count == kLanes) {
        V X;
        if (index == nullptr) {
          X = hn::LoadU(d, rest[c] + begin + k0);
        } else {
          const hn::RebindToSigned<DF> di;
          X = hn::GatherIndex(d, rest[c], hn::LoadU(di, index + k0));
        }
        hn::StoreU(hn::Add(X, u), d, out[c] + k0);
      } else {  // the last group: lanes past COUNT repeat its last point and are dropped
        alignas(64) float lanes[kLanes];
        hn::Store(u, d, lanes);
        for (int k = 0; k < count; ++k) out[c][k0 + k] = rest[c][index ? index[k0 + k] : begin + k0 + k] + lanes[k];
      }
    }
  }
}

void AffineRows(const float* U, int stride, int r, const float* const* rest, const float* q,
                const std::int32_t* index, int begin, int n, float* const* out) {
  switch (stride / kLanes) {
#define CONTACTLAB_CHUNKS(K) \
  case K:                    \
    return AffineRowsOf<K>(U, stride, rest, q, index, begin, n, out);
    CONTACTLAB_CHUNKS(1)
    CONTACTLAB_CHUNKS(2)
    CONTACTLAB_CHUNKS(3)
    CONTACTLAB_CHUNKS(4)
    CONTACTLAB_CHUNKS(5)
    CONTACTLAB_CHUNKS(6)
    CONTACTLAB_CHUNKS(7)
    CONTACTLAB_CHUNKS(8)
    CONTACTLAB_CHUNKS(9)
    CONTACTLAB_CHUNKS(10)
#undef CONTACTLAB_CHUNKS
    default:  // single lanes (no vector unit)
      for (int k = 0; k < n; ++k) {
        const int i = index ? index[k] : begin + k;
        const float* rows = U + 3 * std::size_t(stride) * std::size_t(i);
        for (int c = 0; c < 3; ++c) {
          float s = 0;
          for (int j = 0; j < r; ++j) s += rows[c * stride + j] * q[j];
          out[c][k] = rest[c][i] + s;
        }
      }
      break;
  }
}

void DeformedPositionsImpl(const EmbeddedPoints& P, const float* rest_x, const float* rest_y, const float* rest_z,
                           const float* q, const std::int32_t* index, int begin, int n, float* x, float* y, float* z) {
  const float* rest[3] = {rest_x, rest_y, rest_z};
  float* out[3] = {x, y, z};
  AffineRows(P.basis_rows(), P.basis_stride(), P.r(), rest, q, index, begin, n, out);
}

void CorrectedNormalsImpl(const EmbeddedPoints& P, const float* rest_nx, const float* rest_ny, const float* rest_nz,
                          const float* q, const std::int32_t* index, int n, float* nx, float* ny, float* nz) {
  const float* rest[3] = {rest_nx, rest_ny, rest_nz};
  float* out[3] = {nx, ny, nz};
  AffineRows(P.normal_rows(), P.basis_stride(), P.r(), rest, q, index, 0, n, out);
  const DF d;
  using V = hn::Vec<DF>;
  int k = 0;
  for (; k + kLanes <= n; k += kLanes) {
    const V a = hn::LoadU(d, nx + k), b = hn::LoadU(d, ny + k), c = hn::LoadU(d, nz + k);
    const V len2 = hn::MulAdd(a, a, hn::MulAdd(b, b, hn::Mul(c, c)));
    const V inv = hn::IfThenElseZero(len2 > hn::Zero(d), hn::Set(d, 1.f) / hn::Sqrt(len2));
    hn::StoreU(hn::Mul(a, inv), d, nx + k);
    hn::StoreU(hn::Mul(b, inv), d, ny + k);
    hn::StoreU(hn::Mul(c, inv), d, nz + k);
  }
  for (; k < n; ++k) {
    const float len2 = nx[k] * nx[k] + ny[k] * ny[k] + nz[k] * nz[k];
    const float inv = len2 > 0 ? 1.f / std::sqrt(len2) : 0.f;
    nx[k] *= inv, ny[k] *= inv, nz[k] *= inv;
  }
}

void AddReducedPointSumsImpl(const EmbeddedPoints& P, const float* HWY_RESTRICT nx, const float* HWY_RESTRICT ny,
                             const float* HWY_RESTRICT nz, const std::int32_t* HWY_RESTRICT index,
                             const float* HWY_RESTRICT dist, int n, float* HWY_RESTRICT g_sum,
                             float* HWY_RESTRICT stiffness) {
  const DF d;
  using V = hn::Vec<DF>;
  const float* HWY_RESTRICT U = P.basis_rows();
  const int stride = P.basis_stride(), r = P.r();
  const int chunks = stride / kLanes;
  // w_k = U_i^T N_i of a group of up to kGroup points, one row each; the stiffness rows are
  // read and written once per group (a rank-kGroup update), not once per point.
  constexpr int kGroup = 8;
  alignas(64) float w[kGroup][kMaxBasisStride];
  for (int k0 = 0; k0 < n; k0 += kGroup) {
    const int count = std::min(kGroup, n - k0);
    for (int k = 0; k < count; ++k) {
      const std::int32_t i = index[k0 + k];
      const float* HWY_RESTRICT rows = U + 3 * std::size_t(stride) * std::size_t(i);
      const V n0 = hn::Set(d, nx[i]), n1 = hn::Set(d, ny[i]), n2 = hn::Set(d, nz[i]), dk = hn::Set(d, dist[k0 + k]);
      for (int m = 0; m < chunks; ++m) {
        const int o = m * kLanes;
        const V wm = hn::MulAdd(hn::Load(d, rows + o), n0,
                                hn::MulAdd(hn::Load(d, rows + stride + o), n1, hn::Mul(hn::Load(d, rows + 2 * stride + o), n2)));
        hn::Store(wm, d, w[k] + o);
        hn::StoreU(hn::MulAdd(dk, wm, hn::LoadU(d, g_sum + o)), d, g_sum + o);
      }
    }
    if (stiffness == nullptr) continue;
    for (int b = 0; b < r; ++b) {
      float* HWY_RESTRICT row = stiffness + std::size_t(b) * stride;
      for (int m = 0; m < chunks; ++m) {
        const int o = m * kLanes;
        V acc = hn::LoadU(d, row + o);
        for (int k = 0; k < count; ++k) acc = hn::MulAdd(hn::Set(d, w[k][b]), hn::Load(d, w[k] + o), acc);
        hn::StoreU(acc, d, row + o);
      }
    }
  }
}

float StreamRowsImpl(const EmbeddedPoints& P, const float* HWY_RESTRICT rest_x, const float* HWY_RESTRICT rest_y,
                     const float* HWY_RESTRICT rest_z, int n) {
  const DF d;
  using V = hn::Vec<DF>;
  const float* HWY_RESTRICT U = P.basis_rows();
  const std::size_t floats = 3 * std::size_t(P.basis_stride()) * std::size_t(n);
  V a0 = hn::Zero(d), a1 = a0, a2 = a0, a3 = a0;
  std::size_t f = 0;
  for (; f + 4 * kLanes <= floats; f += 4 * kLanes) {
    a0 = hn::Add(a0, hn::Load(d, U + f));
    a1 = hn::Add(a1, hn::Load(d, U + f + kLanes));
    a2 = hn::Add(a2, hn::Load(d, U + f + 2 * kLanes));
    a3 = hn::Add(a3, hn::Load(d, U + f + 3 * kLanes));
  }
  for (; f + kLanes <= floats; f += kLanes) a0 = hn::Add(a0, hn::Load(d, U + f));
  int k = 0;
  for (; k + kLanes <= n; k += kLanes) {
    a1 = hn::Add(a1, hn::LoadU(d, rest_x + k));
    a2 = hn::Add(a2, hn::LoadU(d, rest_y + k));
    a3 = hn::Add(a3, hn::LoadU(d, rest_z + k));
  }
  float sum = hn::GetLane(hn::SumOfLanes(d, hn::Add(hn::Add(a0, a1), hn::Add(a2, a3))));
  for (; k < n; ++k) sum += rest_x[k] + rest_y[k] + rest_z[k];
  return sum;
}

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace contactlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace contactlab {

HWY_EXPORT(DeformedPositionsImpl);
HWY_EXPORT(CorrectedNormalsImpl);
HWY_EXPORT(AddReducedPointSumsImpl);
HWY_EXPORT(StreamRowsImpl);
HWY_EXPORT(TargetName);

void DeformedPositions(const EmbeddedPoints& P, const float* rest_x, const float* rest_y, const float* rest_z,
                       const float* q, const std::int32_t* index, int begin, int n, float* x, float* y, float* z) {
  if (n <= 0) return;
  HWY_DYNAMIC_DISPATCH(DeformedPositionsImpl)(P, rest_x, rest_y, rest_z, q, index, begin, n, x, y, z);
}

void CorrectedNormals(const EmbeddedPoints& P, const float* rest_nx, const float* rest_ny, const float* rest_nz,
                      const float* q, const std::int32_t* index, int n, float* nx, float* ny, float* nz) {
  if (n <= 0) return;
  HWY_DYNAMIC_DISPATCH(CorrectedNormalsImpl)(P, rest_nx, rest_ny, rest_nz, q, index, n, nx, ny, nz);
}

void AddReducedPointSums(const EmbeddedPoints& P, const float* nx, const float* ny, const float* nz,
                         const std::int32_t* index, const float* d, int n, float* g_sum, float* stiffness) {
  if (n <= 0) return;
  HWY_DYNAMIC_DISPATCH(AddReducedPointSumsImpl)(P, nx, ny, nz, index, d, n, g_sum, stiffness);
}

float StreamPointRows(const EmbeddedPoints& P, const float* rest_x, const float* rest_y, const float* rest_z, int n) {
  return HWY_DYNAMIC_DISPATCH(StreamRowsImpl)(P, rest_x, rest_y, rest_z, n);
}

const char* ReducedPointBatchTarget() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }

}  // namespace contactlab
#endif
