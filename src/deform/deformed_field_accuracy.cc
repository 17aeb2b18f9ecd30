#include "deform/deformed_field_accuracy.h"

#include <cmath>
#include <random>

#include "deform/reduced_integrator.h"
#include "util/error.h"

namespace contactlab {

EmbeddedSurface::EmbeddedSurface(const TriangleMesh& rest, const TetMesh& tets, const Eigen::MatrixXd& U)
    : rest_(rest), vertices_(tets, U, rest.vertices) {}

TriangleMesh EmbeddedSurface::Deformed(const Eigen::VectorXd& q) const {
  TriangleMesh m = rest_;
  for (int v = 0; v < m.num_vertices(); ++v) m.vertices[v] = vertices_.Position(v, q.data());
  return m;
}

double EmbeddedSurface::MaxDisplacement(const Eigen::VectorXd& q) const {
  double m = 0;
  for (int v = 0; v < vertices_.size(); ++v) m = std::max(m, vertices_.Displacement(v, q.data()).norm());
  return m;
}

Eigen::VectorXd SolveScaledPointLoadPose(const ReducedInternalForces& forces, const TetMesh& tets,
                                         const Eigen::MatrixXd& U, const std::vector<PointLoad>& loads,
                                         const EmbeddedSurface& surface, double target, const std::string& where) {
  if (loads.empty()) Fail(where, "no point load given");
  if (!(target > 0)) Fail(where, "the target displacement must be positive");
  // The reduced force of the unscaled loads.
  std::vector<Eigen::Vector3d> at;
  for (const PointLoad& l : loads) at.push_back(l.at);
  const EmbeddedPoints points(tets, U, at);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(U.cols());
  for (int i = 0; i < points.size(); ++i) points.AddPointForce(i, loads[i].force, f.data());
  if (!(f.norm() > 0)) Fail(where, "the loads do not act on any mode (zero reduced force)");
  // Rescale the loads until the largest surface displacement is TARGET (one rescaling is
  // exact for a linear model; reduced StVK stiffens or softens, so repeat).
  double scale = 1;
  Eigen::VectorXd q;
  for (int iteration = 0; iteration < 30; ++iteration) {
    const ReducedVector fs = scale * f;
    q = SolveReducedStatic(forces, fs);
    const double m = surface.MaxDisplacement(q);
    if (!(m > 0) || !std::isfinite(m)) Fail(where, "the static solve under the loads did not move the body");
    if (std::abs(m / target - 1) < 1e-3) return q;
    scale *= target / m;
  }
  Fail(where, "no static pose with the largest displacement at " + std::to_string(target) +
                  " m was found (the reduced StVK solve does not converge at this size; use a smaller one)");
}

BandError MeasureBandError(const DeformedDistanceField& field, const DeformedFieldState& state,
                           const MeshSignedDistance& exact, const BandErrorOptions& options, const std::string& where) {
  if (!(options.band > 0) || options.points < 1) Fail(where, "the band and the number of points must be positive");
  const Aabb bounds = exact.mesh().Bounds();
  const Eigen::Vector3d lo = bounds.min - Eigen::Vector3d::Constant(options.band);
  const Eigen::Vector3d size = bounds.size() + Eigen::Vector3d::Constant(2 * options.band);
  BandError r;
  r.box_volume = size.prod();
  std::mt19937_64 rng(options.seed);
  std::uniform_real_distribution<double> u(0, 1);
  const std::int64_t limit = std::int64_t(options.points) * options.max_candidates_per_point;
  std::int64_t false_inside = 0;
  double sum = 0, sum2 = 0;
  r.band_points.reserve(3 * std::size_t(options.points));
  r.exact.reserve(std::size_t(options.points));
  // Uniform samples of the box: those in the band are measured; every sample counts toward
  // the spurious-inside volume.
  while (r.points < options.points) {
    if (r.candidates >= limit) {
      Fail(where, "found only " + std::to_string(r.points) + " of " + std::to_string(options.points) +
                      " points within " + std::to_string(options.band) + " m of the surface in " +
                      std::to_string(r.candidates) + " samples");
    }
    ++r.candidates;
    const Eigen::Vector3d x = lo + size.cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const double e = exact.Distance(x);
    const double a = field.Distance(state, x);
    if (e > options.band && a < 0) ++false_inside;
    if (std::abs(e) > options.band) continue;
    const double err = a - e;
    sum += err;
    sum2 += err * err;
    r.max = std::max(r.max, std::abs(err));
    for (int c = 0; c < 3; ++c) r.band_points.push_back(float(x[c]));
    r.exact.push_back(e);
    ++r.points;
  }
  r.mean = sum / r.points;
  r.rms = std::sqrt(sum2 / r.points);
  r.false_inside_volume = r.box_volume * double(false_inside) / double(r.candidates);
  return r;
}

}  // namespace contactlab
