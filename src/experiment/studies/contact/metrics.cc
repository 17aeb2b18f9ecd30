#include "experiment/studies/contact/metrics.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>

namespace contactlab {
namespace {

// In-place iterative radix-2 FFT; A.size() must be a power of two.
void Fft(std::vector<std::complex<double>>& a) {
  const std::size_t n = a.size();
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(a[i], a[j]);
  }
  for (std::size_t len = 2; len <= n; len <<= 1) {
    const double ang = -2 * M_PI / double(len);
    const std::complex<double> wl(std::cos(ang), std::sin(ang));
    for (std::size_t i = 0; i < n; i += len) {
      std::complex<double> w(1);
      for (std::size_t j = 0; j < len / 2; ++j) {
        const std::complex<double> u = a[i + j], v = a[i + j + len / 2] * w;
        a[i + j] = u + v;
        a[i + j + len / 2] = u - v;
        w *= wl;
      }
    }
  }
}

}  // namespace

std::vector<double> PowerSpectrum(const std::vector<double>& signal, std::size_t* padded_length) {
  std::size_t n = 1;
  while (n < signal.size()) n <<= 1;
  if (padded_length) *padded_length = n;
  if (signal.empty()) return {};
  const double mean = std::accumulate(signal.begin(), signal.end(), 0.0) / double(signal.size());
  std::vector<std::complex<double>> a(n, 0.0);
  for (std::size_t i = 0; i < signal.size(); ++i) a[i] = signal[i] - mean;
  Fft(a);
  std::vector<double> power(n / 2 + 1);
  for (std::size_t k = 0; k <= n / 2; ++k) power[k] = std::norm(a[k]) * (k == 0 || k == n / 2 ? 1.0 : 2.0);
  return power;
}

double HighFrequencyShare(const std::vector<double>& signal, double dt, double cutoff_hz) {
  std::size_t n = 0;
  const std::vector<double> power = PowerSpectrum(signal, &n);
  double total = 0, high = 0;
  for (std::size_t k = 0; k < power.size(); ++k) {
    total += power[k];
    if (double(k) / (double(n) * dt) > cutoff_hz) high += power[k];
  }
  return total > 0 ? high / total : 0.0;
}

double DominantFrequency(const std::vector<double>& signal, double dt) {
  std::size_t n = 0;
  const std::vector<double> power = PowerSpectrum(signal, &n);
  if (power.size() < 2) return 0;
  const auto it = std::max_element(power.begin() + 1, power.end());
  return double(it - power.begin()) / (double(n) * dt);
}

ContinuityMetrics ForceContinuity(const std::vector<Eigen::Vector3d>& force, const std::vector<Pose>& poses,
                                  double dt, double radius, double cutoff_hz) {
  ContinuityMetrics m;
  for (std::size_t k = 1; k < force.size(); ++k) {
    const double jump = (force[k] - force[k - 1]).norm();
    if (jump > m.max_jump) {
      m.max_jump = jump;
      m.max_jump_cycle = std::int64_t(k);
    }
    if (k < poses.size()) {
      const double motion = (poses[k].translation - poses[k - 1].translation).norm() +
                            radius * poses[k].rotation.angularDistance(poses[k - 1].rotation);
      if (motion > 1e-12) m.lipschitz = std::max(m.lipschitz, jump / motion);
    }
  }
  double total = 0, high = 0;
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> s(force.size());
    for (std::size_t k = 0; k < force.size(); ++k) s[k] = force[k][axis];
    std::size_t n = 0;
    const std::vector<double> power = PowerSpectrum(s, &n);
    for (std::size_t b = 0; b < power.size(); ++b) {
      total += power[b];
      if (double(b) / (double(n) * dt) > cutoff_hz) high += power[b];
    }
  }
  m.high_frequency_share = total > 0 ? high / total : 0.0;
  return m;
}

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const std::size_t i = std::min(values.size() - 1, std::size_t(std::ceil(q * double(values.size()))) - (q > 0 ? 1 : 0));
  return values[i];
}

TimingMetrics Timing(const std::vector<double>& cycle_us, const std::vector<int>& level, double dt) {
  TimingMetrics t;
  if (cycle_us.empty()) return t;
  t.median_us = Quantile(cycle_us, 0.5);
  t.p99_us = Quantile(cycle_us, 0.99);
  t.max_us = *std::max_element(cycle_us.begin(), cycle_us.end());
  t.mean_us = std::accumulate(cycle_us.begin(), cycle_us.end(), 0.0) / double(cycle_us.size());
  int switches = 0;
  for (std::size_t k = 1; k < level.size(); ++k) switches += level[k] != level[k - 1];
  const double seconds = double(level.size()) * dt;
  t.level_switches_per_second = seconds > 0 ? switches / seconds : 0;
  return t;
}

ErrorMetrics ErrorAgainstReference(const std::vector<Eigen::Vector3d>& force,
                                   const std::vector<Eigen::Vector3d>& reference, const std::vector<bool>& has_reference) {
  ErrorMetrics e;
  double num = 0, den = 0, max_ref = 0, ff = 0, fr = 0;
  std::vector<double> angles;
  angles.reserve(force.size());
  for (std::size_t k = 0; k < force.size(); ++k)
    if (has_reference[k]) max_ref = std::max(max_ref, reference[k].norm());
  for (std::size_t k = 0; k < force.size(); ++k) {
    if (!has_reference[k]) continue;
    ++e.samples;
    num += (force[k] - reference[k]).squaredNorm();
    den += reference[k].squaredNorm();
    ff += force[k].squaredNorm();
    fr += force[k].norm() * reference[k].norm();
    if (reference[k].norm() > 0.05 * max_ref && max_ref > 0) {
      const double f = force[k].norm();
      const double angle =
          f > 0 ? std::acos(std::clamp(force[k].dot(reference[k]) / (f * reference[k].norm()), -1.0, 1.0)) : M_PI;
      angles.push_back(angle * 180 / M_PI);
      e.max_direction_deg = std::max(e.max_direction_deg, angles.back());
    }
  }
  auto relative = [&](double squared_error) {
    return den > 0 ? std::sqrt(squared_error / den)
                   : (squared_error > 0 ? std::numeric_limits<double>::infinity() : 0.0);
  };
  e.rms_relative = relative(num);
  if (ff > 0) {
    e.scale = fr / ff;
    double calibrated = 0;
    for (std::size_t k = 0; k < force.size(); ++k) {
      if (has_reference[k]) calibrated += (e.scale * force[k] - reference[k]).squaredNorm();
    }
    e.rms_relative_calibrated = relative(calibrated);
  }
  if (!angles.empty()) {
    e.median_direction_deg = Quantile(angles, 0.5);
    e.p95_direction_deg = Quantile(angles, 0.95);
  }
  return e;
}

double MedianForceInContact(const std::vector<Eigen::Vector3d>& force) {
  std::vector<double> magnitudes;
  magnitudes.reserve(force.size());
  for (const Eigen::Vector3d& f : force) {
    if (f.norm() > 0) magnitudes.push_back(f.norm());
  }
  return magnitudes.empty() ? 0.0 : Quantile(magnitudes, 0.5);
}

double FittedOrder(const std::vector<double>& size, const std::vector<double>& error) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < size.size() && i < error.size(); ++i) {
    if (!(size[i] > 0) || !(error[i] > 0)) continue;
    const double x = std::log(size[i]), y = std::log(error[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y, ++n;
  }
  if (n < 2 || sxx * n - sx * sx == 0) return std::numeric_limits<double>::quiet_NaN();
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

double FittedOrderHalfWidth95(const std::vector<double>& size, const std::vector<double>& error) {
  std::vector<double> x, y;
  for (std::size_t i = 0; i < size.size() && i < error.size(); ++i) {
    if (size[i] > 0 && error[i] > 0) x.push_back(std::log(size[i])), y.push_back(std::log(error[i]));
  }
  const std::size_t n = x.size();
  if (n < 3) return std::numeric_limits<double>::quiet_NaN();
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i] / double(n), my += y[i] / double(n);
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < n; ++i) sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
  if (sxx == 0) return std::numeric_limits<double>::quiet_NaN();
  const double slope = sxy / sxx, intercept = my - slope * mx;
  double rss = 0;
  for (std::size_t i = 0; i < n; ++i) rss += std::pow(y[i] - intercept - slope * x[i], 2);
  const double se = std::sqrt(rss / double(n - 2) / sxx);
  // Student's t, two-sided 95 %, for 1..30 degrees of freedom; 1.96 beyond.
  static constexpr double kT[] = {12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                  2.201,  2.179, 2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086,
                                  2.080,  2.074, 2.069, 2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  const std::size_t dof = n - 2;
  return (dof <= 30 ? kT[dof - 1] : 1.96) * se;
}

}  // namespace contactlab
