// Particle repulsion on a level set (Barbič & James 2008, sec. 2.4).
#include "pointshell/particle_repulsion.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>

#include "pointshell/level_set_sampling.h"
#include "pointshell/uniform_grid.h"

namespace contactlab {

RepulsionLevelStats RepelOnLevelSet(const DistanceField& field, double delta, double expected_spacing,
                                    const RepulsionOptions& options, std::int32_t frozen,
                                    std::vector<Eigen::Vector3d>* positions, Progress* progress) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Eigen::Vector3d>& p = *positions;
  const std::int32_t total = std::int32_t(p.size());
  const std::int32_t num_free = total - frozen;
  const double s = expected_spacing;
  const double sigma = options.kernel_width * s;
  const float sigma_f = float(sigma), sigma2 = float(sigma * sigma), inv_sigma = float(1 / sigma);
  const double step = options.strength * s, max_step = options.max_step * s;
  const double tolerance = LevelSetTolerance(field);

  RepulsionLevelStats stats;
  stats.frozen_points = frozen;
  stats.free_points = num_free;
  stats.expected_spacing = s;
  stats.kernel_width = sigma;
  if (num_free <= 0) return stats;

  // Frozen points push but never move: their grid is built once.
  UniformGrid frozen_grid, free_grid;
  frozen_grid.Build(p.data(), frozen, 0, sigma);

  // Working buffers for the free points (Jacobi: read p, write next).
  std::vector<Eigen::Vector3d> next(num_free), normal(num_free);
  std::vector<double> moved(num_free, 0.0);
  tbb::parallel_for(std::int32_t(0), num_free, [&](std::int32_t f) {
    Eigen::Vector3d g;
    field.DistanceAndGradient(p[frozen + f], &g);
    const double n = g.norm();
    normal[f] = n > 0 ? Eigen::Vector3d(g / n) : Eigen::Vector3d::Zero();
  });

  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    free_grid.Build(p.data() + frozen, num_free, frozen, sigma);
    tbb::parallel_for(std::int32_t(0), num_free, [&](std::int32_t f) {
      const std::int32_t i = frozen + f;
      const float qx = float(p[i].x()), qy = float(p[i].y()), qz = float(p[i].z());
      // Sum of the kernel forces of all neighbours within sigma.
      float fx = 0, fy = 0, fz = 0;
      auto push = [&](const UniformGrid::Entry& e) {
        if (e.index == i) return;
        const float dx = qx - e.x, dy = qy - e.y, dz = qz - e.z;
        const float r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= sigma2) return;
        const float r = std::sqrt(r2);
        if (r < 1e-6f * sigma_f) {
          // Coincident points: separate them along a direction fixed by the index pair.
          const float sign = e.index < i ? 1.f : -1.f;
          fx += sign;
          return;
        }
        const float t = 1.f - r * inv_sigma;
        const float w = t * t * t / r;
        fx += w * dx;
        fy += w * dy;
        fz += w * dz;
      };
      frozen_grid.ForEachNear(qx, qy, qz, sigma_f, push);
      free_grid.ForEachNear(qx, qy, qz, sigma_f, push);
      // Tangential step, clamped, then back onto the level set.
      Eigen::Vector3d force(fx, fy, fz);
      force -= force.dot(normal[f]) * normal[f];
      Eigen::Vector3d delta_p = step * force;
      const double len = delta_p.norm();
      if (len > max_step) delta_p *= max_step / len;
      // A step whose projection fails (e.g. across a crease of the level set, where the
      // trilinear gradient jumps) is retried at half length, twice, then dropped.
      next[f] = p[i];
      moved[f] = 0;
      for (int attempt = 0; attempt < 3 && len > 0; ++attempt, delta_p *= 0.5) {
        Eigen::Vector3d q = p[i] + delta_p;
        Eigen::Vector3d g;
        if (ProjectOntoLevelSet(field, delta, tolerance, 8, &q, &g) && (q - p[i]).norm() < 2 * max_step + sigma) {
          next[f] = q;
          normal[f] = g.normalized();
          moved[f] = (q - p[i]).norm();
          break;
        }
      }
    });
    std::copy(next.begin(), next.end(), p.begin() + frozen);
    double sum = 0;
    for (double m : moved) sum += m;
    stats.iterations = iteration + 1;
    stats.last_mean_step = sum / num_free / s;
    if (progress) progress->Advance(1);
    if (stats.last_mean_step < options.tolerance) {
      stats.converged = true;
      if (progress) progress->Advance(options.max_iterations - stats.iterations);
      break;
    }
  }
  stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace contactlab
