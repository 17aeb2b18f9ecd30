// AddHalfspaceContacts for each instruction set Highway compiles (this file is included once
// per target by foreach_target.h), and the run-time dispatch between them.
#include "contact/halfspace_contacts.h"

#include <algorithm>

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "contact/halfspace_contacts.cc"
#include <hwy/foreach_target.h>  // NOLINT: re-includes this file per target
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace contactlab {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The sums in A's frame (HalfspaceSums' terms with N = n_i and p = p_i + R^T t, which
// AddHalfspaceContacts rotates into B's frame), N > 0.
void HalfspaceSumsInAImpl(const ContactPointArrays& s, const float* t_A, const std::int32_t* HWY_RESTRICT index,
                          const float* HWY_RESTRICT d, int n, HalfspaceSums* out) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  using VF = hn::Vec<decltype(df)>;
  const int lanes = int(hn::Lanes(df));
  const VF t0 = hn::Set(df, t_A[0]), t1 = hn::Set(df, t_A[1]), t2 = hn::Set(df, t_A[2]);
  const float *x = s.x, *y = s.y, *z = s.z;
  const float *nx = s.nx, *ny = s.ny, *nz = s.nz;

  // Per-lane partial sums: d N (3), p x d N (3), N N^T (6), N G^T (9), G G^T (6).
  VF f[3], t[3], nn[6], ng[9], gg[6];
  for (VF& v : f) v = hn::Zero(df);
  for (VF& v : t) v = hn::Zero(df);
  for (VF& v : nn) v = hn::Zero(df);
  for (VF& v : ng) v = hn::Zero(df);
  for (VF& v : gg) v = hn::Zero(df);
  VF min_d = hn::Zero(df);

  // One vector of points; lanes beyond the last point have N = 0 and d = 0, so add nothing.
  auto add = [&](hn::Vec<decltype(di)> i, VF dv, hn::Mask<decltype(df)> valid) HWY_ATTR {
    const VF px = hn::GatherIndex(df, x, i) + t0, py = hn::GatherIndex(df, y, i) + t1;
    const VF pz = hn::GatherIndex(df, z, i) + t2;
    const VF Nx = hn::IfThenElseZero(valid, hn::GatherIndex(df, nx, i));
    const VF Ny = hn::IfThenElseZero(valid, hn::GatherIndex(df, ny, i));
    const VF Nz = hn::IfThenElseZero(valid, hn::GatherIndex(df, nz, i));
    const VF fx = dv * Nx, fy = dv * Ny, fz = dv * Nz;
    f[0] += fx;
    f[1] += fy;
    f[2] += fz;
    t[0] += hn::MulSub(py, fz, pz * fy);
    t[1] += hn::MulSub(pz, fx, px * fz);
    t[2] += hn::MulSub(px, fy, py * fx);
    const VF Gx = hn::MulSub(Ny, pz, Nz * py), Gy = hn::MulSub(Nz, px, Nx * pz), Gz = hn::MulSub(Nx, py, Ny * px);
    nn[0] = hn::MulAdd(Nx, Nx, nn[0]);
    nn[1] = hn::MulAdd(Nx, Ny, nn[1]);
    nn[2] = hn::MulAdd(Nx, Nz, nn[2]);
    nn[3] = hn::MulAdd(Ny, Ny, nn[3]);
    nn[4] = hn::MulAdd(Ny, Nz, nn[4]);
    nn[5] = hn::MulAdd(Nz, Nz, nn[5]);
    ng[0] = hn::MulAdd(Nx, Gx, ng[0]);
    ng[1] = hn::MulAdd(Nx, Gy, ng[1]);
    ng[2] = hn::MulAdd(Nx, Gz, ng[2]);
    ng[3] = hn::MulAdd(Ny, Gx, ng[3]);
    ng[4] = hn::MulAdd(Ny, Gy, ng[4]);
    ng[5] = hn::MulAdd(Ny, Gz, ng[5]);
    ng[6] = hn::MulAdd(Nz, Gx, ng[6]);
    ng[7] = hn::MulAdd(Nz, Gy, ng[7]);
    ng[8] = hn::MulAdd(Nz, Gz, ng[8]);
    gg[0] = hn::MulAdd(Gx, Gx, gg[0]);
    gg[1] = hn::MulAdd(Gx, Gy, gg[1]);
    gg[2] = hn::MulAdd(Gx, Gz, gg[2]);
    gg[3] = hn::MulAdd(Gy, Gy, gg[3]);
    gg[4] = hn::MulAdd(Gy, Gz, gg[4]);
    gg[5] = hn::MulAdd(Gz, Gz, gg[5]);
    min_d = hn::Min(min_d, dv);
  };

  int k = 0;
  for (; k + lanes <= n; k += lanes) add(hn::LoadU(di, index + k), hn::LoadU(df, d + k), hn::FirstN(df, lanes));
  if (k < n) {  // the last N mod lanes points, padded with the first point at d = 0
    constexpr int kMaxLanes = HWY_MAX_BYTES / sizeof(float);
    HWY_ALIGN std::int32_t pi[kMaxLanes];
    HWY_ALIGN float pd[kMaxLanes];
    for (int j = 0; j < lanes; ++j) {
      pi[j] = k + j < n ? index[k + j] : index[0];
      pd[j] = k + j < n ? d[k + j] : 0.f;
    }
    add(hn::Load(di, pi), hn::Load(df, pd), hn::FirstN(df, std::size_t(n - k)));
  }

  auto sum = [&](VF v) HWY_ATTR { return double(hn::GetLane(hn::SumOfLanes(df, v))); };
  for (int j = 0; j < 3; ++j) {
    out->dN[j] = sum(f[j]);
    out->p_x_dN[j] = sum(t[j]);
  }
  for (int j = 0; j < 6; ++j) {
    out->NN[j] = sum(nn[j]);
    out->GG[j] = sum(gg[j]);
  }
  for (int j = 0; j < 9; ++j) out->NG[j] = sum(ng[j]);
  out->count = n;
  out->max_penetration = -double(hn::GetLane(hn::MinOfLanes(df, min_d)));
}

// HalfspaceContactBuffer::Collect: each vector of distances with a lane below zero is
// compressed into the buffer (a full-vector store, which the buffer's padding absorbs; Added
// flushes it once kCapacity points are in).
void CollectContactsImpl(HalfspaceContactBuffer* buffer, int begin, const std::int32_t* HWY_RESTRICT index,
                         const float* HWY_RESTRICT d, int n) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const int lanes = int(hn::Lanes(df));
  static_assert(HalfspaceContactBuffer::kPadding * sizeof(float) >= HWY_MAX_BYTES);
  const auto zero = hn::Zero(df);
  int k = 0;
  for (; k + lanes <= n; k += lanes) {
    const auto dv = hn::LoadU(df, d + k);
    const auto in_contact = dv < zero;
    if (hn::AllFalse(df, in_contact)) continue;
    const auto i = index ? hn::LoadU(di, index + k) : hn::Iota(di, begin + k);
    hn::StoreU(hn::Compress(i, hn::RebindMask(di, in_contact)), di, buffer->free_index());
    hn::StoreU(hn::Compress(dv, in_contact), df, buffer->free_d());
    buffer->Added(int(hn::CountTrue(df, in_contact)));
  }
  for (; k < n; ++k) {
    if (d[k] < 0.f) {
      *buffer->free_index() = index ? index[k] : begin + k;
      *buffer->free_d() = d[k];
      buffer->Added(1);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace contactlab
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace contactlab {

HWY_EXPORT(HalfspaceSumsInAImpl);
HWY_EXPORT(CollectContactsImpl);

// With p_B = R p_A + t = R (p_A + R^T t) and N_B = R N_A, the B-frame point is R q for
// q = p_A + R^T t, and G_B = N_B x p_B = R (N_A x q): every sum is the A-frame sum of the
// same terms, rotated (vectors R v, matrices R S R^T). The kernel then needs no rotation.
void AddHalfspaceContacts(const ContactPointArrays& s, const BatchTransform& X, const std::int32_t* index,
                          const float* d, int n, ContactAccumulator* acc) {
  if (n <= 0) return;
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R(i, j) = X.r[3 * i + j];
  const Eigen::Vector3d t_A = R.transpose() * Eigen::Vector3d(X.t[0], X.t[1], X.t[2]);
  const float t_Af[3] = {float(t_A[0]), float(t_A[1]), float(t_A[2])};
  HalfspaceSums a;
  HWY_DYNAMIC_DISPATCH(HalfspaceSumsInAImpl)(s, t_Af, index, d, n, &a);
  using Row3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  auto vector = [&R](double* v) {
    Eigen::Map<Eigen::Vector3d> m(v);
    m = R * Eigen::Vector3d(m);
  };
  auto symmetric = [&R](double* U) {
    const Eigen::Matrix3d S = R * ContactAccumulator::Symmetric(U) * R.transpose();
    const double upper[6] = {S(0, 0), S(0, 1), S(0, 2), S(1, 1), S(1, 2), S(2, 2)};
    std::copy(upper, upper + 6, U);
  };
  vector(a.dN);
  vector(a.p_x_dN);
  symmetric(a.NN);
  symmetric(a.GG);
  Eigen::Map<Row3> NG(a.NG);
  NG = R * Row3(NG) * R.transpose();
  acc->Add(a);
}

void HalfspaceContactBuffer::Collect(int begin, const std::int32_t* index, const float* d, int n) {
  HWY_DYNAMIC_DISPATCH(CollectContactsImpl)(this, begin, index, d, n);
}

}  // namespace contactlab
#endif  // HWY_ONCE
