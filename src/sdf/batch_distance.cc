// BatchDistances for each instruction set Highway compiles (this file is included once per
// target by foreach_target.h), and the run-time dispatch between them.
#include "sdf/batch_distance.h"

#include "sdf/sparse_field.h"

#include <algorithm>
#include <limits>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sdf/batch_distance.cc"
#include <hwy/foreach_target.h>  // NOLINT: re-includes this file per target
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace contactlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Trilinear interpolation of the corner values V (bit order x, y, z) at T in [0, 1]^3.
template <class VF>
HWY_INLINE VF Trilinear(VF tx, VF ty, VF tz, VF v000, VF v100, VF v010, VF v110, VF v001, VF v101, VF v011, VF v111) {
  const VF c00 = hn::MulAdd(tx, v100 - v000, v000);
  const VF c10 = hn::MulAdd(tx, v110 - v010, v010);
  const VF c01 = hn::MulAdd(tx, v101 - v001, v001);
  const VF c11 = hn::MulAdd(tx, v111 - v011, v011);
  const VF c0 = hn::MulAdd(ty, c10 - c00, c00);
  const VF c1 = hn::MulAdd(ty, c11 - c01, c01);
  return hn::MulAdd(tz, c1 - c0, c0);
}

// What the vector lookups read of a sparse field (sdf/sparse_field.h): brick slots, 16-bit
// samples read in x-pairs as 32-bit words, coarse cells and their bounds. Zeros for a dense one.
struct SparseView {
  explicit SparseView(const SparseFieldStorage* sp)
      : slots(sp ? sp->slot.data() : nullptr),
        words(sp ? reinterpret_cast<const std::int32_t*>(sp->samples.data()) : nullptr),
        coarse(sp ? sp->coarse.data() : nullptr),
        nbx(sp ? sp->bricks.x() : 0),
        nby(sp ? sp->bricks.y() : 0),
        ocy(sp ? sp->bricks.x() + 1 : 0),
        ocz(sp ? (sp->bricks.x() + 1) * (sp->bricks.y() + 1) : 0),
        quantum(sp ? sp->quantum : 0.f),
        coarse_h(sp ? sp->coarse_spacing : 0.f),
        band_floor(sp ? sp->floor : 0.f),
        margin(sp ? sp->margin : 0.f) {}

  const std::int32_t* slots;
  const std::int32_t* words;
  const float* coarse;
  std::int32_t nbx, nby;  // bricks along x and y
  std::int32_t ocy, ocz;  // coarse-sample strides of y and z
  float quantum, coarse_h, band_floor, margin;
};

// Fine cells (CI, CJ, CK) at fine coordinates (GX, GY, GZ) of a sparse field, for the lanes
// INSIDE the box: a stored brick's samples, or else the bounds of its coarse cell.
template <class DF, class DI>
HWY_INLINE hn::Vec<DF> SparseCellLookup(DF df, DI di, const SparseView& sp, hn::Vec<DF> gx, hn::Vec<DF> gy,
                                        hn::Vec<DF> gz, hn::Vec<DI> ci, hn::Vec<DI> cj, hn::Vec<DI> ck,
                                        hn::Mask<DF> inside) {
  using VF = hn::Vec<DF>;
  using VI = hn::Vec<DI>;
  constexpr int kE = SparseFieldStorage::kBrickEdge;
  const VF zero = hn::Zero(df);
  const VI bi = hn::ShiftRight<3>(ci), bj = hn::ShiftRight<3>(cj), bk = hn::ShiftRight<3>(ck);
  const VI s = hn::GatherIndex(di, sp.slots, bi + hn::Set(di, sp.nbx) * (bj + hn::Set(di, sp.nby) * bk));
  const auto stored = hn::RebindMask(df, s > hn::Set(di, -1));
  VF result = zero;
  if (!hn::AllFalse(df, hn::And(stored, inside))) {
    // Word offsets in bytes: sample e and e + 1 share a 32-bit load (little-endian).
    const VI seven = hn::Set(di, 7);
    const VI e = hn::Max(s, hn::Zero(di)) * hn::Set(di, SparseFieldStorage::kBrickStride) + (ci & seven) +
                 hn::Set(di, kE) * ((cj & seven) + hn::Set(di, kE) * (ck & seven));
    const VI off = hn::ShiftLeft<1>(e);
    const VI w0 = hn::GatherOffset(di, sp.words, off);
    const VI w1 = hn::GatherOffset(di, sp.words, off + hn::Set(di, 2 * kE));
    const VI w2 = hn::GatherOffset(di, sp.words, off + hn::Set(di, 2 * kE * kE));
    const VI w3 = hn::GatherOffset(di, sp.words, off + hn::Set(di, 2 * (kE * kE + kE)));
    auto lo = [&](VI w) HWY_ATTR { return hn::ConvertTo(df, hn::ShiftRight<16>(hn::ShiftLeft<16>(w))); };
    auto hi = [&](VI w) HWY_ATTR { return hn::ConvertTo(df, hn::ShiftRight<16>(w)); };
    const VF tx = gx - hn::ConvertTo(df, ci), ty = gy - hn::ConvertTo(df, cj), tz = gz - hn::ConvertTo(df, ck);
    result = Trilinear(tx, ty, tz, lo(w0), hi(w0), lo(w1), hi(w1), lo(w2), hi(w2), lo(w3), hi(w3)) *
             hn::Set(df, sp.quantum);
  }
  if (!hn::AllFalse(df, hn::AndNot(stored, inside))) {
    // The coarse cell is the brick; its samples are 8 fine spacings apart.
    const VF eighth = hn::Set(df, 0.125f), one = hn::Set(df, 1.f), coarse_h = hn::Set(df, sp.coarse_h);
    const VF band_floor = hn::Set(df, sp.band_floor);
    const std::int32_t ocy = sp.ocy, ocz = sp.ocz;
    const float* coarse = sp.coarse;
    const VF tx = (gx - hn::ConvertTo(df, hn::ShiftLeft<3>(bi))) * eighth;
    const VF ty = (gy - hn::ConvertTo(df, hn::ShiftLeft<3>(bj))) * eighth;
    const VF tz = (gz - hn::ConvertTo(df, hn::ShiftLeft<3>(bk))) * eighth;
    const VI base = bi + hn::Set(di, ocy) * bj + hn::Set(di, ocz) * bk;
    const VF c000 = hn::GatherIndex(df, coarse, base), c100 = hn::GatherIndex(df, coarse + 1, base);
    const VF c010 = hn::GatherIndex(df, coarse + ocy, base), c110 = hn::GatherIndex(df, coarse + ocy + 1, base);
    const VF c001 = hn::GatherIndex(df, coarse + ocz, base), c101 = hn::GatherIndex(df, coarse + ocz + 1, base);
    const VF c011 = hn::GatherIndex(df, coarse + ocz + ocy, base);
    const VF c111 = hn::GatherIndex(df, coarse + ocz + ocy + 1, base);
    const VF d = Trilinear(tx, ty, tz, c000, c100, c010, c110, c001, c101, c011, c111);
    // Outside: the interpolant less the margin, or a corner's value less its distance.
    const VF ux = one - tx, uy = one - ty, uz = one - tz;
    const VF x0 = tx * tx, x1 = ux * ux, y0 = ty * ty, y1 = uy * uy, z0 = tz * tz, z1 = uz * uz;
    VF lip = hn::Max(band_floor, d - hn::Set(df, sp.margin));
    lip = hn::Max(lip, c000 - coarse_h * hn::Sqrt(x0 + y0 + z0));
    lip = hn::Max(lip, c100 - coarse_h * hn::Sqrt(x1 + y0 + z0));
    lip = hn::Max(lip, c010 - coarse_h * hn::Sqrt(x0 + y1 + z0));
    lip = hn::Max(lip, c110 - coarse_h * hn::Sqrt(x1 + y1 + z0));
    lip = hn::Max(lip, c001 - coarse_h * hn::Sqrt(x0 + y0 + z1));
    lip = hn::Max(lip, c101 - coarse_h * hn::Sqrt(x1 + y0 + z1));
    lip = hn::Max(lip, c011 - coarse_h * hn::Sqrt(x0 + y1 + z1));
    lip = hn::Max(lip, c111 - coarse_h * hn::Sqrt(x1 + y1 + z1));
    const auto out = hn::RebindMask(df, s == hn::Set(di, SparseFieldStorage::kOutside));
    const VF bounded = hn::IfThenElse(out, lip, hn::Min(hn::Neg(band_floor), d));
    result = hn::IfThenElse(stored, result, bounded);
  }
  return result;
}

// Fine cells (CI, CJ, CK) at fine coordinates (GX, GY, GZ) of a dense field G: the trilinear
// interpolant of the cell's eight samples.
template <class DF, class DI>
HWY_INLINE hn::Vec<DF> DenseCellLookup(DF df, DI di, const DistanceField::FloatGrid& g, hn::Vec<DF> gx,
                                       hn::Vec<DF> gy, hn::Vec<DF> gz, hn::Vec<DI> ci, hn::Vec<DI> cj, hn::Vec<DI> ck) {
  using VF = hn::Vec<DF>;
  const VF tx = gx - hn::ConvertTo(df, ci), ty = gy - hn::ConvertTo(df, cj), tz = gz - hn::ConvertTo(df, ck);
  const auto base = ci + hn::Set(di, g.nx) * cj + hn::Set(di, g.nx * g.ny) * ck;
  const std::int32_t oxy = g.nx, oxz = g.nx * g.ny;
  const float* v = g.values;
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX2
  // Corners i and i + 1 are adjacent: one 64-bit load fetches both, so four gathers of
  // half-width vectors per half replace eight full ones; the pairs are then split.
  const hn::Half<DI> dh;
  const hn::Repartition<std::int64_t, DF> dl;
  const hn::Repartition<double, DF> dd;
  const auto off_lo = hn::ShiftLeft<2>(hn::PromoteTo(dl, hn::LowerHalf(dh, base)));
  const auto off_hi = hn::ShiftLeft<2>(hn::PromoteTo(dl, hn::UpperHalf(dh, base)));
  VF pair_lo, pair_hi;
  auto pairs = [&](const float* p) HWY_ATTR {
    const double* q = reinterpret_cast<const double*>(p);
    pair_lo = hn::BitCast(df, hn::GatherOffset(dd, q, off_lo));
    pair_hi = hn::BitCast(df, hn::GatherOffset(dd, q, off_hi));
  };
  pairs(v);
  const VF v000 = hn::ConcatEven(df, pair_hi, pair_lo), v100 = hn::ConcatOdd(df, pair_hi, pair_lo);
  pairs(v + oxy);
  const VF v010 = hn::ConcatEven(df, pair_hi, pair_lo), v110 = hn::ConcatOdd(df, pair_hi, pair_lo);
  pairs(v + oxz);
  const VF v001 = hn::ConcatEven(df, pair_hi, pair_lo), v101 = hn::ConcatOdd(df, pair_hi, pair_lo);
  pairs(v + oxz + oxy);
  const VF v011 = hn::ConcatEven(df, pair_hi, pair_lo), v111 = hn::ConcatOdd(df, pair_hi, pair_lo);
#else
  const VF v000 = hn::GatherIndex(df, v, base);
  const VF v100 = hn::GatherIndex(df, v + 1, base);
  const VF v010 = hn::GatherIndex(df, v + oxy, base);
  const VF v110 = hn::GatherIndex(df, v + oxy + 1, base);
  const VF v001 = hn::GatherIndex(df, v + oxz, base);
  const VF v101 = hn::GatherIndex(df, v + oxz + 1, base);
  const VF v011 = hn::GatherIndex(df, v + oxz + oxy, base);
  const VF v111 = hn::GatherIndex(df, v + oxz + oxy + 1, base);
#endif
  return Trilinear(tx, ty, tz, v000, v100, v010, v110, v001, v101, v011, v111);
}

// One vector of points (PX, PY, PZ) in A's frame -> their distances in the field G (B's frame),
// X taking A's frame to B's. Dense and sparse storage compile to separate code (KSPARSE).
template <bool kSparse, class DF>
HWY_INLINE hn::Vec<DF> DistancesOfVector(DF df, const BatchTransform& X, const DistanceField::FloatGrid& g,
                                         const SparseView& sp, hn::Vec<DF> px, hn::Vec<DF> py, hn::Vec<DF> pz) {
  using VF = hn::Vec<DF>;
  const hn::RebindToSigned<DF> di;
  const VF zero = hn::Zero(df);
  // The points in B's frame.
  const VF r0 = hn::Set(df, X.r[0]), r1 = hn::Set(df, X.r[1]), r2 = hn::Set(df, X.r[2]);
  const VF r3 = hn::Set(df, X.r[3]), r4 = hn::Set(df, X.r[4]), r5 = hn::Set(df, X.r[5]);
  const VF r6 = hn::Set(df, X.r[6]), r7 = hn::Set(df, X.r[7]), r8 = hn::Set(df, X.r[8]);
  const VF t0 = hn::Set(df, X.t[0]), t1 = hn::Set(df, X.t[1]), t2 = hn::Set(df, X.t[2]);
  const VF bx = hn::MulAdd(r0, px, hn::MulAdd(r1, py, hn::MulAdd(r2, pz, t0)));
  const VF by = hn::MulAdd(r3, px, hn::MulAdd(r4, py, hn::MulAdd(r5, pz, t1)));
  const VF bz = hn::MulAdd(r6, px, hn::MulAdd(r7, py, hn::MulAdd(r8, pz, t2)));
  // Outside the box: the conservative bound of Fig. 5(c); a NaN or infinite point: +inf.
  const VF ox = hn::Set(df, g.ox), oy = hn::Set(df, g.oy), oz = hn::Set(df, g.oz);
  const VF dx = hn::Max(hn::Max(ox - bx, bx - hn::Set(df, g.x1)), zero);
  const VF dy = hn::Max(hn::Max(oy - by, by - hn::Set(df, g.y1)), zero);
  const VF dz = hn::Max(hn::Max(oz - bz, bz - hn::Set(df, g.z1)), zero);
  const VF outside = hn::Sqrt(hn::MulAdd(dx, dx, hn::MulAdd(dy, dy, dz * dz))) + hn::Set(df, g.boundary_min);
  const VF inf = hn::Set(df, std::numeric_limits<float>::infinity());
  const auto finite = (hn::Abs(bx) + hn::Abs(by) + hn::Abs(bz)) < inf;
  VF result = hn::IfThenElse(finite, outside, inf);

  // Inside the box: grid coordinates, the lanes outside it at cell 0 (a valid address, then
  // discarded). The last grid plane uses the last cell with t = 1.
  const VF inv_h = hn::Set(df, g.inv_h);
  VF gx = (bx - ox) * inv_h, gy = (by - oy) * inv_h, gz = (bz - oz) * inv_h;
  const auto inside = hn::And(hn::And(hn::And(gx >= zero, gy >= zero), hn::And(gz >= zero, gx <= hn::Set(df, g.ex))),
                              hn::And(gy <= hn::Set(df, g.ey), gz <= hn::Set(df, g.ez)));
  if (hn::AllFalse(df, inside)) return result;
  gx = hn::IfThenElseZero(inside, gx);
  gy = hn::IfThenElseZero(inside, gy);
  gz = hn::IfThenElseZero(inside, gz);
  const auto ci = hn::Min(hn::ConvertTo(di, gx), hn::Set(di, g.nx - 2));
  const auto cj = hn::Min(hn::ConvertTo(di, gy), hn::Set(di, g.ny - 2));
  const auto ck = hn::Min(hn::ConvertTo(di, gz), hn::Set(di, g.nz - 2));
  if constexpr (kSparse) {
    return hn::IfThenElse(inside, SparseCellLookup(df, di, sp, gx, gy, gz, ci, cj, ck, inside), result);
  } else {
    return hn::IfThenElse(inside, DenseCellLookup(df, di, g, gx, gy, gz, ci, cj, ck), result);
  }
}

template <bool kSparse>
void BatchDistancesOf(const DistanceField& field, const BatchTransform& X, const float* HWY_RESTRICT x,
                      const float* HWY_RESTRICT y, const float* HWY_RESTRICT z,
                      const std::int32_t* HWY_RESTRICT index, int n, float* HWY_RESTRICT d) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  using VF = hn::Vec<decltype(df)>;
  using VI = hn::Vec<decltype(di)>;
  const int lanes = int(hn::Lanes(df));
  if (field.empty()) {  // never in contact, as Distance
    for (int k = 0; k < n; ++k) d[k] = std::numeric_limits<float>::infinity();
    return;
  }
  const DistanceField::FloatGrid g = field.float_grid();
  const SparseView sp(g.sparse);
  auto lookup = [&](VF px, VF py, VF pz) HWY_ATTR { return DistancesOfVector<kSparse>(df, X, g, sp, px, py, pz); };

  // Whole vectors of points.
  int k = 0;
  for (; k + lanes <= n; k += lanes) {
    VF result;
    if (index) {
      const VI i = hn::LoadU(di, index + k);
      const std::int32_t i0 = index[k];
      if (hn::AllTrue(di, i == hn::Iota(di, i0))) {  // consecutive points (a tree's top level): loads
        result = lookup(hn::LoadU(df, x + i0), hn::LoadU(df, y + i0), hn::LoadU(df, z + i0));
      } else {
        result = lookup(hn::GatherIndex(df, x, i), hn::GatherIndex(df, y, i), hn::GatherIndex(df, z, i));
      }
    } else {
      result = lookup(hn::LoadU(df, x + k), hn::LoadU(df, y + k), hn::LoadU(df, z + k));
    }
    hn::StoreU(result, df, d + k);
  }
  // The last N mod lanes points: one more vector, padded with the last point, so every point
  // is rounded alike wherever it falls in a batch.
  if (k < n) {
    constexpr int kMaxLanes = HWY_MAX_BYTES / sizeof(float);
    HWY_ALIGN float px[kMaxLanes], py[kMaxLanes], pz[kMaxLanes], out[kMaxLanes];
    for (int j = 0; j < lanes; ++j) {
      const int m = std::min(k + j, n - 1);
      const int i = index ? index[m] : m;
      px[j] = x[i];
      py[j] = y[i];
      pz[j] = z[i];
    }
    hn::Store(lookup(hn::Load(df, px), hn::Load(df, py), hn::Load(df, pz)), df, out);
    for (int j = 0; k + j < n; ++j) d[k + j] = out[j];
  }
}

void BatchDistancesImpl(const DistanceField& field, const BatchTransform& X, const float* HWY_RESTRICT x,
                        const float* HWY_RESTRICT y, const float* HWY_RESTRICT z,
                        const std::int32_t* HWY_RESTRICT index, int n, float* HWY_RESTRICT d) {
  if (field.sparse()) {
    BatchDistancesOf<true>(field, X, x, y, z, index, n, d);
  } else {
    BatchDistancesOf<false>(field, X, x, y, z, index, n, d);
  }
}

const char* TargetNameImpl() { return hwy::TargetName(HWY_TARGET); }

}  // namespace HWY_NAMESPACE
}  // namespace contactlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace contactlab {

HWY_EXPORT(BatchDistancesImpl);
HWY_EXPORT(TargetNameImpl);

void BatchDistances(const DistanceField& field, const BatchTransform& X, const float* x, const float* y,
                    const float* z, const std::int32_t* index, int n, float* d) {
  HWY_DYNAMIC_DISPATCH(BatchDistancesImpl)(field, X, x, y, z, index, n, d);
}

const char* BatchDistanceTarget() { return HWY_DYNAMIC_DISPATCH(TargetNameImpl)(); }

}  // namespace contactlab
#endif  // HWY_ONCE
