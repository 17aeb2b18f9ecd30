// The narrow-band field's lookups, checks and builder (sdf/sparse_field.h).
#include "sdf/sparse_field.h"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sdf/distance_field.h"
#include "sdf/point_triangle_batch.h"
#include "sdf/point_triangle_distance.h"
#include "sdf/unsigned_distance_grid.h"
#include "util/error.h"

namespace contactlab {

float SparseLookup(const SparseFieldStorage& s, float gx, float gy, float gz) {
  return float(s.Lookup(Eigen::Vector3d(gx, gy, gz)));
}
float SparseSample(const SparseFieldStorage& s, int i, int j, int k) { return s.Sample(i, j, k); }

namespace {

constexpr int kEdge = SparseFieldStorage::kBrickEdge;
constexpr int kBrickSamples = kEdge * kEdge * kEdge;

// Trilinear interpolation of corner values C at T in [0, 1]^3; GRAD: its gradient per cell edge.
double Trilinear(const double c[2][2][2], const Eigen::Vector3d& t, Eigen::Vector3d* grad) {
  auto lerp = [](double a, double b, double u) { return a + u * (b - a); };
  const double c00 = lerp(c[0][0][0], c[1][0][0], t.x()), c10 = lerp(c[0][1][0], c[1][1][0], t.x());
  const double c01 = lerp(c[0][0][1], c[1][0][1], t.x()), c11 = lerp(c[0][1][1], c[1][1][1], t.x());
  const double c0 = lerp(c00, c10, t.y()), c1 = lerp(c01, c11, t.y());
  const double dx00 = c[1][0][0] - c[0][0][0], dx10 = c[1][1][0] - c[0][1][0];
  const double dx01 = c[1][0][1] - c[0][0][1], dx11 = c[1][1][1] - c[0][1][1];
  *grad << lerp(lerp(dx00, dx10, t.y()), lerp(dx01, dx11, t.y()), t.z()), lerp(c10 - c00, c11 - c01, t.z()), c1 - c0;
  return lerp(c0, c1, t.z());
}

// A coarse cell (edge H) with corner values C, at T in [0, 1]^3, where every point is farther
// than FLOOR from the surface. Outside the body: the largest lower bound of FLOOR, the
// interpolant less MARGIN and each corner's value less its distance (the distance is
// 1-Lipschitz). Inside: the interpolant, at most -FLOOR. GRAD: per coarse-cell edge.
double CoarseCellValue(const double c[2][2][2], const Eigen::Vector3d& t, bool outside, double floor, double margin,
                       double H, Eigen::Vector3d* grad) {
  double value = Trilinear(c, t, grad);
  if (!outside) {
    if (value > -floor) value = -floor, grad->setZero();
    return value;
  }
  value -= margin;
  if (value < floor) value = floor, grad->setZero();
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d k(corner & 1, (corner >> 1) & 1, corner >> 2);
    const double r = (t - k).norm();
    const double b = c[corner & 1][(corner >> 1) & 1][corner >> 2] - H * r;
    if (b > value) {
      value = b;
      *grad = r > 0 ? Eigen::Vector3d(-H * (t - k) / r) : Eigen::Vector3d::Zero();
    }
  }
  return value;
}

// The corner values of coarse cell (BX, BY, BZ).
void CoarseCorners(const SparseFieldStorage& s, int bx, int by, int bz, double c[2][2][2]) {
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) c[dx][dy][dz] = s.coarse[s.CoarseIndex(bx + dx, by + dy, bz + dz)];
}

}  // namespace

void SparseFieldStorage::SetSpacing(double h) {
  floor = float((band_voxels - std::sqrt(3.0) / 2) * h);
  margin = float(std::sqrt(3.0) / 2 * kBrick * h);
  coarse_spacing = float(kBrick * h);
}

float SparseFieldStorage::Sample(int i, int j, int k) const {
  const int bx = std::min(i / kBrick, bricks.x() - 1), by = std::min(j / kBrick, bricks.y() - 1),
            bz = std::min(k / kBrick, bricks.z() - 1);
  const std::int32_t s = slot[BrickIndex(bx, by, bz)];
  if (s < 0) return float(Lookup(Eigen::Vector3d(i, j, k)));
  const int l = (i - kBrick * bx) + kBrickEdge * ((j - kBrick * by) + kBrickEdge * (k - kBrick * bz));
  return samples[std::size_t(s) * kBrickStride + l] * quantum;
}

double SparseFieldStorage::Lookup(const Eigen::Vector3d& g, Eigen::Vector3d* gradient) const {
  // The fine cell, clamped so the last grid plane uses the last cell with t = 1, and its brick.
  const int i = std::clamp(int(g.x()), 0, kBrick * bricks.x() - 1);
  const int j = std::clamp(int(g.y()), 0, kBrick * bricks.y() - 1);
  const int k = std::clamp(int(g.z()), 0, kBrick * bricks.z() - 1);
  const int bx = i >> 3, by = j >> 3, bz = k >> 3;
  const std::int32_t s = slot[BrickIndex(bx, by, bz)];
  double c[2][2][2];
  double value;
  Eigen::Vector3d grad;
  if (s >= 0) {
    const std::int16_t* v =
        samples.data() + std::int64_t(s) * kBrickStride + (i & 7) + kBrickEdge * ((j & 7) + kBrickEdge * (k & 7));
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) c[dx][dy][dz] = double(v[dx + kBrickEdge * (dy + kBrickEdge * dz)]) * quantum;
    value = Trilinear(c, Eigen::Vector3d(g.x() - i, g.y() - j, g.z() - k), &grad);
  } else {
    // No samples here: the coarse cell (the brick itself), bounded as the header says.
    CoarseCorners(*this, bx, by, bz, c);
    const Eigen::Vector3d t = (g - kBrick * Eigen::Vector3d(bx, by, bz)) / kBrick;
    value = CoarseCellValue(c, t, s == kOutside, floor, margin, coarse_spacing, &grad);
    grad /= kBrick;
  }
  if (gradient) *gradient = grad;
  return value;
}

void SparseFieldStorage::Validate(const std::string& where) const {
  if ((bricks.array() < 1).any()) Fail(where, "needs at least one brick per axis");
  const std::int64_t nb = std::int64_t(bricks.x()) * bricks.y() * bricks.z();
  const std::int64_t nc = std::int64_t(bricks.x() + 1) * (bricks.y() + 1) * (bricks.z() + 1);
  if (std::int64_t(coarse.size()) != nc) {
    Fail(where, "holds " + std::to_string(coarse.size()) + " coarse samples, its bricks need " + std::to_string(nc));
  }
  if (std::int64_t(slot.size()) != nb) {
    Fail(where, "holds " + std::to_string(slot.size()) + " brick slots, its bricks need " + std::to_string(nb));
  }
  if (samples.size() % kBrickStride != 0) Fail(where, "holds a partial brick of samples");
  const std::int64_t stored = num_stored();
  if (stored >= std::numeric_limits<std::int32_t>::max() / kBrickStride) Fail(where, "holds too many bricks");
  for (std::int32_t s : slot) {
    if (s < kInside || s >= stored) Fail(where, "a brick slot " + std::to_string(s) + " is out of range");
  }
  for (float v : coarse) {
    if (!std::isfinite(v)) Fail(where, "a coarse sample is not finite");
  }
  if (!(quantum > 0) || !std::isfinite(quantum)) Fail(where, "the sample quantum must be positive and finite");
  if (band_voxels < 1 || band_voxels > kMaxBand) {
    Fail(where, "the band of " + std::to_string(band_voxels) + " voxels is outside [1, " + std::to_string(kMaxBand) + "]");
  }
}

namespace {

// What every stage of the sparse build reads: the fine lattice (origin O, spacing h, LAST fine
// sample per axis), the coarse spacing H, the band (metres) and EXACT = band + h, the radius
// within which samples get exact distances, and the flattened triangles (FlattenTriangles).
struct SparseBuild {
  const SparseFieldStorage& s;
  Eigen::Vector3d o;
  double H, h, band, exact;
  Eigen::Vector3i last;
  const std::vector<double>& corners;

  // Fine-sample index range [lo, hi] per axis within EXACT of triangle T's box.
  void SampleRange(int t, Eigen::Vector3i* lo, Eigen::Vector3i* hi) const {
    const double* c = corners.data() + 9 * std::size_t(t);
    for (int a = 0; a < 3; ++a) {
      const double mn = std::min({c[a], c[3 + a], c[6 + a]}) - exact, mx = std::max({c[a], c[3 + a], c[6 + a]}) + exact;
      (*lo)[a] = std::clamp(int(std::floor((mn - o[a]) / h)), 0, last[a]);
      (*hi)[a] = std::clamp(int(std::ceil((mx - o[a]) / h)), 0, last[a]);
    }
  }
  // The brick (BX, BY, BZ) of brick id ID.
  Eigen::Vector3i BrickOf(std::int64_t id) const {
    return {int(id % s.bricks.x()), int((id / s.bricks.x()) % s.bricks.y()),
            int(id / (std::int64_t(s.bricks.x()) * s.bricks.y()))};
  }
};

// The bricks some triangle's grown box reaches (CANDIDATE, ascending ids), each with its
// triangles: PAIRS[BEGIN[c] .. BEGIN[c + 1]) for candidate c.
struct BrickCandidates {
  struct Pair {
    std::int64_t brick;
    std::int32_t tri;
  };
  std::vector<Pair> pairs;
  std::vector<std::int64_t> candidate;
  std::vector<std::size_t> begin;
};

// (brick, triangle) for every brick whose samples a triangle's grown box reaches, in parallel,
// then sorted and grouped by brick.
BrickCandidates FindCandidateBricks(const SparseBuild& b, int num_triangles) {
  using Pair = BrickCandidates::Pair;
  const SparseFieldStorage& s = b.s;
  tbb::enumerable_thread_specific<std::vector<Pair>> local;
  tbb::parallel_for(tbb::blocked_range<int>(0, num_triangles, 256), [&](const tbb::blocked_range<int>& r) {
    auto& out = local.local();
    for (int t = r.begin(); t < r.end(); ++t) {
      Eigen::Vector3i lo, hi;
      b.SampleRange(t, &lo, &hi);
      Eigen::Vector3i b0, b1;  // brick b holds samples [8 b, 8 b + 8]
      for (int a = 0; a < 3; ++a) {
        b0[a] = std::max(0, (lo[a] - 1) / SparseFieldStorage::kBrick);
        b1[a] = std::min(s.bricks[a] - 1, hi[a] / SparseFieldStorage::kBrick);
      }
      for (int bz = b0.z(); bz <= b1.z(); ++bz)
        for (int by = b0.y(); by <= b1.y(); ++by)
          for (int bx = b0.x(); bx <= b1.x(); ++bx) out.push_back({s.BrickIndex(bx, by, bz), t});
    }
  });
  BrickCandidates out;
  std::vector<Pair>& pairs = out.pairs;
  for (auto& v : local) pairs.insert(pairs.end(), v.begin(), v.end());
  local.clear();
  tbb::parallel_sort(pairs.begin(), pairs.end(), [](const Pair& x, const Pair& y) {
    return x.brick != y.brick ? x.brick < y.brick : x.tri < y.tri;
  });
  for (std::size_t p = 0; p < pairs.size(); ++p) {
    if (p == 0 || pairs[p].brick != pairs[p - 1].brick) {
      out.candidate.push_back(pairs[p].brick);
      out.begin.push_back(p);
    }
  }
  out.begin.push_back(pairs.size());
  return out;
}

// Per-brick scratch, kBrickSamples entries each (x fastest): the best squared distance so far
// and its triangle (-1: none within EXACT), the samples a triangle's plane leaves for the
// vectorised test (position, brick index, result), the breadth-first queue, the signs and the
// final values.
struct BrickScratch {
  double d2[kBrickSamples];
  std::int32_t tri[kBrickSamples];
  double qx[kBrickSamples], qy[kBrickSamples], qz[kBrickSamples], e2[kBrickSamples];
  int ql[kBrickSamples], queue[kBrickSamples];
  std::int8_t sgn[kBrickSamples];
  float value[kBrickSamples];
};

// Lowers the brick's distances (first fine sample FIRST) to triangle T's where closer.
void TriangleIntoBrick(const SparseBuild& b, int t, const Eigen::Vector3i& first, BrickScratch* w) {
  const Eigen::Vector3d& o = b.o;
  const double h = b.h, exact = b.exact;
  double* d2 = w->d2;
  Eigen::Vector3i lo, hi;
  b.SampleRange(t, &lo, &hi);
  lo = lo.cwiseMax(first);
  hi = hi.cwiseMin(first + Eigen::Vector3i::Constant(SparseFieldStorage::kBrick));
  const double* tc = b.corners.data() + 9 * std::size_t(t);
  // The triangle's plane, s(p) = n . p - c with |n| = 1 (zero for a degenerate one): no
  // point farther from the plane than from its best triangle so far can gain, and none
  // farther than EXACT is wanted, which bounds each grid row to a run of samples.
  const Eigen::Vector3d A(tc[0], tc[1], tc[2]), B(tc[3], tc[4], tc[5]), C(tc[6], tc[7], tc[8]);
  Eigen::Vector3d n = (B - A).cross(C - A);
  // Degenerate as PointTriangleDistanceSquared decides it: the union of its edges.
  const bool degenerate = !(n.squaredNorm() > 1e-24 * (B - A).squaredNorm() * (C - A).squaredNorm());
  n = degenerate ? Eigen::Vector3d::Zero() : n.normalized();
  const double c = n.dot(A);
  int m = 0;
  for (int k = lo.z(); k <= hi.z(); ++k)
    for (int j = lo.y(); j <= hi.y(); ++j) {
      int i0 = lo.x(), i1 = hi.x();
      const double s0 = n.x() * o.x() + n.y() * (o.y() + h * j) + n.z() * (o.z() + h * k) - c;  // s at i = 0
      const double ds = n.x() * h;
      if (std::abs(ds) > 1e-12 * h) {
        const double a0 = (-exact - s0) / ds, a1 = (exact - s0) / ds;
        i0 = std::max(i0, int(std::floor(std::min(a0, a1))));
        i1 = std::min(i1, int(std::ceil(std::max(a0, a1))));
      } else if (std::abs(s0) >= exact) {
        continue;
      }
      for (int i = i0; i <= i1; ++i) {
        const int l = (i - first.x()) + kEdge * ((j - first.y()) + kEdge * (k - first.z()));
        const double plane = s0 + ds * i;
        if (plane * plane >= d2[l]) continue;
        if (degenerate) {
          const double q[3] = {o.x() + h * i, o.y() + h * j, o.z() + h * k};
          const double e2 = PointTriangleDistanceSquared(q, tc, tc + 3, tc + 6);
          if (e2 < d2[l]) d2[l] = e2, w->tri[l] = t;
          continue;
        }
        w->qx[m] = o.x() + h * i, w->qy[m] = o.y() + h * j, w->qz[m] = o.z() + h * k, w->ql[m] = l;
        ++m;
      }
    }
  // The samples the plane left, several per instruction.
  PointsTriangleDistancesSquared(tc, w->qx, w->qy, w->qz, m, w->e2);
  for (int r = 0; r < m; ++r) {
    if (w->e2[r] < d2[w->ql[r]]) d2[w->ql[r]] = w->e2[r], w->tri[w->ql[r]] = t;
  }
}

// Signs of the brick's exact samples (pseudo-normals) and their values. Returns whether there
// is any; *NEAREST: the smallest exact distance.
bool SignExactSamples(const SparseBuild& b, const MeshSignedDistance& sign, const Eigen::Vector3i& first,
                      BrickScratch* w, double* nearest) {
  *nearest = std::numeric_limits<double>::infinity();
  bool any = false;
  for (int l = 0; l < kBrickSamples; ++l) {
    w->sgn[l] = 0;
    if (w->tri[l] < 0) continue;
    const int i = first.x() + l % kEdge, j = first.y() + (l / kEdge) % kEdge, k = first.z() + l / (kEdge * kEdge);
    const double d = std::sqrt(w->d2[l]);
    const bool inside = sign.Inside(b.o + b.h * Eigen::Vector3d(i, j, k), w->tri[l]);
    w->sgn[l] = inside ? -1 : 1;
    w->value[l] = float(inside ? -d : d);
    *nearest = std::min(*nearest, d);
    any = true;
  }
  return any;
}

// Spreads the exact samples' signs to the rest, breadth-first over the brick's 6-neighbour
// grid: a sample farther than EXACT has no surface within EXACT > h of it, so its neighbours
// share its sign.
void SpreadSigns(BrickScratch* w) {
  std::int8_t* sgn = w->sgn;
  int* queue = w->queue;
  int head = 0, tail = 0;
  for (int l = 0; l < kBrickSamples; ++l) {
    if (sgn[l] != 0) queue[tail++] = l;
  }
  while (head < tail) {
    const int l = queue[head++];
    const int i = l % kEdge, j = (l / kEdge) % kEdge, k = l / (kEdge * kEdge);
    const int n[6] = {i > 0 ? l - 1 : -1, i < kEdge - 1 ? l + 1 : -1, j > 0 ? l - kEdge : -1,
                      j < kEdge - 1 ? l + kEdge : -1, k > 0 ? l - kEdge * kEdge : -1,
                      k < kEdge - 1 ? l + kEdge * kEdge : -1};
    for (int m : n) {
      if (m >= 0 && sgn[m] == 0) {
        sgn[m] = sgn[l];
        queue[tail++] = m;
      }
    }
  }
}

// Samples of brick BRICK beyond EXACT: the bounds of the coarse cell, with EXACT as the floor.
// Every sample of a stored brick is within 8 sqrt(3) h of one with |d| <= band, so the clamp to
// band + 14 h loses nothing true and keeps the 16-bit step below 6e-4 h.
void FillBeyondExact(const SparseBuild& b, const Eigen::Vector3i& brick, BrickScratch* w) {
  const double band = b.band, h = b.h;
  double corners_c[2][2][2];
  CoarseCorners(b.s, brick.x(), brick.y(), brick.z(), corners_c);
  for (int l = 0; l < kBrickSamples; ++l) {
    if (w->tri[l] >= 0) continue;
    const Eigen::Vector3d t(l % kEdge, (l / kEdge) % kEdge, l / (kEdge * kEdge));
    Eigen::Vector3d unused;
    const double v = CoarseCellValue(corners_c, t / SparseFieldStorage::kBrick, w->sgn[l] > 0, b.exact, b.s.margin,
                                     b.H, &unused);
    w->value[l] = float(std::clamp(v, -(band + 14 * h), band + 14 * h));
  }
}

// The samples of candidate brick C: exact within EXACT of the surface, signed, the rest
// bounded. Writes them to *KEPT and returns 0 when the brick is stored; else leaves *KEPT empty
// and returns its slot code (kInside or kOutside).
std::int32_t BuildCandidateBrick(const SparseBuild& b, const MeshSignedDistance& sign, const BrickCandidates& cand,
                                 std::size_t c, BrickScratch* w, std::vector<float>* kept) {
  const std::int64_t id = cand.candidate[c];
  const Eigen::Vector3i brick = b.BrickOf(id);
  const Eigen::Vector3i first = SparseFieldStorage::kBrick * brick;
  // Exact distances from the brick's triangles.
  std::fill(w->d2, w->d2 + kBrickSamples, b.exact * b.exact);
  std::fill(w->tri, w->tri + kBrickSamples, -1);
  for (std::size_t p = cand.begin[c]; p < cand.begin[c + 1]; ++p) TriangleIntoBrick(b, cand.pairs[p].tri, first, w);
  // Their signs, spread to the rest.
  double nearest;
  if (!SignExactSamples(b, sign, first, w, &nearest)) {
    return b.s.slot[id];  // the grown box reached the brick, no sample is within EXACT: as a far brick
  }
  SpreadSigns(w);
  if (nearest > b.band) {  // not stored: every sample is beyond the band
    return w->sgn[0] < 0 ? SparseFieldStorage::kInside : SparseFieldStorage::kOutside;
  }
  FillBeyondExact(b, brick, w);
  kept->assign(w->value, w->value + kBrickSamples);
  return 0;
}

// The Morton (z-curve) code of brick ID's position in S.
std::uint64_t MortonCode(const SparseFieldStorage& s, std::int64_t id) {
  const std::uint64_t b[3] = {std::uint64_t(id % s.bricks.x()), std::uint64_t((id / s.bricks.x()) % s.bricks.y()),
                              std::uint64_t(id / (std::int64_t(s.bricks.x()) * s.bricks.y()))};
  std::uint64_t code = 0;
  for (int bit = 0; bit < 21; ++bit)
    for (int a = 0; a < 3; ++a) code |= ((b[a] >> bit) & 1u) << (3 * bit + a);
  return code;
}

// Stores the kept bricks in Morton order of their position, so bricks near in space are near
// in memory, with samples quantised to one step for the whole field; the others get their
// CODE as slot.
void StoreBricks(const std::vector<std::int64_t>& candidate, const std::vector<std::vector<float>>& kept,
                 const std::vector<std::int32_t>& code, double h, SparseFieldStorage* s) {
  std::vector<std::pair<std::uint64_t, std::size_t>> order;
  double largest = 0;
  for (std::size_t c = 0; c < candidate.size(); ++c) {
    if (kept[c].empty()) {
      s->slot[candidate[c]] = code[c];
      continue;
    }
    order.emplace_back(MortonCode(*s, candidate[c]), c);
    for (float v : kept[c]) largest = std::max(largest, double(std::abs(v)));
  }
  std::sort(order.begin(), order.end());
  const std::int64_t stored = std::int64_t(order.size());
  for (std::size_t r = 0; r < order.size(); ++r) s->slot[candidate[order[r].second]] = std::int32_t(r);
  s->quantum = float(largest > 0 ? largest / 32767 : h * 1e-6);
  s->samples.assign(std::size_t(stored) * SparseFieldStorage::kBrickStride, 0);
  tbb::parallel_for(std::size_t(0), candidate.size(), [&](std::size_t c) {
    if (kept[c].empty()) return;
    std::int16_t* out = s->samples.data() + std::size_t(s->slot[candidate[c]]) * SparseFieldStorage::kBrickStride;
    for (int l = 0; l < kBrickSamples; ++l) {
      out[l] = std::int16_t(std::clamp(std::lround(kept[c][l] / s->quantum), -32767L, 32767L));
    }
  });
}

}  // namespace

SparseFieldStorage BuildSparseStorage(const TriangleMesh& mesh, const MeshSignedDistance& sign,
                                      const FieldGrid& coarse_grid, std::vector<float> coarse, int band_voxels) {
  SparseFieldStorage s;
  s.bricks = coarse_grid.dims - Eigen::Vector3i::Ones();
  s.coarse = std::move(coarse);
  s.band_voxels = band_voxels;
  const double H = coarse_grid.spacing, h = H / SparseFieldStorage::kBrick;
  const double band = band_voxels * h, exact = band + h;
  s.SetSpacing(h);
  const std::vector<double> corners = FlattenTriangles(mesh);
  const SparseBuild build{s, coarse_grid.origin, H, h, band, exact,
                          SparseFieldStorage::kBrick * s.bricks,  // last fine sample per axis
                          corners};

  // 1. The bricks a triangle's grown box reaches, each with its triangles.
  const BrickCandidates cand = FindCandidateBricks(build, mesh.num_triangles());

  // Bricks no triangle comes near: every sample is farther than EXACT, one sign, the coarse one.
  s.slot.resize(std::size_t(s.bricks.prod()));
  for (int bz = 0; bz < s.bricks.z(); ++bz)
    for (int by = 0; by < s.bricks.y(); ++by)
      for (int bx = 0; bx < s.bricks.x(); ++bx) {
        s.slot[s.BrickIndex(bx, by, bz)] =
            s.coarse[s.CoarseIndex(bx, by, bz)] < 0 ? SparseFieldStorage::kInside : SparseFieldStorage::kOutside;
      }

  // 2. Exact distances within EXACT of the surface, per candidate brick, in parallel.
  std::vector<std::vector<float>> kept(cand.candidate.size());
  std::vector<std::int32_t> code(cand.candidate.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cand.candidate.size(), 4),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      BrickScratch scratch;
                      for (std::size_t c = r.begin(); c < r.end(); ++c) {
                        code[c] = BuildCandidateBrick(build, sign, cand, c, &scratch, &kept[c]);
                      }
                    });

  // 3. Stored bricks in Morton order, quantised.
  StoreBricks(cand.candidate, kept, code, h, &s);
  return s;
}

}  // namespace contactlab
