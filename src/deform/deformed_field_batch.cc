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
  int slot_bits = 1;
  while ((1 << slot_bits) < field.num_slots() && slot_bits < 20) ++slot_bits;
  const VI low = hn::Set(di, (1 << slot_bits) - 1), high = hn::Not(low);
  const VI last_slot = hn::Set(di, field.num_slots() - 1);
  bool last_weighted = false;
  for (int b0 = 0; b0 < nb; b0 += kLanes) {  // NB is a whole number of vectors (padded by the caller)
    const VF px = hn::LoadU(df, x + b0), py = hn::LoadU(df, y + b0), pz = hn::LoadU(df, z + b0);
    // The sorted list as integer keys: a squared distance's bits (a non-negative float orders
    // as an integer) with the low SLOT_BITS replaced by the slot, so a candidate is carried
    // down the list by one min and one max per entry, and the list takes k registers, not 2k.
    VI key[k];
    for (int m = 0; m < k; ++m) key[m] = hn::Set(di, std::numeric_limits<std::int32_t>::max());
    for (int j = begin; j < end; ++j) {
      const VF dx = px - hn::Set(df, sx[j]), dy = py - hn::Set(df, sy[j]), dz = pz - hn::Set(df, sz[j]);
      const VF e = hn::MulAdd(dx, dx, hn::MulAdd(dy, dy, dz * dz));
      VI c = hn::Or(hn::And(hn::BitCast(di, e), high), hn::Set(di, j));
      if (hn::AllFalse(di, c < key[k - 1])) continue;  // nearer than no point's k-th: often so for a tree level's neighbours
      for (int m = 0; m < k; ++m) {
        const VI t = key[m];
        key[m] = hn::Min(t, c);
        c = hn::Max(t, c);
      }
    }
    // The chosen slots' exact squared distances (as the scan formed them). The keys order them
    // by distance to the bits the slot replaced and by slot within, so equal distances keep
    // the earlier slot first, as in the scalar scan; a pair whose distances differ only in
    // those bits may be out of order, and is sorted by (distance, slot) here.
    VF top[k], slot[k];
    for (int m = 0; m < k; ++m) {
      const VI sl = hn::Min(hn::And(key[m], low), last_slot);
      slot[m] = hn::BitCast(df, sl);
      const VF dx = px - hn::GatherIndex(df, sx, sl), dy = py - hn::GatherIndex(df, sy, sl),
               dz = pz - hn::GatherIndex(df, sz, sl);
      top[m] = hn::MulAdd(dx, dx, hn::MulAdd(dy, dy, dz * dz));
    }
    auto unordered = top[0] > top[1];
    for (int m = 1; m + 1 < k; ++m) unordered = hn::Or(unordered, top[m] > top[m + 1]);
    if (HWY_UNLIKELY(!hn::AllFalse(df, unordered))) {
      for (int pass = 0; pass < k; ++pass) {
        for (int m = pass % 2; m + 1 < k; m += 2) {
          const VI sa = hn::BitCast(di, slot[m]), sb = hn::BitCast(di, slot[m + 1]);
          const auto swap = hn::Or(top[m + 1] < top[m],
                                   hn::And(top[m + 1] == top[m], hn::RebindMask(df, sb < sa)));
          const VF ta = top[m], ua = slot[m];
          top[m] = hn::IfThenElse(swap, top[m + 1], ta);
          top[m + 1] = hn::IfThenElse(swap, ta, top[m + 1]);
          slot[m] = hn::IfThenElse(swap, slot[m + 1], ua);
          slot[m + 1] = hn::IfThenElse(swap, ua, slot[m + 1]);
        }
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
      const VI base = hn::BitCast(di, slot[m]) * hn::Set(di, 12);
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

// Domain DOM's distance at the NB points (X, Y, Z) (NB <= kBatch, padded by the caller to
// whole vectors) into SUM, and each point's nearest slot into S->first.
void DomainSums(const DeformedDistanceField& field, const DeformedFieldState& state, int dom, const float* x,
                const float* y, const float* z, int nb, Scratch* s, float* HWY_RESTRICT sum) {
  const int k = field.neighbours();  // every domain holds at least k slots (its construction)
  // Only the first k - 1 neighbours carry weight unless some point weighs its k-th (ties,
  // or points on a proxy): their lookups are skipped then.
  const int looked = NearestAndPullBacksFor(k, field, state, dom, x, y, z, nb, s) ? k : k - 1;
  const DistanceField& rest = field.domain_field(dom);
  if (nb == kBatch) {
    BatchDistances(rest, kIdentityTransform, s->px, s->py, s->pz, nullptr, looked * kBatch, s->looked);
  } else {
    for (int m = 0; m < looked; ++m) {
      BatchDistances(rest, kIdentityTransform, s->px + m * kBatch, s->py + m * kBatch, s->pz + m * kBatch, nullptr, nb,
                     s->looked + m * kBatch);
    }
  }
  // d = sum of w_m d_rest(X_m), skipping zero weights as the one-point query does.
  for (int b = 0; b < nb; ++b) {
    float total = 0;
    for (int m = 0; m < looked; ++m) {
      const float w = s->w[m * kBatch + b];
      if (w != 0.f) total += w * s->looked[m * kBatch + b];
    }
    sum[b] = total;
  }
}

// DeformedFieldDomainBounds (deformed_field_batch.h) for the NB points (X, Y, Z), NB a whole
// number of vectors.
void DomainBounds(const DeformedDistanceField& field, const DeformedFieldState& state, int dom, const float* x,
                  const float* y, const float* z, int nb, float* HWY_RESTRICT out) {
  const DF df;
  using VF = hn::Vec<DF>;
  auto c = [&](float v) HWY_ATTR { return hn::Set(df, v); };
  const DeformedFieldState::DomainBound& bd = state.domain_bound(dom);
  const DomainLevels& lv = field.domain_levels(dom);
  const DistanceField::FloatGrid g = field.domain_field(dom).float_grid();
  const VF zero = hn::Zero(df), ninf = c(-std::numeric_limits<float>::infinity());
  const float margin = 1e-4f / g.inv_h;
  for (int b0 = 0; b0 < nb; b0 += kLanes) {
    const VF px = hn::LoadU(df, x + b0), py = hn::LoadU(df, y + b0), pz = hn::LoadU(df, z + b0);
    const VF X = c(bd.c[0]) + c(bd.a[0]) * px + c(bd.a[1]) * py + c(bd.a[2]) * pz;
    const VF Y = c(bd.c[1]) + c(bd.a[3]) * px + c(bd.a[4]) * py + c(bd.a[5]) * pz;
    const VF Z = c(bd.c[2]) + c(bd.a[6]) * px + c(bd.a[7]) * py + c(bd.a[8]) * pz;
    const VF ex = px - c(bd.o[0]), ey = py - c(bd.o[1]), ez = pz - c(bd.o[2]);
    const VF rho = c(bd.spread) + c(bd.slope) * hn::Sqrt(ex * ex + ey * ey + ez * ez);
    auto box_distance = [&](float lx, float ly, float lz, float hx, float hy, float hz) HWY_ATTR {
      const VF dx = hn::Max(hn::Max(c(lx) - X, X - c(hx)), zero);
      const VF dy = hn::Max(hn::Max(c(ly) - Y, Y - c(hy)), zero);
      const VF dz = hn::Max(hn::Max(c(lz) - Z, Z - c(hz)), zero);
      return hn::Sqrt(dx * dx + dy * dy + dz * dz);
    };
    const VF t = box_distance(g.ox, g.oy, g.oz, g.x1, g.y1, g.z1) - rho;
    const VF v = t + c(g.boundary_min);
    VF bound = hn::IfThenElse(t > zero, v - c(1e-5f) * hn::Abs(v) - c(margin), ninf);
    for (int j = 0; j < lv.count; ++j) {
      const VF outside = box_distance(lv.lo[j][0], lv.lo[j][1], lv.lo[j][2], lv.hi[j][0], lv.hi[j][1], lv.hi[j][2]);
      const float tau = lv.tau[j] - 1e-5f * std::abs(lv.tau[j]) - margin;
      bound = hn::IfThenElse(outside > rho, hn::Max(bound, c(tau)), bound);
    }
    hn::StoreU(bound, df, out + b0);
  }
}

// Copies the NB points from B0 of (X, Y, Z) to (PX, PY, PZ), padded to whole vectors by
// repeating the last (lanes past the last point repeat it); returns the padded count.
int CopyBatch(const float* x, const float* y, const float* z, int b0, int nb, float* px, float* py, float* pz) {
  const int padded = (nb + kLanes - 1) / kLanes * kLanes;
  for (int b = 0; b < padded; ++b) {
    const int i = b0 + std::min(b, nb - 1);
    px[b] = x[i], py[b] = y[i], pz[b] = z[i];
  }
  return padded;
}

void DeformedFieldDomainBoundsImpl(const DeformedDistanceField& field, const DeformedFieldState& state, int dom,
                                   const float* x, const float* y, const float* z, int n, float* out) {
  alignas(64) float px[kBatch], py[kBatch], pz[kBatch], bound[kBatch];
  for (int b0 = 0; b0 < n; b0 += kBatch) {
    const int nb = std::min(kBatch, n - b0);
    const int padded = CopyBatch(x, y, z, b0, nb, px, py, pz);
    DomainBounds(field, state, dom, px, py, pz, padded, bound);
    std::copy(bound, bound + nb, out + b0);
  }
}

// Copies the points IDX[0, M) of (X, Y, Z) to (CX, CY, CZ), padded to whole vectors by
// repeating the last; returns the padded count.
int Gather(const int* idx, int m, const float* x, const float* y, const float* z, float* cx, float* cy, float* cz) {
  const int padded = (m + kLanes - 1) / kLanes * kLanes;
  for (int j = 0; j < padded; ++j) {
    const int b = idx[std::min(j, m - 1)];
    cx[j] = x[b], cy[j] = y[b], cz[j] = z[b];
  }
  return padded;
}

std::int64_t DeformedFieldDistancesImpl(const DeformedDistanceField& field, const DeformedFieldState& state,
                                        const float* HWY_RESTRICT x, const float* HWY_RESTRICT y,
                                        const float* HWY_RESTRICT z, int n, float* HWY_RESTRICT d,
                                        std::int32_t* HWY_RESTRICT nearest) {
  const int domains = field.num_domains();
  Scratch s;
  alignas(64) float bx[kBatch], by[kBatch], bz[kBatch], best[kBatch], sum[kBatch];
  alignas(64) float cx[kBatch], cy[kBatch], cz[kBatch], bound[kBatch], home_bound[kBatch];
  alignas(64) std::int32_t best_slot[kBatch], best_domain[kBatch], home[kBatch];
  int idx[kBatch];
  std::int64_t answered = 0;
  for (int b0 = 0; b0 < n; b0 += kBatch) {
    const int nb = std::min(kBatch, n - b0);
    const int padded = CopyBatch(x, y, z, b0, nb, bx, by, bz);
    for (int b = 0; b < padded; ++b) {
      best[b] = std::numeric_limits<float>::infinity();
      best_slot[b] = -1;
      best_domain[b] = domains;
    }
    // Domain DOM's distances SUM at the points IDX[0, M): kept where smaller than the best so
    // far, or equal and from an earlier domain (the one-point query keeps the first smallest).
    auto keep = [&](int dom, int m) {
      for (int j = 0; j < m; ++j) {
        const int b = idx[j];
        if (sum[j] < best[b] || (sum[j] == best[b] && dom < best_domain[b])) {
          best[b] = sum[j];
          best_slot[b] = s.first[j];
          best_domain[b] = dom;
        }
      }
      answered += m;
    };
    // Domain DOM at the points IDX[0, M), gathered into whole vectors.
    auto answer = [&](int dom, int m) {
      if (m == 0) return;
      DomainSums(field, state, dom, cx, cy, cz, Gather(idx, m, bx, by, bz, cx, cy, cz), &s, sum);
      keep(dom, m);
    };
    if (domains == 1) {
      for (int b = 0; b < nb; ++b) idx[b] = b;
      DomainSums(field, state, 0, bx, by, bz, padded, &s, sum);
      keep(0, nb);
    } else {
      // Branch and bound over the domains: each point is first answered by the domain with the
      // smallest lower bound, then by each other domain whose bound does not exceed the
      // distance it has.
      for (int b = 0; b < padded; ++b) home[b] = 0, home_bound[b] = std::numeric_limits<float>::infinity();
      for (int dom = 0; dom < domains; ++dom) {
        DomainBounds(field, state, dom, bx, by, bz, padded, bound);
        for (int b = 0; b < nb; ++b) {
          if (bound[b] < home_bound[b]) home_bound[b] = bound[b], home[b] = dom;
        }
      }
      for (int dom = 0; dom < domains; ++dom) {
        int m = 0;
        for (int b = 0; b < nb; ++b) {
          if (home[b] == dom) idx[m++] = b;
        }
        answer(dom, m);
      }
      for (int dom = 0; dom < domains; ++dom) {
        DomainBounds(field, state, dom, bx, by, bz, padded, bound);
        int m = 0;
        for (int b = 0; b < nb; ++b) {
          if (home[b] != dom && !(bound[b] > best[b])) idx[m++] = b;
        }
        answer(dom, m);
      }
    }
    for (int b = 0; b < nb; ++b) d[b0 + b] = best[b];
    if (nearest != nullptr) {
      for (int b = 0; b < nb; ++b) nearest[b0 + b] = best_slot[b];
    }
  }
  return answered;
}

}  // namespace HWY_NAMESPACE
}  // namespace contactlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace contactlab {

HWY_EXPORT(DeformedFieldDistancesImpl);
HWY_EXPORT(DeformedFieldDomainBoundsImpl);

void DeformedFieldDomainBounds(const DeformedDistanceField& field, const DeformedFieldState& state, int dom,
                               const float* x, const float* y, const float* z, int n, float* out) {
  if (n <= 0) return;
  HWY_DYNAMIC_DISPATCH(DeformedFieldDomainBoundsImpl)(field, state, dom, x, y, z, n, out);
}

std::int64_t DeformedFieldDistances(const DeformedDistanceField& field, const DeformedFieldState& state,
                                    const float* x, const float* y, const float* z, int n, float* d,
                                    std::int32_t* nearest) {
  if (n <= 0) return 0;
  return HWY_DYNAMIC_DISPATCH(DeformedFieldDistancesImpl)(field, state, x, y, z, n, d, nearest);
}

}  // namespace contactlab
#endif
