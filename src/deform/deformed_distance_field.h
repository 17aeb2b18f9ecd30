// The deformed distance field of a reduced deformable body (Barbič & James 2008, sec. 4.2):
// approximate signed distances to the deformed body, at haptic rates, from its rest field.
//
// A proxyshell of a few (default 40) proxies is fitted to the rest surface by the pointshells'
// particle repulsion and embedded in the simulation mesh. At reduced coordinates q each proxy
// i sits at p_i = P_i + U_i q with deformation gradient F_i = I + sum_j F_ij q_j (smooth
// gradient modes, EmbeddedPoints). A query x takes the k nearest deformed proxies, weights
//     w_i ~ 1/|x - p_i| - 1/d_max   (eq. (3); d_max the k-th distance, so w_k = 0),
// pulls x back through each proxy's first-order model, X_i = P_i + F_i^{-1} (x - p_i), and
// returns d = sum_i w_i d_rest(X_i). The weights are continuous and vanish at the k-th
// neighbour, so d is C^0 in x and in q. Outside the rest field's box, d_rest is its conservative
// bound (DistanceField), applied at X_i.
//
// Domains (Fig. 10(c)). Proxies of one part pull a point near another part back onto the wrong
// geometry ("mirroring") when the parts move apart. The body is therefore split into convex
// domains of the rest configuration, each with its own rest field, the body cut to the domain
// widened by OVERLAP, d_D = max(d_rest, s_D - overlap) with s_D the region's signed plane
// distance, and its own proxies (those within OVERLAP of it, and at least the k nearest to it);
// the field is the minimum over
// domains. Cut faces lie OVERLAP inside the neighbouring domain, so at rest the minimum equals
// d_rest wherever d_rest > -overlap. Domains are user-given convex regions (boxes, halfspaces)
// or the Voronoi cells of a k-means clustering of the proxies' rest positions.
//
// Evaluation is split: a DeformedFieldState, sized once, holds each proxy's deformed position
// and affine pull-back for the q of this cycle (Update: about 12 r flops a proxy); Distance then
// costs a scan over the proxies and k-1 rest-field lookups per domain, allocation-free.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "deform/embedded_points.h"
#include "deform/tet_mesh.h"
#include "geometry/aabb.h"
#include "sdf/distance_field.h"

namespace contactlab {

// Largest k of the k-nearest-proxy query.
inline constexpr int kMaxProxyNeighbours = 16;

// A convex region of the rest configuration: the points X with n . X <= c for every plane
// (n, c), n a unit vector. No planes: all of space.
struct DomainRegion {
  std::vector<Eigen::Vector4d> planes;  // (n_x, n_y, n_z, c)
  std::string description;              // for listings and errors

  // max over planes of n . X - c (-infinity without planes): <= 0 inside; outside, a lower
  // bound on the distance to the region (exact for one plane), so 1-Lipschitz.
  double SignedDistance(const Eigen::Vector3d& X) const;
  static DomainRegion Box(const Aabb& box);
  // The side n . X <= c of a plane (N need not be unit; it is normalised with C).
  static DomainRegion Halfspace(const Eigen::Vector3d& n, double c);
};

struct DeformedFieldOptions {
  int proxies = 40;                  // proxyshell points fitted to the whole body
  int neighbours = 5;                // k, in [2, kMaxProxyNeighbours]
  std::vector<DomainRegion> regions; // explicit domains; empty: DOMAINS automatic clusters
  int domains = 1;                   // automatic domains (k-means of the proxies), >= 1
  double overlap = -1;               // metres by which domains overlap; < 0: 3 rest-field cells
  std::uint64_t seed = 1;            // proxy fitting and clustering
  // Where a contact force on the body acts on its deformation: at the nearest proxy (the
  // paper's choice, U_p^T F), or spread over the k proxies with the weights of the query,
  // sum_i w_i U_i^T F, which matches how the field moves with q to first order and does not
  // jump when the nearest proxy changes.
  enum class ForceAt { kNearestProxy, kWeightedProxies };
  ForceAt force_at = ForceAt::kNearestProxy;
};

class DeformedDistanceField;

// The deformation-dependent part of a deformed field: per proxy slot its deformed position
// and the affine pull-back X = c + A x (A = F^{-1}, c = P - A p), flat floats sized once.
class DeformedFieldState {
 public:
  DeformedFieldState() = default;
  explicit DeformedFieldState(const DeformedDistanceField& field);
  // Proxies at reduced coordinates Q (r entries; null: at rest). Allocation-free. A proxy whose
  // deformation gradient is (nearly) singular or inverted, det F <= 1e-3, keeps F = I.
  void Update(const DeformedDistanceField& field, const double* q);
  // Sets proxy slot I to position P (deformed) and gradient F directly (e.g. a rigid motion
  // applied through F in tests). F must be invertible.
  void Set(const DeformedDistanceField& field, int i, const Eigen::Vector3d& p, const Eigen::Matrix3d& F);
  // Deformed position of proxy slot I, and the coordinates of all slots (structure of arrays).
  Eigen::Vector3f position(int i) const { return Eigen::Vector3f(x_[i], y_[i], z_[i]); }
  const float* xs() const { return x_.data(); }
  const float* ys() const { return y_.data(); }
  const float* zs() const { return z_.data(); }
  const float* pullback(int i) const { return &a_[12 * std::size_t(i)]; }  // A row-major, then c

  // What bounds a domain's distance from below without querying it. Every slot i of the domain
  // pulls x back to X_i = c_i + A_i x; against the domain's mean map (A, c) and the mean O of
  // its deformed proxies,
  //   |X_i - (c + A x)| <= spread + slope |x - O|,
  // spread = max_i |c_i - c + (A_i - A) O| and slope = max_i ||A_i - A||_F. When c + A x lies
  // farther than that from the domain field's grid box, every pulled-back point is outside the
  // box, where the field is its conservative bound (distance to the box + boundary_min), and the
  // domain's distance, a convex combination of such values, is at least the smallest of them
  // (DeformedFieldDomainBounds, deform/deformed_field_batch.h).
  struct DomainBound {
    float a[9], c[3], o[3];  // A row-major, c, O
    float spread, slope;
  };
  const DomainBound& domain_bound(int d) const { return bounds_[d]; }  // kept with several domains only

 private:
  void SetSlot(const DeformedDistanceField& field, int i, const Eigen::Vector3d& p, const Eigen::Matrix3d& F);
  void UpdateBounds(const DeformedDistanceField& field);

  std::vector<float> x_, y_, z_;  // (#slots) deformed proxy positions
  std::vector<float> a_;          // (#slots x 12)
  std::vector<DomainBound> bounds_;  // (#domains)
};

// Levels of a domain field below which its samples lie only inside a box: for level j, every
// sample <= tau[j] lies in the box (lo[j], hi[j]) shrunk by one cell, so the trilinear field
// exceeds tau[j] at any point outside the box. Levels above the field's boundary_min are left
// out (outside the grid the field is its conservative bound, which may be smaller).
inline constexpr int kDomainBoundLevels = 6;
struct DomainLevels {
  float lo[kDomainBoundLevels][3], hi[kDomainBoundLevels][3], tau[kDomainBoundLevels];
  int count = 0;
};

class DeformedDistanceField {
 public:
  // Builds the proxyshell on REST's zero level set, embeds it in MESH with basis U (3#V x r),
  // forms the domains and their fields. WHERE names the body in errors. Throws Error for bad
  // options (more than proxies / 2 automatic domains), a domain holding no geometry, or
  // domains that leave part of the body's interior uncovered.
  DeformedDistanceField(std::shared_ptr<const DistanceField> rest, const TetMesh& mesh, const Eigen::MatrixXd& U,
                        const DeformedFieldOptions& options, const std::string& where);

  int r() const { return proxies_.r(); }
  int neighbours() const { return k_; }
  int num_proxies() const { return num_proxies_; }  // distinct proxies fitted
  int num_slots() const { return proxies_.size(); } // proxy slots over all domains (shared ones repeat)
  int num_domains() const { return int(domains_.size()); }
  double overlap() const { return overlap_; }
  const DistanceField& rest_field() const { return *rest_; }
  const DistanceField& domain_field(int d) const { return *domains_[d].field; }
  const DomainRegion& domain_region(int d) const { return domains_[d].region; }
  const DomainLevels& domain_levels(int d) const { return domains_[d].levels; }
  int slot_begin(int d) const { return domains_[d].begin; }
  // The domain holding proxy slot SLOT.
  int domain_of_slot(int slot) const {
    int d = 0;
    while (d + 1 < num_domains() && slot >= domains_[d].end) ++d;
    return d;
  }
  DeformedFieldOptions::ForceAt force_at() const { return force_at_; }
  int slot_end(int d) const { return domains_[d].end; }
  // Proxy slots embedded in the mesh: rest positions, bases U_i (for forces), gradients.
  const EmbeddedPoints& proxies() const { return proxies_; }
  // Largest displacement of any proxy per unit q_j (r entries).
  float mode_travel(int j) const { return travel_[j]; }

  // Approximate deformed distance at X (body frame) for STATE; NEAREST (may be null) gets the
  // nearest proxy slot of the domain that gave the minimum. Allocation-free, never throws.
  float Distance(const DeformedFieldState& state, const float* x, int* nearest) const {
    float best = std::numeric_limits<float>::infinity();
    int best_slot = -1;
    for (const Domain& D : domains_) {
      int slot;
      const float d = DomainDistance(D, state, x, &slot);
      if (d < best) {
        best = d;
        best_slot = slot;
      }
    }
    if (nearest != nullptr) *nearest = best_slot;
    return best;
  }
  double Distance(const DeformedFieldState& state, const Eigen::Vector3d& x, int* nearest = nullptr) const {
    const float xf[3] = {float(x.x()), float(x.y()), float(x.z())};
    return Distance(state, xf, nearest);
  }

  // The k nearest slots of domain D to X and their weights (eq. (3)), nearest first; returns k.
  int Weights(const DeformedFieldState& state, int d, const float* x, int* slots, float* weights) const;

  // Lines describing proxies, k, domains (with their proxies and field sizes).
  std::string Describe() const;

 private:
  struct Domain {
    std::shared_ptr<const DistanceField> field;
    DomainRegion region;
    DomainLevels levels;     // with several domains (DeformedFieldDomainBounds)
    int begin = 0, end = 0;  // proxy slots [begin, end)
  };

  // The k nearest slots of D (sorted by distance) and normalised weights; returns k.
  int Nearest(const Domain& D, const DeformedFieldState& state, const float* x, int* slots, float* w) const {
    float d2[kMaxProxyNeighbours + 1];
    int n = 0;
    const float* px = state.xs();
    const float* py = state.ys();
    const float* pz = state.zs();
    // Squared distances a chunk at a time (a loop the compiler vectorises), then insertion of
    // the few that beat the current k-th.
    constexpr int kChunk = 64;
    float e[kChunk];
    for (int begin = D.begin; begin < D.end; begin += kChunk) {
      const int count = std::min(kChunk, D.end - begin);
      for (int c = 0; c < count; ++c) {
        const float dx = x[0] - px[begin + c], dy = x[1] - py[begin + c], dz = x[2] - pz[begin + c];
        e[c] = dx * dx + dy * dy + dz * dz;
      }
      for (int c = 0; c < count; ++c) {
        if (n == k_ && !(e[c] < d2[k_ - 1])) continue;
        int m = n < k_ ? n++ : k_ - 1;  // insert at m, shifting larger ones up
        while (m > 0 && d2[m - 1] > e[c]) {
          d2[m] = d2[m - 1];
          slots[m] = slots[m - 1];
          --m;
        }
        d2[m] = e[c];
        slots[m] = begin + c;
      }
    }
    // w_i ~ 1/d_i - 1/d_max (eq. (3)); the k-th weight is zero.
    const float dmax = std::sqrt(d2[n - 1]);
    const float inv_max = dmax > 0 ? 1.f / dmax : 0.f;
    float W = 0;
    for (int i = 0; i < n; ++i) {
      const float di = std::sqrt(d2[i]);
      w[i] = (di > 1e-20f ? 1.f / di : 1e20f) - inv_max;
      if (!(w[i] > 0)) w[i] = 0;
      W += w[i];
    }
    if (!(W > 0) || !(W < std::numeric_limits<float>::infinity())) {  // all equidistant (or x on a proxy)
      float s = 0;
      for (int i = 0; i < n; ++i) s += (w[i] = (d2[i] <= d2[0] ? 1.f : 0.f));
      W = s;
    }
    const float inv_W = 1.f / W;
    for (int i = 0; i < n; ++i) w[i] *= inv_W;
    return n;
  }

  float DomainDistance(const Domain& D, const DeformedFieldState& state, const float* x, int* nearest) const {
    int slots[kMaxProxyNeighbours];
    float w[kMaxProxyNeighbours];
    const int n = Nearest(D, state, x, slots, w);
    float d = 0;
    for (int i = 0; i < n; ++i) {
      if (w[i] == 0.f) continue;
      const float* a = state.pullback(slots[i]);
      const float X = a[9] + a[0] * x[0] + a[1] * x[1] + a[2] * x[2];
      const float Y = a[10] + a[3] * x[0] + a[4] * x[1] + a[5] * x[2];
      const float Z = a[11] + a[6] * x[0] + a[7] * x[1] + a[8] * x[2];
      d += w[i] * D.field->Distance(X, Y, Z);
    }
    *nearest = slots[0];
    return d;
  }

  std::shared_ptr<const DistanceField> rest_;
  std::vector<Domain> domains_;
  EmbeddedPoints proxies_;  // slots, domain by domain
  int k_ = 5;
  DeformedFieldOptions::ForceAt force_at_ = DeformedFieldOptions::ForceAt::kNearestProxy;
  int num_proxies_ = 0;
  double overlap_ = 0;
  std::vector<float> travel_;  // (r)
};

// Parses "auto" counts and regions are set by the caller; this checks OPTIONS, naming WHERE.
void ValidateDeformedFieldOptions(const DeformedFieldOptions& options, const std::string& where);

}  // namespace contactlab
