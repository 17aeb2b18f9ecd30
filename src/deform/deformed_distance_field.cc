// Barbič & James 2008, sec. 4.2: the proxy-based deformed distance field and its domains.
#include "deform/deformed_distance_field.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "pointshell/build_pointshell.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Deterministic k-means (k-means++ seeding, Lloyd iterations) of POINTS into K clusters;
// returns the centroids.
std::vector<Eigen::Vector3d> KMeans(const std::vector<Eigen::Vector3d>& points, int k, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Eigen::Vector3d> c;
  c.push_back(points[std::uniform_int_distribution<std::size_t>(0, points.size() - 1)(rng)]);
  std::vector<double> d2(points.size());
  while (int(c.size()) < k) {
    double total = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& ci : c) best = std::min(best, (points[i] - ci).squaredNorm());
      total += (d2[i] = best);
    }
    double pick = std::uniform_real_distribution<double>(0, total)(rng);
    std::size_t chosen = points.size() - 1;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if ((pick -= d2[i]) <= 0) {
        chosen = i;
        break;
      }
    }
    c.push_back(points[chosen]);
  }
  std::vector<int> label(points.size(), -1);
  for (int it = 0; it < 100; ++it) {
    bool changed = false;
    for (std::size_t i = 0; i < points.size(); ++i) {
      int best = 0;
      for (int a = 1; a < k; ++a) {
        if ((points[i] - c[a]).squaredNorm() < (points[i] - c[best]).squaredNorm()) best = a;
      }
      changed |= label[i] != best;
      label[i] = best;
    }
    if (!changed) break;
    std::vector<Eigen::Vector3d> sum(std::size_t(k), Eigen::Vector3d::Zero());
    std::vector<int> count(std::size_t(k), 0);
    for (std::size_t i = 0; i < points.size(); ++i) {
      sum[label[i]] += points[i];
      ++count[label[i]];
    }
    for (int a = 0; a < k; ++a) {
      if (count[a] > 0) c[a] = sum[a] / count[a];
    }
  }
  return c;
}

// The Voronoi cells of CENTROIDS as domain regions.
std::vector<DomainRegion> VoronoiRegions(const std::vector<Eigen::Vector3d>& centroids) {
  std::vector<DomainRegion> regions(centroids.size());
  for (std::size_t a = 0; a < centroids.size(); ++a) {
    for (std::size_t b = 0; b < centroids.size(); ++b) {
      if (a == b) continue;
      const Eigen::Vector3d n = centroids[b] - centroids[a];
      if (n.norm() <= 0) continue;
      const Eigen::Vector3d u = n.normalized();
      regions[a].planes.emplace_back(u.x(), u.y(), u.z(), u.dot(0.5 * (centroids[a] + centroids[b])));
    }
    char buf[160];
    std::snprintf(buf, sizeof buf, "cluster %zu around (%.4g, %.4g, %.4g)", a, centroids[a].x(), centroids[a].y(),
                  centroids[a].z());
    regions[a].description = buf;
  }
  return regions;
}

// REST cut to REGION widened by OVERLAP, max(d, s - overlap), on the sub-grid of REST whose
// samples of the cut field are within BAND of the surface (grown by one cell): outside that
// box the field's conservative bound holds, as the cut field is 1-Lipschitz.
std::shared_ptr<const DistanceField> CutField(const DistanceField& rest, const DomainRegion& region, double overlap,
                                              double band) {
  const Eigen::Vector3i n = rest.dims();
  std::vector<float> cut(rest.values().size());
  Eigen::Vector3i lo = n, hi(-1, -1, -1);
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const double s = region.SignedDistance(rest.GridPoint(i, j, k)) - overlap;
        const float v = float(std::max(double(rest.value(i, j, k)), s));
        cut[rest.Index(i, j, k)] = v;
        if (v <= band) {
          lo = lo.cwiseMin(Eigen::Vector3i(i, j, k));
          hi = hi.cwiseMax(Eigen::Vector3i(i, j, k));
        }
      }
  if (hi.x() < 0) return nullptr;
  for (int c = 0; c < 3; ++c) {
    lo[c] = std::max(lo[c] - 1, 0);
    hi[c] = std::min(hi[c] + 1, n[c] - 1);
    if (hi[c] - lo[c] < 1) {  // at least two samples per axis
      if (hi[c] + 1 < n[c]) ++hi[c];
      else --lo[c];
    }
  }
  const Eigen::Vector3i dims = hi - lo + Eigen::Vector3i::Ones();
  std::vector<float> values(std::size_t(dims.x()) * dims.y() * dims.z());
  std::size_t o = 0;
  for (int k = lo.z(); k <= hi.z(); ++k)
    for (int j = lo.y(); j <= hi.y(); ++j)
      for (int i = lo.x(); i <= hi.x(); ++i) values[o++] = cut[rest.Index(i, j, k)];
  DistanceFieldInfo info = rest.info();
  info.source += " [" + region.description + "]";
  return std::make_shared<const DistanceField>(rest.GridPoint(lo.x(), lo.y(), lo.z()), rest.spacing(), dims,
                                               std::move(values), info);
}

// The levels 0, 1/2, 1, 2, 3 and 4 cells of FIELD (a dense domain field) up to its
// boundary_min, with their boxes, from one pass over the samples.
DomainLevels BoundLevels(const DistanceField& field) {
  DomainLevels lv;
  const Eigen::Vector3i n = field.dims();
  const double h = field.spacing();
  for (double cells : {0.0, 0.5, 1.0, 2.0, 3.0, 4.0}) {
    const float tau = float(cells * h);
    if (tau > field.boundary_min()) break;
    lv.tau[lv.count++] = tau;
  }
  std::vector<Eigen::Vector3i> lo(std::size_t(lv.count), n), hi(std::size_t(lv.count), Eigen::Vector3i(-1, -1, -1));
  for (int k = 0; k < n.z(); ++k)
    for (int j = 0; j < n.y(); ++j)
      for (int i = 0; i < n.x(); ++i) {
        const float v = field.value(i, j, k);
        for (int l = lv.count - 1; l >= 0 && v <= lv.tau[l]; --l) {  // the levels v is at or below
          lo[l] = lo[l].cwiseMin(Eigen::Vector3i(i, j, k));
          hi[l] = hi[l].cwiseMax(Eigen::Vector3i(i, j, k));
        }
      }
  for (int l = 0; l < lv.count; ++l) {
    for (int c = 0; c < 3; ++c) {
      if (hi[l].x() < 0) {  // no sample that low: the field exceeds tau everywhere
        lv.lo[l][c] = std::numeric_limits<float>::infinity();
        lv.hi[l][c] = -std::numeric_limits<float>::infinity();
        continue;
      }
      // The cells around those samples, grown by a little more than float rounding.
      lv.lo[l][c] = float(field.origin()[c] + (std::max(lo[l][c] - 1, 0) - 1e-3) * h);
      lv.hi[l][c] = float(field.origin()[c] + (std::min(hi[l][c] + 1, n[c] - 1) + 1e-3) * h);
    }
  }
  return lv;
}

}  // namespace

double DomainRegion::SignedDistance(const Eigen::Vector3d& X) const {
  double s = -std::numeric_limits<double>::infinity();
  for (const Eigen::Vector4d& p : planes) s = std::max(s, p.head<3>().dot(X) - p[3]);
  return s;
}

DomainRegion DomainRegion::Box(const Aabb& box) {
  DomainRegion r;
  for (int c = 0; c < 3; ++c) {
    Eigen::Vector4d lo = Eigen::Vector4d::Zero(), hi = Eigen::Vector4d::Zero();
    lo[c] = -1;
    lo[3] = -box.min[c];
    hi[c] = 1;
    hi[3] = box.max[c];
    r.planes.push_back(lo);
    r.planes.push_back(hi);
  }
  char buf[200];
  std::snprintf(buf, sizeof buf, "box [%.4g, %.4g, %.4g] - [%.4g, %.4g, %.4g]", box.min.x(), box.min.y(), box.min.z(),
                box.max.x(), box.max.y(), box.max.z());
  r.description = buf;
  return r;
}

DomainRegion DomainRegion::Halfspace(const Eigen::Vector3d& n, double c) {
  DomainRegion r;
  const double len = n.norm();
  r.planes.emplace_back(n.x() / len, n.y() / len, n.z() / len, c / len);
  char buf[160];
  std::snprintf(buf, sizeof buf, "halfspace (%.4g, %.4g, %.4g) . X <= %.4g", n.x(), n.y(), n.z(), c);
  r.description = buf;
  return r;
}

void ValidateDeformedFieldOptions(const DeformedFieldOptions& o, const std::string& where) {
  if (o.neighbours < 2 || o.neighbours > kMaxProxyNeighbours) {
    Fail(where, "neighbours (k) must be in [2, " + std::to_string(kMaxProxyNeighbours) + "], got " +
                    std::to_string(o.neighbours));
  }
  if (o.proxies < o.neighbours || o.proxies > 4096) {
    Fail(where, "proxies must be in [neighbours = " + std::to_string(o.neighbours) + ", 4096], got " +
                    std::to_string(o.proxies));
  }
  if (o.regions.empty() && (o.domains < 1 || o.domains > 64)) {
    Fail(where, "domains must be in [1, 64], got " + std::to_string(o.domains));
  }
  if (o.regions.size() > 64) Fail(where, "at most 64 domains, got " + std::to_string(o.regions.size()));
  for (const DomainRegion& r : o.regions) {
    for (const Eigen::Vector4d& p : r.planes) {
      if (!p.allFinite() || std::abs(p.head<3>().norm() - 1) > 1e-6) {
        Fail(where, "domain " + r.description + " has a plane that is not finite or not normalised");
      }
    }
  }
  if (!std::isfinite(o.overlap)) Fail(where, "domain overlap must be finite");
}

DeformedDistanceField::DeformedDistanceField(std::shared_ptr<const DistanceField> rest, const TetMesh& mesh,
                                             const Eigen::MatrixXd& U, const DeformedFieldOptions& options,
                                             const std::string& where)
    : rest_(std::move(rest)), k_(options.neighbours), force_at_(options.force_at) {
  ValidateDeformedFieldOptions(options, where);
  if (!rest_ || rest_->empty()) Fail(where, "the deformed distance field needs the body's rest field");
  if (rest_->sparse()) Fail(where, "the deformed distance field needs a dense rest field, not a sparse one");
  overlap_ = options.overlap >= 0 ? options.overlap : 3 * rest_->spacing();

  // The proxyshell: one repulsion level on the rest surface.
  PointshellOptions po;
  po.num_points = options.proxies;
  po.num_levels = 1;
  po.offset = 0.0;
  po.seed = options.seed;
  po.show_progress = false;
  const Pointshell shell = BuildPointshell(*rest_, po);
  num_proxies_ = shell.num_points();
  std::vector<Eigen::Vector3d> P(static_cast<std::size_t>(num_proxies_));
  for (int i = 0; i < num_proxies_; ++i) P[i] = Eigen::Vector3d(shell.x[i], shell.y[i], shell.z[i]);

  // Domains: the user's regions or the Voronoi cells of clustered proxies.
  std::vector<DomainRegion> regions = options.regions;
  if (regions.empty()) {
    if (options.domains == 1) {
      regions.resize(1);
      regions[0].description = "whole body";
    } else {
      if (options.domains > num_proxies_ / 2) {
        Fail(where, std::to_string(options.domains) + " automatic domains need at least " +
                        std::to_string(2 * options.domains) + " proxies, not " + std::to_string(num_proxies_));
      }
      regions = VoronoiRegions(KMeans(P, options.domains, options.seed));
    }
  }
  // Every interior sample of the rest field must lie in some domain.
  if (regions.size() > 1 || !regions[0].planes.empty()) {
    const Eigen::Vector3i n = rest_->dims();
    for (int k = 0; k < n.z(); ++k)
      for (int j = 0; j < n.y(); ++j)
        for (int i = 0; i < n.x(); ++i) {
          if (rest_->value(i, j, k) >= 0) continue;
          const Eigen::Vector3d X = rest_->GridPoint(i, j, k);
          bool covered = false;
          for (const DomainRegion& r : regions) covered = covered || r.SignedDistance(X) <= 0;
          if (!covered) {
            char buf[200];
            std::snprintf(buf, sizeof buf,
                          "the domains leave part of the body uncovered: (%.4g, %.4g, %.4g) is inside the body and "
                          "in no domain",
                          X.x(), X.y(), X.z());
            Fail(where, buf);
          }
        }
  }

  // Slots: each domain's proxies (those within the overlap of its region), domain by domain.
  std::vector<Eigen::Vector3d> slot_points;
  const double band = 8 * rest_->spacing() + overlap_;
  for (std::size_t d = 0; d < regions.size(); ++d) {
    Domain D;
    D.region = regions[d];
    D.begin = int(slot_points.size());
    // Its proxies: those within the overlap of the region, and at least the k nearest to it.
    std::vector<std::pair<double, int>> by_distance;
    for (int i = 0; i < num_proxies_; ++i) by_distance.emplace_back(D.region.SignedDistance(P[i]), i);
    std::sort(by_distance.begin(), by_distance.end());
    for (int a = 0; a < num_proxies_; ++a) {
      if (a < k_ || by_distance[a].first <= overlap_) slot_points.push_back(P[by_distance[a].second]);
    }
    D.end = int(slot_points.size());
    D.field = D.region.planes.empty() ? rest_ : CutField(*rest_, D.region, overlap_, band);
    if (!D.field) Fail(where, "domain " + std::to_string(d) + " (" + D.region.description + ") holds no geometry");
    if (regions.size() > 1) D.levels = BoundLevels(*D.field);
    domains_.push_back(std::move(D));
  }
  proxies_ = EmbeddedPoints(mesh, U, slot_points, {}, GradientScheme::kSmooth);

  travel_.assign(std::size_t(r()), 0.f);
  for (int i = 0; i < proxies_.size(); ++i) {
    const Eigen::MatrixXd Ui = proxies_.Basis(i);
    for (int j = 0; j < r(); ++j) travel_[j] = std::max(travel_[j], float(Ui.col(j).norm()));
  }
}

int DeformedDistanceField::Weights(const DeformedFieldState& state, int d, const float* x, int* slots,
                                   float* weights) const {
  return Nearest(domains_[d], state, x, slots, weights);
}

std::string DeformedDistanceField::Describe() const {
  std::string s = "deformed distance field: " + std::to_string(num_proxies_) + " proxies, k = " + std::to_string(k_) +
                  ", " + std::to_string(num_domains()) + " domain(s)";
  char buf[64];
  std::snprintf(buf, sizeof buf, ", overlap %.3g m\n", overlap_);
  s += buf;
  for (int d = 0; d < num_domains(); ++d) {
    const Eigen::Vector3i n = domains_[d].field->dims();
    s += "  domain " + std::to_string(d) + ": " + domains_[d].region.description + ", " +
         std::to_string(slot_end(d) - slot_begin(d)) + " proxies, field " + std::to_string(n.x()) + "x" +
         std::to_string(n.y()) + "x" + std::to_string(n.z()) + "\n";
  }
  return s;
}

DeformedFieldState::DeformedFieldState(const DeformedDistanceField& field)
    : x_(std::size_t(field.num_slots())),
      y_(std::size_t(field.num_slots())),
      z_(std::size_t(field.num_slots())),
      a_(12 * std::size_t(field.num_slots())),
      bounds_(std::size_t(field.num_domains())) {
  Update(field, nullptr);
}

void DeformedFieldState::Set(const DeformedDistanceField& field, int i, const Eigen::Vector3d& p,
                             const Eigen::Matrix3d& F) {
  SetSlot(field, i, p, F);
  UpdateBounds(field);
}

void DeformedFieldState::UpdateBounds(const DeformedDistanceField& field) {
  if (field.num_domains() == 1) return;  // nothing to cull
  using Matrix3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  for (int d = 0; d < field.num_domains(); ++d) {
    const int begin = field.slot_begin(d), end = field.slot_end(d);
    Matrix3 A = Matrix3::Zero();
    Eigen::Vector3d c = Eigen::Vector3d::Zero(), o = Eigen::Vector3d::Zero();
    auto slot_map = [&](int i, Matrix3* Ai, Eigen::Vector3d* ci) {
      const float* a = pullback(i);
      for (int e = 0; e < 9; ++e) (*Ai)(e / 3, e % 3) = a[e];
      *ci = Eigen::Vector3d(a[9], a[10], a[11]);
    };
    for (int i = begin; i < end; ++i) {
      Matrix3 Ai;
      Eigen::Vector3d ci;
      slot_map(i, &Ai, &ci);
      A += Ai;
      c += ci;
      o += Eigen::Vector3d(x_[i], y_[i], z_[i]);
    }
    const double inv = 1.0 / std::max(end - begin, 1);
    A *= inv, c *= inv, o *= inv;
    double spread = 0, slope = 0;
    for (int i = begin; i < end; ++i) {
      Matrix3 Ai;
      Eigen::Vector3d ci;
      slot_map(i, &Ai, &ci);
      spread = std::max(spread, (ci - c + (Ai - A) * o).norm());
      slope = std::max(slope, (Ai - A).norm());
    }
    DomainBound& b = bounds_[d];
    for (int e = 0; e < 9; ++e) b.a[e] = float(A(e / 3, e % 3));
    for (int e = 0; e < 3; ++e) b.c[e] = float(c[e]), b.o[e] = float(o[e]);
    // Rounded up by a little more than the float conversions of the slots' maps can move them.
    b.spread = float(spread * (1 + 1e-5) + 1e-6 * (c.lpNorm<Eigen::Infinity>() + A.lpNorm<Eigen::Infinity>() *
                                                                                    o.lpNorm<Eigen::Infinity>()));
    b.slope = float(slope * (1 + 1e-5) + 1e-6 * A.lpNorm<Eigen::Infinity>());
  }
}

void DeformedFieldState::SetSlot(const DeformedDistanceField& field, int i, const Eigen::Vector3d& p,
                                 const Eigen::Matrix3d& F) {
  const Eigen::Matrix3d A = F.inverse();
  const Eigen::Vector3d c = field.proxies().rest_position(i) - A * p;
  x_[i] = float(p.x());
  y_[i] = float(p.y());
  z_[i] = float(p.z());
  float* a = &a_[12 * std::size_t(i)];
  for (int e = 0; e < 9; ++e) a[e] = float(A(e / 3, e % 3));
  for (int e = 0; e < 3; ++e) a[9 + e] = float(c[e]);
}

void DeformedFieldState::Update(const DeformedDistanceField& field, const double* q) {
  const EmbeddedPoints& proxies = field.proxies();
  for (int i = 0; i < proxies.size(); ++i) {
    if (q == nullptr) {
      SetSlot(field, i, proxies.rest_position(i), Eigen::Matrix3d::Identity());
      continue;
    }
    const Eigen::Matrix3d F = proxies.DeformationGradient(i, q);
    const bool invertible = F.determinant() > 1e-3;
    SetSlot(field, i, proxies.Position(i, q), invertible ? F : Eigen::Matrix3d::Identity());
  }
  UpdateBounds(field);
}

}  // namespace contactlab
