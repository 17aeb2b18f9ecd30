// FrictionSums' batch kernel for each instruction set Highway compiles (this file is included
// once per target by foreach_target.h), and the run-time dispatch between them.
#include <algorithm>

#include "contact/friction.h"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "contact/friction_sums.cc"
#include <hwy/foreach_target.h>  // NOLINT: re-includes this file per target
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace contactlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The sums of FrictionBatch B's N contacts (friction.h, FrictionSums::Flush), in passes of a
// few dozen accumulators each so that they stay in registers. Lanes past N are padded with
// w = z = 0 and u = 0, which add nothing.
void FrictionBatchSumsImpl(const FrictionBatch& b, int n, FrictionBatchTotals* out) {
  const hn::ScalableTag<float> df;
  using VF = hn::Vec<decltype(df)>;
  const int lanes = int(hn::Lanes(df));
  struct Lane {
    VF w, z, u[3], N[3], g[3], q[3], r[3];
  };
  auto load = [&](int k) HWY_ATTR {
    Lane l;
    l.w = hn::LoadU(df, b.w + k), l.z = hn::LoadU(df, b.z + k);
    for (int a = 0; a < 3; ++a) {
      l.u[a] = hn::LoadU(df, b.u[a] + k), l.N[a] = hn::LoadU(df, b.N[a] + k), l.g[a] = hn::LoadU(df, b.g[a] + k);
      l.q[a] = hn::LoadU(df, b.q[a] + k), l.r[a] = hn::LoadU(df, b.r[a] + k);
    }
    return l;
  };
  auto cross = [](const VF* a, const VF* c, VF* o) HWY_ATTR {
    o[0] = hn::MulSub(a[1], c[2], a[2] * c[1]);
    o[1] = hn::MulSub(a[2], c[0], a[0] * c[2]);
    o[2] = hn::MulSub(a[0], c[1], a[1] * c[0]);
  };
  // acc[3i + j] += s a_i c_j (S: a per-lane weight).
  auto outer = [](const VF* a, const VF* c, VF s, VF* acc) HWY_ATTR {
    for (int i = 0; i < 3; ++i) {
      const VF sa = s * a[i];
      for (int j = 0; j < 3; ++j) acc[3 * i + j] = hn::MulAdd(sa, c[j], acc[3 * i + j]);
    }
  };
  auto sum = [&](const VF* acc, int m, double* to) HWY_ATTR {
    for (int j = 0; j < m; ++j) to[j] += double(hn::GetLane(hn::SumOfLanes(df, acc[j])));
  };
  const VF one = hn::Set(df, 1.f);
  // Each pass: ACC (up to 27 accumulators) filled by TERMS(lane, acc), then added to TO.
  auto pass = [&](int m, double* to, auto&& terms) HWY_ATTR {
    VF acc[27];
    for (int j = 0; j < m; ++j) acc[j] = hn::Zero(df);
    for (int k = 0; k < n; k += lanes) terms(load(k), acc);
    sum(acc, m, to);
  };
  // 1. Force w u, torque w q x u, K_xx's u g^T, w N N^T, z u u^T and sum w.
  pass(25, out->pass1, [&](const Lane& l, VF* acc) HWY_ATTR {
    VF qu[3];
    cross(l.q, l.u, qu);
    for (int a = 0; a < 3; ++a) acc[a] = hn::MulAdd(l.w, l.u[a], acc[a]), acc[3 + a] = hn::MulAdd(l.w, qu[a], acc[3 + a]);
    outer(l.u, l.g, one, acc + 6);
    acc[15] = hn::MulAdd(l.w, l.N[0] * l.N[0], acc[15]);
    acc[16] = hn::MulAdd(l.w, l.N[0] * l.N[1], acc[16]);
    acc[17] = hn::MulAdd(l.w, l.N[0] * l.N[2], acc[17]);
    acc[18] = hn::MulAdd(l.w, l.N[1] * l.N[1], acc[18]);
    acc[19] = hn::MulAdd(l.w, l.N[1] * l.N[2], acc[19]);
    acc[20] = hn::MulAdd(l.w, l.N[2] * l.N[2], acc[20]);
    acc[21] = acc[21] + l.w;
    for (int a = 0; a < 3; ++a) acc[22 + a] = hn::MulAdd(l.w, l.r[a], acc[22 + a]);
  });
  // 2. The sliding contacts' z u u^T, sum w q, sum w q . r, and K_xtheta's u (q x g)^T.
  pass(22, out->pass2, [&](const Lane& l, VF* acc) HWY_ATTR {
    outer(l.u, l.u, l.z, acc);
    for (int a = 0; a < 3; ++a) acc[9 + a] = hn::MulAdd(l.w, l.q[a], acc[9 + a]);
    acc[12] = hn::MulAdd(l.w, hn::MulAdd(l.q[0], l.r[0], hn::MulAdd(l.q[1], l.r[1], l.q[2] * l.r[2])), acc[12]);
    VF qg[3];
    cross(l.q, l.g, qg);
    outer(l.u, qg, one, acc + 13);
  });
  // 3. K_xtheta's w N (N x r)^T and z u (u x r)^T, K_thetax's (q x u) g^T.
  pass(27, out->pass3, [&](const Lane& l, VF* acc) HWY_ATTR {
    VF Nr[3], ur[3], qu[3];
    cross(l.N, l.r, Nr);
    cross(l.u, l.r, ur);
    cross(l.q, l.u, qu);
    outer(l.N, Nr, l.w, acc);
    outer(l.u, ur, l.z, acc + 9);
    outer(qu, l.g, one, acc + 18);
  });
  // 4. K_thetax's w (q x N) N^T and z (q x u) u^T, K_thetatheta's (q x u)(q x g)^T.
  pass(27, out->pass4, [&](const Lane& l, VF* acc) HWY_ATTR {
    VF qN[3], qu[3], qg[3];
    cross(l.q, l.N, qN);
    cross(l.q, l.u, qu);
    cross(l.q, l.g, qg);
    outer(qN, l.N, l.w, acc);
    outer(qu, l.u, l.z, acc + 9);
    outer(qu, qg, one, acc + 18);
  });
  // 5. K_thetatheta's w r q^T, w (q x N)(N x r)^T and z (q x u)(u x r)^T.
  pass(27, out->pass5, [&](const Lane& l, VF* acc) HWY_ATTR {
    VF qN[3], Nr[3], qu[3], ur[3];
    cross(l.q, l.N, qN);
    cross(l.N, l.r, Nr);
    cross(l.q, l.u, qu);
    cross(l.u, l.r, ur);
    outer(l.r, l.q, l.w, acc);
    outer(qN, Nr, l.w, acc + 9);
    outer(qu, ur, l.z, acc + 18);
  });
}

}  // namespace HWY_NAMESPACE
}  // namespace contactlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace contactlab {

HWY_EXPORT(FrictionBatchSumsImpl);

void FrictionSums::Flush() {
  if (count_ == 0) return;
  for (int k = count_; k < count_ + FrictionBatch::kPadding; ++k) {  // padding: adds nothing
    batch_.w[k] = batch_.z[k] = 0.f;
    for (int a = 0; a < 3; ++a) batch_.u[a][k] = batch_.N[a][k] = batch_.g[a][k] = batch_.q[a][k] = batch_.r[a][k] = 0.f;
  }
  HWY_DYNAMIC_DISPATCH(FrictionBatchSumsImpl)(batch_, count_, &totals_);
  count_ = 0;
}

}  // namespace contactlab
#endif  // HWY_ONCE
