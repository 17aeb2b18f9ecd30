// Metrics over a trajectory's per-cycle signals (force continuity, spectra, timing, error
// against a reference, convergence order). Pure functions on arrays, checked on synthetic
// signals with known answers.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

#include "geometry/pose.h"

namespace contactlab {

struct ContinuityMetrics {
  double max_jump = 0;          // largest |F(k+1) - F(k)| over consecutive cycles, N
  std::int64_t max_jump_cycle = -1;
  double lipschitz = 0;         // largest |dF| / (|dp| + radius |dθ|) over cycles that move, N/m
  double high_frequency_share = 0;  // share of the (mean-removed) force energy above the cutoff
};

// FORCE and POSES per cycle (same length), DT seconds per cycle; RADIUS converts rotation to
// a length for the Lipschitz estimate; CUTOFF_HZ splits the spectrum.
ContinuityMetrics ForceContinuity(const std::vector<Eigen::Vector3d>& force, const std::vector<Pose>& poses,
                                  double dt, double radius, double cutoff_hz);

// Share of the energy of SIGNAL (mean removed) at frequencies above CUTOFF_HZ, sampled every
// DT seconds (discrete Fourier transform, zero-padded to a power of two).
double HighFrequencyShare(const std::vector<double>& signal, double dt, double cutoff_hz);

// The frequency (Hz) of the largest spectral peak of SIGNAL (mean removed).
double DominantFrequency(const std::vector<double>& signal, double dt);

// Power spectrum |X_k|^2 of SIGNAL (mean removed, zero-padded to a power of two, length n):
// bins k = 0..n/2, frequency k / (n dt).
std::vector<double> PowerSpectrum(const std::vector<double>& signal, std::size_t* padded_length = nullptr);

struct TimingMetrics {
  double median_us = 0, p99_us = 0, max_us = 0, mean_us = 0;
  double level_switches_per_second = 0;  // changes of the rendered level
  double mean_nodes = 0;
};
TimingMetrics Timing(const std::vector<double>& cycle_us, const std::vector<int>& level, double dt);

// Quantile Q in [0, 1] of VALUES (nearest rank).
double Quantile(std::vector<double> values, double q);

struct ErrorMetrics {
  double rms_relative = 0;      // RMS |F - F_ref| / RMS |F_ref| over cycles with a reference
  double max_direction_deg = 0; // largest angle between F and F_ref where |F_ref| > 5 % of max
  int samples = 0;
  // Calibrated magnitude: each model's force law scales differently (area-normalised, per
  // triangle pair, per manifold point), so one stiffness scale s is fitted per run, least
  // squares over the cycles with a reference, mapping |F| onto |F_ref|:
  //     s = sum |F| |F_ref| / sum |F|^2   (NaN when every |F| is 0),
  // and the relative RMS error of s F is reported beside the raw one.
  double scale = std::numeric_limits<double>::quiet_NaN();
  double rms_relative_calibrated = std::numeric_limits<double>::quiet_NaN();
  // Angles between F and F_ref (no calibration needed) where |F_ref| > 5 % of its max: median
  // and 95th percentile (nearest rank) beside the max; 180° where F = 0.
  double median_direction_deg = 0, p95_direction_deg = 0;
};
ErrorMetrics ErrorAgainstReference(const std::vector<Eigen::Vector3d>& force,
                                   const std::vector<Eigen::Vector3d>& reference, const std::vector<bool>& has_reference);

// The force scale of a run: the median |F| over the cycles with a force (0 when none). Jumps
// and Lipschitz estimates divided by it compare models whose force laws differ in magnitude.
double MedianForceInContact(const std::vector<Eigen::Vector3d>& force);

// Least-squares slope of log(error) against log(size): the fitted convergence order is
// -slope (error ~ size^-order). Needs at least two positive pairs; returns NaN otherwise.
double FittedOrder(const std::vector<double>& size, const std::vector<double>& error);

// The half-width of the 95 % confidence interval of FittedOrder's slope: t(0.975, n - 2) times
// the slope's standard error from the residuals. NaN with fewer than three positive pairs.
double FittedOrderHalfWidth95(const std::vector<double>& size, const std::vector<double>& error);

}  // namespace contactlab
