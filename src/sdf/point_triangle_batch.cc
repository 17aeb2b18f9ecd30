// PointsTriangleDistancesSquared per instruction set (included once per target by
// foreach_target.h) and its run-time dispatch.
#include "sdf/point_triangle_batch.h"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "sdf/point_triangle_batch.cc"
#include <hwy/foreach_target.h>  // NOLINT: re-includes this file per target
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace contactlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void PointsTriangleDistancesSquaredImpl(const double* HWY_RESTRICT tri, const double* HWY_RESTRICT x,
                                        const double* HWY_RESTRICT y, const double* HWY_RESTRICT z, int n,
                                        double* HWY_RESTRICT out) {
  const hn::ScalableTag<double> d;
  using V = hn::Vec<decltype(d)>;
  const int lanes = int(hn::Lanes(d));
  const double abx = tri[3] - tri[0], aby = tri[4] - tri[1], abz = tri[5] - tri[2];
  const double acx = tri[6] - tri[0], acy = tri[7] - tri[1], acz = tri[8] - tri[2];
  const V ax = hn::Set(d, tri[0]), ay = hn::Set(d, tri[1]), az = hn::Set(d, tri[2]);
  const V vabx = hn::Set(d, abx), vaby = hn::Set(d, aby), vabz = hn::Set(d, abz);
  const V vacx = hn::Set(d, acx), vacy = hn::Set(d, acy), vacz = hn::Set(d, acz);
  // Dot products with AB and AC of p - B and p - C follow from those of p - A.
  const V ab_ab = hn::Set(d, abx * abx + aby * aby + abz * abz), ab_ac = hn::Set(d, abx * acx + aby * acy + abz * acz),
          ac_ac = hn::Set(d, acx * acx + acy * acy + acz * acz);
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);

  auto distance2 = [&](V px, V py, V pz) HWY_ATTR {
    const V apx = px - ax, apy = py - ay, apz = pz - az;
    const V d1 = hn::MulAdd(vabx, apx, hn::MulAdd(vaby, apy, vabz * apz));
    const V d2 = hn::MulAdd(vacx, apx, hn::MulAdd(vacy, apy, vacz * apz));
    const V d3 = d1 - ab_ab, d4 = d2 - ab_ac;  // (p - B) . AB, (p - B) . AC
    const V d5 = d1 - ab_ac, d6 = d2 - ac_ac;  // (p - C) . AB, (p - C) . AC
    const V vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    // Face region, then the others from the last tested to the first, so that the first
    // region whose test passes decides, as in the scalar function.
    const V den = va + vb + vc;
    V v = vb / den, w = vc / den;
    const V e_bc = (d4 - d3) + (d5 - d6);
    const auto in_bc = hn::And(va <= zero, hn::And((d4 - d3) >= zero, (d5 - d6) >= zero));
    const V w_bc = hn::IfThenElse(e_bc > zero, (d4 - d3) / e_bc, zero);
    v = hn::IfThenElse(in_bc, one - w_bc, v);
    w = hn::IfThenElse(in_bc, w_bc, w);
    const auto in_ac = hn::And(vb <= zero, hn::And(d2 >= zero, d6 <= zero));
    v = hn::IfThenElse(in_ac, zero, v);
    w = hn::IfThenElse(in_ac, hn::IfThenElse((d2 - d6) > zero, d2 / (d2 - d6), zero), w);
    const auto in_c = hn::And(d6 >= zero, d5 <= d6);
    v = hn::IfThenElse(in_c, zero, v);
    w = hn::IfThenElse(in_c, one, w);
    const auto in_ab = hn::And(vc <= zero, hn::And(d1 >= zero, d3 <= zero));
    v = hn::IfThenElse(in_ab, hn::IfThenElse((d1 - d3) > zero, d1 / (d1 - d3), zero), v);
    w = hn::IfThenElse(in_ab, zero, w);
    const auto in_b = hn::And(d3 >= zero, d4 <= d3);
    v = hn::IfThenElse(in_b, one, v);
    w = hn::IfThenElse(in_b, zero, w);
    const auto in_a = hn::And(d1 <= zero, d2 <= zero);
    v = hn::IfThenElseZero(hn::Not(in_a), v);
    w = hn::IfThenElseZero(hn::Not(in_a), w);
    // p - (A + v AB + w AC)
    const V qx = apx - hn::MulAdd(v, vabx, w * vacx);
    const V qy = apy - hn::MulAdd(v, vaby, w * vacy);
    const V qz = apz - hn::MulAdd(v, vabz, w * vacz);
    return hn::MulAdd(qx, qx, hn::MulAdd(qy, qy, qz * qz));
  };

  int i = 0;
  for (; i + lanes <= n; i += lanes) {
    hn::StoreU(distance2(hn::LoadU(d, x + i), hn::LoadU(d, y + i), hn::LoadU(d, z + i)), d, out + i);
  }
  if (i < n) {
    constexpr int kMaxLanes = HWY_MAX_BYTES / sizeof(double);
    HWY_ALIGN double px[kMaxLanes], py[kMaxLanes], pz[kMaxLanes], r[kMaxLanes];
    for (int j = 0; j < lanes; ++j) {
      const int m = std::min(i + j, n - 1);
      px[j] = x[m];
      py[j] = y[m];
      pz[j] = z[m];
    }
    hn::Store(distance2(hn::Load(d, px), hn::Load(d, py), hn::Load(d, pz)), d, r);
    for (int j = 0; i + j < n; ++j) out[i + j] = r[j];
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace contactlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace contactlab {

HWY_EXPORT(PointsTriangleDistancesSquaredImpl);

void PointsTriangleDistancesSquared(const double* tri, const double* x, const double* y, const double* z, int n,
                                    double* out) {
  HWY_DYNAMIC_DISPATCH(PointsTriangleDistancesSquaredImpl)(tri, x, y, z, n, out);
}

}  // namespace contactlab
#endif  // HWY_ONCE
