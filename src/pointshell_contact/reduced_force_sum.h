// A deformable body's reduced contact force summed over one query's points in contact (Barbič &
// James 2008, sec. 4.1, 4.2): with w = U^T N at the place the point's force acts (the point of a
// deformable pointshell, the nearest proxy of a deformed field), g = sum_i d_i w_i and, for a
// linearly implicit step, G = sum_i w_i w_i^T (the halfspace rule of sec. 5). The force is
// sign * k * g, its stiffness -d(force)/dq = k G. Fixed-size, allocation-free, inline.
#pragma once

#include <algorithm>

#include "reduced/reduced_state.h"

namespace contactlab {

class ReducedForceSum {
 public:
  // Starts a query's sum over R coordinates; STIFFNESS: also sum G.
  void Start(int r, bool stiffness) {
    r_ = r;
    stiffness_ = stiffness;
    std::fill(g_, g_ + r, 0.0);
    if (stiffness) std::fill(G_, G_ + r * r, 0.0);
  }
  // A point at depth D < 0 whose force acts through W = U^T N (r entries).
  void Add(float d, const float* w) {
    for (int j = 0; j < r_; ++j) g_[j] += double(d * w[j]);
    if (stiffness_) {
      for (int b = 0; b < r_; ++b)
        for (int a = 0; a <= b; ++a) G_[b * r_ + a] += double(w[a] * w[b]);
    }
  }
  // Float sums of many points (deform/reduced_point_batch.h): G_SUM (r entries) adds to g and,
  // when the stiffness is summed, row b < r of STIFFNESS (at STIFFNESS + b STRIDE) to G.
  void AddSums(const float* g_sum, const float* stiffness, int stride) {
    for (int j = 0; j < r_; ++j) g_[j] += double(g_sum[j]);
    if (stiffness_) {
      for (int b = 0; b < r_; ++b)
        for (int a = 0; a <= b; ++a) G_[b * r_ + a] += double(stiffness[b * stride + a]);
    }
  }
  bool stiffness() const { return stiffness_; }
  // Writes SIGN * K * g to F and, when K_OUT is non-null (and the stiffness was summed), K * G.
  void Write(double k, double sign, ReducedVector* f, ReducedMatrix* K_out) const {
    f->resize(r_);
    for (int j = 0; j < r_; ++j) (*f)[j] = sign * k * g_[j];
    if (K_out != nullptr && stiffness_) {
      K_out->resize(r_, r_);
      for (int b = 0; b < r_; ++b)
        for (int a = 0; a <= b; ++a) (*K_out)(a, b) = (*K_out)(b, a) = k * G_[b * r_ + a];
    }
  }

 private:
  int r_ = 0;
  bool stiffness_ = false;
  double g_[kMaxReducedModes];
  double G_[kMaxReducedModes * kMaxReducedModes];
};

}  // namespace contactlab
