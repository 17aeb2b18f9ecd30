#include "baselines/pressure_field/pressure_field_model.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "geometry/pose.h"
#include "util/error.h"

namespace contactlab {
namespace {

constexpr int kBlock = 4;                  // cells per block side
constexpr int kVerts = kBlock + 1;         // vertices per block side
constexpr int kBlockVerts = kVerts * kVerts * kVerts;
constexpr double kCullMargin = 0.5;        // cells: blocks kept within this of the surface (K_B steps)

inline int VertexIndex(int i, int j, int k) { return i + kVerts * (j + kVerts * k); }

// One polygon vertex: position (B's frame) and the two fields there.
struct PolyVertex {
  Eigen::Vector3d x;
  double phi_M, phi_L;  // the other body's field and the lattice body's
};

inline PolyVertex Lerp(const PolyVertex& a, const PolyVertex& b, double t) {
  return {a.x + t * (b.x - a.x), a.phi_M + t * (b.phi_M - a.phi_M), a.phi_L + t * (b.phi_L - a.phi_L)};
}

// Clips the convex polygon IN (N vertices) to the side where the field SELECTed is <= 0; OUT
// holds up to N + 1 vertices. Returns their number.
template <class Select>
int ClipInside(const PolyVertex* in, int n, Select value, PolyVertex* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const PolyVertex& a = in[i];
    const PolyVertex& b = in[(i + 1) % n];
    const double va = value(a), vb = value(b);
    if (va <= 0) out[m++] = a;
    if ((va <= 0) != (vb <= 0)) out[m++] = Lerp(a, b, va / (va - vb));
  }
  return m;
}

// The six Kuhn tetrahedra of a cube: corners by bit (x = 1, y = 2, z = 4), each from corner 0 to
// corner 7 along the axes in one order.
constexpr int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};

}  // namespace

struct PressureFieldModel::Sums {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // B's frame
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // about B's origin
  double area = 0;
  double max_penetration = 0;
};

PressureFieldModel::PressureFieldModel(PressureFieldSide A, PressureFieldSide B, const PressureFieldOptions& options)
    : options_(options) {
  const char* where = "pressure-field";
  for (const PressureFieldSide* s : {&A, &B}) {
    const char* body = s == &A ? "body A" : "body B";
    if (!s->field || s->field->empty()) Fail(where, std::string(body) + " has no distance field");
    if (s->field->info().mode == "soup") {
      Fail(where, std::string(body) + "'s field is a polygon soup's offset band, not a volume with a pressure field");
    }
    if (!(s->field->min_value() < 0)) Fail(where, std::string(body) + "'s field has no inside (no negative sample)");
    if (!s->rigid && !(s->modulus > 0)) Fail(where, std::string(body) + "'s modulus must be > 0");
  }
  if (A.rigid && B.rigid) Fail(where, "both bodies are rigid: a pressure field needs one compliant body");
  if (!(options_.lipschitz >= 1) || !(options_.fd_step > 0) || options_.max_blocks < 1 || options_.lattice < 1) {
    Fail(where, "lipschitz must be >= 1, fd_step > 0, max_blocks >= 1 and lattice >= 1");
  }
  depth_A_ = -double(A.field->min_value());
  depth_B_ = -double(B.field->min_value());
  const Aabb box_B = B.field->box();
  radius_B_ = box_B.min.cwiseAbs().cwiseMax(box_B.max.cwiseAbs()).norm();
  lattice_is_A_ = A.field->spacing() < B.field->spacing();
  L_ = lattice_is_A_ ? std::move(A) : std::move(B);
  M_ = lattice_is_A_ ? std::move(B) : std::move(A);
  kL_ = L_.rigid ? 0 : L_.modulus / -double(L_.field->min_value());
  kM_ = M_.rigid ? 0 : M_.modulus / -double(M_.field->min_value());
  h_ = L_.field->spacing() * options_.lattice;
  // Every block of L's box at spacing h fits (capped).
  const Eigen::Vector3d extent = L_.field->box().size() / (h_ * kBlock);
  const double fit = std::ceil(extent.x() + 1) * std::ceil(extent.y() + 1) * std::ceil(extent.z() + 1);
  const std::int64_t capacity = std::int64_t(std::min<double>(fit, double(options_.max_blocks)));
  blocks_.resize(std::size_t(capacity));
  block_phi_L_.resize(std::size_t(capacity) * kBlockVerts);
  block_surface_.resize(std::size_t(capacity));
  surface_cells_.resize(std::size_t(capacity) * kBlock * kBlock * kBlock);
  parent_.resize(surface_cells_.size());
}

bool PressureFieldModel::KeepContactSurface(int max_triangles) {
  record_capacity_ = std::max(0, max_triangles);
  surface_.reserve(std::size_t(record_capacity_) * 3);
  surface_pressure_.reserve(std::size_t(record_capacity_) * 3);
  return true;
}

void PressureFieldModel::LatestContactSurface(ContactSurface* out) const {
  out->corners.resize(surface_.size());
  for (std::size_t i = 0; i < surface_.size(); ++i) out->corners[i] = (X_WL_ * surface_[i].cast<double>()).cast<float>();
  out->pressure = surface_pressure_;
}

bool PressureFieldModel::FindBlocks(const Pose& X_LM, std::int64_t* nodes) {
  num_blocks_ = 0;
  const DistanceField& fM = *M_.field;
  const DistanceField& fL = *L_.field;
  // The overlap of A's box (in B's frame) and B's box.
  const Aabb a = fM.box(), b = fL.box();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner((c & 1) ? a.max.x() : a.min.x(), (c & 2) ? a.max.y() : a.min.y(),
                                 (c & 4) ? a.max.z() : a.min.z());
    const Eigen::Vector3d p = X_LM * corner;
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  lo = lo.cwiseMax(b.min);
  hi = hi.cwiseMin(b.max);
  if ((lo.array() >= hi.array()).any()) return false;
  const Eigen::Vector3d o_L = fL.origin();
  for (int d = 0; d < 3; ++d) {
    origin_[d] = o_L[d] + h_ * std::floor((lo[d] - o_L[d]) / h_);
    cells_[d] = std::max(1, int(std::ceil((hi[d] - origin_[d]) / h_)));
  }
  stride_j_ = std::int64_t(cells_.x()) + kBlock;
  stride_k_ = stride_j_ * (cells_.y() + kBlock);
  int root = kBlock;
  while (root < cells_.maxCoeff()) root *= 2;

  const Pose X_ML = X_LM.Inverse();
  const double lip = options_.lipschitz;
  const bool both = !M_.rigid && !L_.rigid;
  const double lip_g = both ? lip * (kM_ + kL_) : lip;
  const double margin = kCullMargin * h_;
  struct Node {
    std::int32_t i, j, k, size;
  };
  Node stack[512];
  int top = 0;
  stack[top++] = {0, 0, 0, root};
  while (top > 0) {
    const Node n = stack[--top];
    if (n.i >= cells_.x() || n.j >= cells_.y() || n.k >= cells_.z()) continue;
    ++*nodes;
    const double half = 0.5 * n.size;
    const Eigen::Vector3d c = origin_ + h_ * Eigen::Vector3d(n.i + half, n.j + half, n.k + half);
    const double r = h_ * half * std::sqrt(3.0);
    const double phi_L = fL.Distance(c);
    const double phi_M = fM.Distance(X_ML * c);
    const double reach = lip * r + margin;
    if (phi_M > reach || phi_L > reach) continue;
    if (std::abs(Gap(phi_M, phi_L)) > lip_g * (r + margin)) continue;
    if (n.size > kBlock) {
      const std::int32_t s = n.size / 2;
      for (int q = 0; q < 8; ++q) {
        stack[top++] = {n.i + ((q & 1) ? s : 0), n.j + ((q & 2) ? s : 0), n.k + ((q & 4) ? s : 0), s};
      }
      continue;
    }
    if (num_blocks_ >= std::int64_t(blocks_.size())) continue;  // over capacity: not rendered
    blocks_[std::size_t(num_blocks_)] = {n.i, n.j, n.k};
    float* phi = block_phi_L_.data() + num_blocks_ * kBlockVerts;
    for (int k = 0; k < kVerts; ++k) {
      for (int j = 0; j < kVerts; ++j) {
        for (int i = 0; i < kVerts; ++i) {
          const Eigen::Vector3d x = origin_ + h_ * Eigen::Vector3d(n.i + i, n.j + j, n.k + k);
          phi[VertexIndex(i, j, k)] = float(fL.Distance(x));
        }
      }
    }
    ++num_blocks_;
  }
  return num_blocks_ > 0;
}

void PressureFieldModel::Integrate(const Pose& X_LM, bool record, Sums* sums) {
  const DistanceField& fM = *M_.field;
  const Pose X_ML = X_LM.Inverse();
  const Eigen::Matrix3d R_ML = X_ML.R();
  const Eigen::Vector3d step_i = R_ML.col(0) * h_, step_j = R_ML.col(1) * h_, step_k = R_ML.col(2) * h_;
  const bool clip_M = !M_.rigid, clip_L = !L_.rigid;
  auto pressure = [&](const PolyVertex& v) {
    const double pM = -kM_ * v.phi_M, pL = -kL_ * v.phi_L;
    const double p = M_.rigid ? pL : L_.rigid ? pM : 0.5 * (pM + pL);
    return std::max(0.0, p);
  };
  if (record) {
    num_surface_cells_ = 0;
    surface_.clear();
    surface_pressure_.clear();
    std::fill(block_surface_.begin(), block_surface_.begin() + num_blocks_, std::uint8_t(0));
  }
  float phi_M[kBlockVerts];
  for (std::int64_t bi = 0; bi < num_blocks_; ++bi) {
    const auto& blk = blocks_[std::size_t(bi)];
    const float* phi_L = block_phi_L_.data() + bi * kBlockVerts;
    const Eigen::Vector3d x0 = origin_ + h_ * Eigen::Vector3d(blk[0], blk[1], blk[2]);
    const Eigen::Vector3d a0 = X_ML * x0;
    for (int k = 0; k < kVerts; ++k) {
      for (int j = 0; j < kVerts; ++j) {
        Eigen::Vector3d a = a0 + double(j) * step_j + double(k) * step_k;
        for (int i = 0; i < kVerts; ++i, a += step_i) {
          phi_M[VertexIndex(i, j, k)] = fM.Distance(float(a.x()), float(a.y()), float(a.z()));
        }
      }
    }
    for (int ck = 0; ck < kBlock; ++ck) {
      for (int cj = 0; cj < kBlock; ++cj) {
        for (int ci = 0; ci < kBlock; ++ci) {
          PolyVertex corner[8];
          double g[8];
          int positive = 0;
          bool outside_M = true, outside_L = true, inside_M = true, inside_L = true;
          for (int c = 0; c < 8; ++c) {
            const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
            const int v = VertexIndex(ci + di, cj + dj, ck + dk);
            corner[c].phi_M = phi_M[v];
            corner[c].phi_L = phi_L[v];
            g[c] = Gap(corner[c].phi_M, corner[c].phi_L);
            positive += g[c] > 0;
            outside_M = outside_M && corner[c].phi_M > 0;
            outside_L = outside_L && corner[c].phi_L > 0;
            inside_M = inside_M && corner[c].phi_M <= 0;
            inside_L = inside_L && corner[c].phi_L <= 0;
          }
          if (positive == 0 || positive == 8 || (clip_M && outside_M) || (clip_L && outside_L)) continue;
          for (int c = 0; c < 8; ++c) {
            corner[c].x = x0 + h_ * Eigen::Vector3d(ci + (c & 1), cj + ((c >> 1) & 1), ck + ((c >> 2) & 1));
          }
          double cell_area = 0;
          for (const auto& tet : kTets) {
            int pos[4], neg[4], np = 0, nn = 0;
            for (int t = 0; t < 4; ++t) (g[tet[t]] > 0 ? pos[np++] : neg[nn++]) = tet[t];
            if (np == 0 || nn == 0) continue;
            PolyVertex buffers[2][8];
            PolyVertex* poly = buffers[0];
            int m = 0;
            auto cut = [&](int p, int q) { return Lerp(corner[p], corner[q], g[p] / (g[p] - g[q])); };
            if (np == 1) {
              for (int t = 0; t < 3; ++t) poly[m++] = cut(pos[0], neg[t]);
            } else if (nn == 1) {
              for (int t = 0; t < 3; ++t) poly[m++] = cut(pos[t], neg[0]);
            } else {
              poly[m++] = cut(pos[0], neg[0]);
              poly[m++] = cut(pos[0], neg[1]);
              poly[m++] = cut(pos[1], neg[1]);
              poly[m++] = cut(pos[1], neg[0]);
            }
            // A cell inside a body at every corner is inside it throughout (the fields are linear
            // on each tetrahedron): nothing to clip.
            // Each clip writes into the other buffer, which then holds the polygon.
            if (clip_M && !inside_M) {
              PolyVertex* out = poly == buffers[0] ? buffers[1] : buffers[0];
              m = ClipInside(poly, m, [](const PolyVertex& v) { return v.phi_M; }, out);
              poly = out;
            }
            if (clip_L && !inside_L) {
              PolyVertex* out = poly == buffers[0] ? buffers[1] : buffers[0];
              m = ClipInside(poly, m, [](const PolyVertex& v) { return v.phi_L; }, out);
              poly = out;
            }
            if (m < 3) continue;
            // Toward decreasing g: from the positive corners to the others.
            Eigen::Vector3d toward = Eigen::Vector3d::Zero();
            for (int t = 0; t < nn; ++t) toward += corner[neg[t]].x / nn;
            for (int t = 0; t < np; ++t) toward -= corner[pos[t]].x / np;
            Eigen::Vector3d area_vector = Eigen::Vector3d::Zero();
            for (int t = 1; t + 1 < m; ++t) area_vector += (poly[t].x - poly[0].x).cross(poly[t + 1].x - poly[0].x);
            const double sign = area_vector.dot(toward) < 0 ? -1.0 : 1.0;
            double p[8];
            for (int t = 0; t < m; ++t) {
              p[t] = pressure(poly[t]);
              sums->max_penetration = std::max(sums->max_penetration, -(poly[t].phi_M + poly[t].phi_L));
            }
            for (int t = 1; t + 1 < m; ++t) {
              const Eigen::Vector3d av =
                  0.5 * sign * (poly[t].x - poly[0].x).cross(poly[t + 1].x - poly[0].x);  // area times n
              const double psum = p[0] + p[t] + p[t + 1];
              sums->force += (psum / 3) * av;
              // ∫ x p dA over the triangle (p linear): (A/12) [(Σp)(Σx) + Σ p_i x_i].
              const Eigen::Vector3d xp =
                  (psum * (poly[0].x + poly[t].x + poly[t + 1].x) + p[0] * poly[0].x + p[t] * poly[t].x +
                   p[t + 1] * poly[t + 1].x) / 12;
              sums->torque += xp.cross(av);
              const double area = av.norm();
              cell_area += area;
              if (record && int(surface_pressure_.size()) < 3 * record_capacity_) {
                for (const int v : {0, t, t + 1}) {
                  surface_.push_back(poly[v].x.cast<float>());
                  surface_pressure_.push_back(float(p[v]));
                }
              }
            }
          }
          sums->area += cell_area;
          if (record && cell_area > 0) block_surface_[std::size_t(bi)] = 1;
          if (record && cell_area > 0 && num_surface_cells_ < std::int64_t(surface_cells_.size())) {
            const std::int64_t i = blk[0] + ci, j = blk[1] + cj, k = blk[2] + ck;
            surface_cells_[std::size_t(num_surface_cells_++)] = i + stride_j_ * j + stride_k_ * k;
          }
        }
      }
    }
  }
}

void PressureFieldModel::KeepSurfaceBlocks() {
  std::int64_t kept = 0;
  for (std::int64_t b = 0; b < num_blocks_; ++b) {
    if (!block_surface_[std::size_t(b)]) continue;
    if (kept != b) {
      blocks_[std::size_t(kept)] = blocks_[std::size_t(b)];
      std::copy_n(block_phi_L_.begin() + b * kBlockVerts, kBlockVerts, block_phi_L_.begin() + kept * kBlockVerts);
    }
    ++kept;
  }
  num_blocks_ = kept;
}

int PressureFieldModel::CountPatches() {
  const std::int64_t n = num_surface_cells_;
  if (n == 0) return 0;
  std::int64_t* cells = surface_cells_.data();
  std::sort(cells, cells + n);
  for (std::int64_t i = 0; i < n; ++i) parent_[std::size_t(i)] = std::int32_t(i);
  auto find = [&](std::int32_t x) {
    while (parent_[std::size_t(x)] != x) {
      parent_[std::size_t(x)] = parent_[std::size_t(parent_[std::size_t(x)])];
      x = parent_[std::size_t(x)];
    }
    return x;
  };
  int patches = int(n);
  for (std::int64_t a = 0; a < n; ++a) {
    // The 13 neighbours sharing a face, edge or corner that come later in index order.
    for (int dk = 0; dk <= 1; ++dk) {
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          if (dk == 0 && (dj < 0 || (dj == 0 && di <= 0))) continue;
          const std::int64_t key = cells[a] + di + stride_j_ * dj + stride_k_ * dk;
          const std::int64_t* it = std::lower_bound(cells, cells + n, key);
          if (it == cells + n || *it != key) continue;
          const std::int32_t ra = find(std::int32_t(a)), rb = find(std::int32_t(it - cells));
          if (ra != rb) {
            parent_[std::size_t(std::max(ra, rb))] = std::min(ra, rb);
            --patches;
          }
        }
      }
    }
  }
  return patches;
}

Wrench PressureFieldModel::OnB(const Sums& sums, const Pose& X_WA, const Pose& X_WB) const {
  Wrench w;
  if (!lattice_is_A_) {
    const Eigen::Matrix3d R = X_WB.R();
    w.force = R * sums.force;
    w.torque = R * sums.torque;
    return w;
  }
  // The sums are the wrench on A about A's origin: B feels the opposite, about its own origin.
  const Eigen::Matrix3d R = X_WA.R();
  const Eigen::Vector3d F_A = R * sums.force, T_A = R * sums.torque;
  w.force = -F_A;
  w.torque = -(T_A + (X_WA.translation - X_WB.translation).cross(F_A));
  return w;
}

ContactResult PressureFieldModel::Evaluate(const ContactQuery& query) {
  ContactResult r;
  X_WL_ = lattice_is_A_ ? query.X_WA : query.X_WB;
  const Pose X_LM = LatticeToOther(query.X_WA, query.X_WB);
  std::int64_t nodes = 0;
  const bool overlap = FindBlocks(X_LM, &nodes);
  r.stats.nodes_visited = nodes + num_blocks_ * kBlock * kBlock * kBlock;
  if (!overlap) {
    num_surface_cells_ = 0;
    surface_.clear();
    surface_pressure_.clear();
    return r;
  }
  Sums base;
  Integrate(X_LM, /*record=*/true, &base);
  r.on_B = OnB(base, query.X_WA, query.X_WB);
  r.stats.contact_area = base.area;
  r.stats.max_penetration = std::max(0.0, base.max_penetration);
  r.stats.points_in_contact = std::int32_t(std::min<std::int64_t>(num_surface_cells_, INT32_MAX));
  r.stats.patches = CountPatches();
  if (options_.stiffness && base.area > 0) {
    KeepSurfaceBlocks();
    // Forward differences in B's pose over the blocks with surface: a step of 1/100 cell moves
    // the surface into another block only where it passes within that of a block's face.
    const double step_x = options_.fd_step * h_, step_w = options_.fd_step * h_ / std::max(radius_B_, h_);
    const Vector6d w0 = r.on_B.AsVector();
    for (int c = 0; c < 6; ++c) {
      Pose X_WB = query.X_WB;
      if (c < 3) {
        X_WB.translation[c] += step_x;
      } else {
        Eigen::Vector3d w = Eigen::Vector3d::Zero();
        w[c - 3] = step_w;
        X_WB.rotation = (RotationFromVector(w) * X_WB.rotation).normalized();
      }
      Sums s;
      Integrate(LatticeToOther(query.X_WA, X_WB), /*record=*/false, &s);
      r.K_B.col(c) = (OnB(s, query.X_WA, X_WB).AsVector() - w0) / (c < 3 ? step_x : step_w);
    }
  }
  return r;
}

}  // namespace contactlab
