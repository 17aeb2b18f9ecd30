// DeformedFieldDistances for each instruction set Highway compiles (this file is included once
// per target by foreach_target.h), and the run-time dispatch between them.
#include "deform/deformed_field_batch.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sdf/batch_distance.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "deform/deformed_field_batch.cc"
#include <hwy/foreach_target.h>  // NOLINT: re-includes this file per target
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace contactlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::CappedTag<float, 8>;
using DI = hn::RebindToSigned<DF>;
constexpr int kLanes = int(hn::MaxLanes(DF()));
// Points per batch: the k pulled-back points of kBatch points are looked up together.
constexpr int kBatch = 64;
static_assert(kBatch % kLanes == 0);

struct Scratch {
  float px[kMaxProxyNeighbours * kBatch], py[kMaxProxyNeighbours * kBatch], pz[kMaxProxyNeighbours * kBatch];
  float w[kMaxProxyNeighbours * kBatch];       // weight m of point b at [m kBatch + b]
  float looked[kMaxProxyNeighbours * kBatch];  // the rest-field distance there
  std::int32_t first[kBatch];                  // nearest slot of each point
};

// Domain DOM's part of points [0, NB) of a batch at (X, Y, Z): fills S with the pulled-back
// points and weights of each point's K nearest slots, nearest first. K is a template argument
// so the sorted list stays in registers. Returns whether any point weights its K-th slot.
template <int k>
bool NearestAndPullBacks(const DeformedDistanceField& field, const DeformedFieldState& state, int dom,
                         const float* HWY_RESTRICT x, const float* HWY_RESTRICT y, const float* HWY_RESTRICT z, int nb,
                         Scratch* HWY_RESTRICT s) {
  const DF df;
  const DI di;
  using VF = hn::Vec<DF>;
  using VI = hn::Vec<DI>;
  const float* HWY_RESTRICT sx = state.xs();
  const float* HWY_RESTRICT sy = state.ys();
  const float* HWY_RESTRICT sz = state.zs();
  const float* HWY_RESTRICT a = state.pullback(0);
  const int begin = field.slot_begin(dom), end = field.slot_end(dom);
  const VF inf = hn::Set(df, std::numeric_limits<float>::infinity()), zero = hn::Zero(df), one = hn::Set(df, 1.f);
  bool last_weighted = false;
  for (int b0 = 0; b0 < nb; b0 += kLanes) {  // NB is a whole number of vectors (padded by the caller)
    const VF px = hn::LoadU(df, x + b0), py = hn::LoadU(df, y + b0), pz = hn::LoadU(df, z + b0);
    // The sorted list: squared distances and slots (as float bit patterns, so one float mask
    // blends both).
    VF top[k], slot[k];
    for (int m = 0; m < k; ++m) top[m] = inf, slot[m] = hn::BitCast(df, hn::Set(di, -1));
    // The domain's slots in order; a nearer one is carried down the sorted list (strictly
    // nearer only, so of equal distances the earlier slot stays first, as in the scalar scan).
    for (int j = begin; j < end; ++j) {
      const VF dx = px - hn::Set(df, sx[j]), dy = py - hn::Set(df, sy[j]), dz = pz - hn::Set(df, sz[j]);
      VF e = hn::MulAdd(dx, dx, hn::MulAdd(dy, dy, dz * dz));
      if (hn::AllFalse(df, e < top[k - 1])) continue;  // nearer than no point's k-th: often so for a tree level's neighbours
      VF c = hn::BitCast(df, hn::Set(di, j));
      for (int m = 0; m < k; ++m) {
        const auto nearer = e < top[m];
        const VF t = top[m], u = slot[m];
        top[m] = hn::IfThenElse(nearer, e, t);
        e = hn::IfThenElse(nearer, t, e);
        slot[m] = hn::IfThenElse(nearer, c, u);
        c = hn::IfThenElse(nearer, u, c);
      }
    }
    // w_m ~ 1/d_m - 1/d_max (eq. (3)), clamped at zero, normalised; all equidistant (or the
    // point on a proxy): equal weights on those at the nearest distance.
    VF dist[k], w[k];
    for (int m = 0; m < k; ++m) dist[m] = hn::Sqrt(top[m]);
    const VF dmax = dist[k - 1];
    const VF inv_max = hn::IfThenElseZero(dmax > zero, one / dmax);
    VF W = zero;
    for (int m = 0; m < k; ++m) {
      const VF inv = hn::IfThenElse(dist[m] > hn::Set(df, 1e-20f), one / dist[m], hn::Set(df, 1e20f));
      w[m] = inv - inv_max;
      w[m] = hn::IfThenElseZero(w[m] > zero, w[m]);
      W = W + w[m];
    }
    const auto degenerate = hn::Not(hn::And(W > zero, W < inf));
    if (!hn::AllFalse(df, degenerate)) {
      VF count = zero;
      for (int m = 0; m < k; ++m) {
        const VF e = hn::IfThenElseZero(top[m] <= top[0], one);
        w[m] = hn::IfThenElse(degenerate, e, w[m]);
        count = count + e;
      }
      W = hn::IfThenElse(degenerate, count, W);
    }
    const VF inv_W = one / W;
    // The pull-backs X = c + A x through each chosen slot's affine map (12 floats a slot). The
    // k-th weight is zero but where all k are equidistant: only then is its point pulled back
    // (elsewhere it keeps the query point, a valid lookup that is never weighted).
    for (int m = 0; m < k; ++m) {
      const VF wm = w[m] * inv_W;
      hn::StoreU(wm, df, s->w + m * kBatch + b0);
      if (m == k - 1 && hn::AllTrue(df, wm == zero)) {
        hn::StoreU(px, df, s->px + m * kBatch + b0);
        hn::StoreU(py, df, s->py + m * kBatch + b0);
        hn::StoreU(pz, df, s->pz + m * kBatch + b0);
        continue;
      }
      if (m == k - 1) last_weighted = true;
      const VI base = hn::Max(hn::BitCast(di, slot[m]), hn::Zero(di)) * hn::Set(di, 12);  // -1 (a NaN point): slot 0
      auto coef = [&](int e) HWY_ATTR { return hn::GatherIndex(df, a + e, base); };
      const VF X = hn::MulAdd(coef(0), px, hn::MulAdd(coef(1), py, hn::MulAdd(coef(2), pz, coef(9))));
      const VF Y = hn::MulAdd(coef(3), px, hn::MulAdd(coef(4), py, hn::MulAdd(coef(5), pz, coef(10))));
      const VF Z = hn::MulAdd(coef(6), px, hn::MulAdd(coef(7), py, hn::MulAdd(coef(8), pz, coef(11))));
      hn::StoreU(X, df, s->px + m * kBatch + b0);
      hn::StoreU(Y, df, s->py + m * kBatch + b0);
      hn::StoreU(Z, df, s->pz + m * kBatch + b0);
    }
    hn::StoreU(hn::BitCast(di, slot[0]), di, s->first + b0);
  }
  return last_weighted;
}

bool NearestAndPullBacksFor(int k, const DeformedDistanceField& field, const DeformedFieldState& state, int dom,
                            const float* x, const float* y, const float* z, int nb, Scratch* s) {
  static_assert(kMaxProxyNeighbours == 16);
  switch (k) {
#define CONTACTLAB_K(K) \
  case K:               \
    return NearestAndPullBacks<K>(field, state, dom, x, y, z, nb, s);
    CONTACTLAB_K(2)
    CONTACTLAB_K(3)
    CONTACTLAB_K(4)
    CONTACTLAB_K(5)
    CONTACTLAB_K(6)
    CONTACTLAB_K(7)
    CONTACTLAB_K(8)
    CONTACTLAB_K(9)
    CONTACTLAB_K(10)
    CONTACTLAB_K(11)
    CONTACTLAB_K(12)
    CONTACTLAB_K(13)
    CONTACTLAB_K(14)
    CONTACTLAB_K(15)
    CONTACTLAB_K(16)
#undef CONTACTLAB_K
    default:
      break;  // k is checked in [2, kMaxProxyNeighbours] when the field is built
  }
  return false;
}

void DeformedFieldDistancesImpl(const DeformedDistanceField& field, const DeformedFieldState& state,
                                const float* HWY_RESTRICT x, const float* HWY_RESTRICT y,
                                const float* HWY_RESTRICT z, int n, float* HWY_RESTRICT d,
                                std::int32_t* HWY_RESTRICT nearest) {
  const int k = field.neighbours();  // every domain holds at least k slots (its construction)
  const BatchTransform identity{{1, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 0, 0}};
  Scratch s;
  alignas(64) float bx[kBatch], by[kBatch], bz[kBatch], best[kBatch];
  alignas(64) std::int32_t best_slot[kBatch];
  for (int b0 = 0; b0 < n; b0 += kBatch) {
    const int nb = std::min(kBatch, n - b0);
    const int padded = (nb + kLanes - 1) / kLanes * kLanes;
    for (int b = 0; b < padded; ++b) {  // lanes past the last point repeat it
      const int i = b0 + std::min(b, nb - 1);
      bx[b] = x[i], by[b] = y[i], bz[b] = z[i];
      best[b] = std::numeric_limits<float>::infinity();
      best_slot[b] = -1;
    }
    for (int dom = 0; dom < field.num_domains(); ++dom) {
      // The lookups of the weighted neighbours: the first k - 1, the k-th only when some point
      // weights it.
      const int looked = NearestAndPullBacksFor(k, field, state, dom, bx, by, bz, padded, &s) ? k : k - 1;
      const DistanceField& rest = field.domain_field(dom);
      if (padded == kBatch) {
        BatchDistances(rest, identity, s.px, s.py, s.pz, nullptr, looked * kBatch, s.looked);
      } else {
        for (int m = 0; m < looked; ++m) {
          BatchDistances(rest, identity, s.px + m * kBatch, s.py + m * kBatch, s.pz + m * kBatch, nullptr, padded,
                         s.looked + m * kBatch);
        }
      }
      // d = sum_m w_m d_rest(X_m), a zero weight adding nothing (even where d_rest is infinite).
      for (int b = 0; b < padded; ++b) {
        float sum = 0;
        for (int m = 0; m < looked; ++m) {
          const float w = s.w[m * kBatch + b];
          if (w != 0.f) sum += w * s.looked[m * kBatch + b];
        }
        if (sum < best[b]) {
          best[b] = sum;
          best_slot[b] = s.first[b];
        }
      }
    }
    for (int b = 0; b < nb; ++b) d[b0 + b] = best[b];
    if (nearest != nullptr) {
      for (int b = 0; b < nb; ++b) nearest[b0 + b] = best_slot[b];
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace contactlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace contactlab {

HWY_EXPORT(DeformedFieldDistancesImpl);

void DeformedFieldDistances(const DeformedDistanceField& field, const DeformedFieldState& state, const float* x,
                            const float* y, const float* z, int n, float* d, std::int32_t* nearest) {
  if (n <= 0) return;
  HWY_DYNAMIC_DISPATCH(DeformedFieldDistancesImpl)(field, state, x, y, z, n, d, nearest);
}

}  // namespace contactlab
#endif
