// Nearest-point queries over a pointshell's float positions (a nanoflann k-d tree), used to
// assign tree parents (Barbič & James 2008, sec. 2.4) and to measure sampling quality.
#pragma once

#include <cstdint>
#include <memory>

namespace contactlab {

class NearestPointIndex {
 public:
  // Indexes points [0, COUNT) of the arrays X, Y, Z (each at least COUNT long; the arrays
  // must outlive the index). COUNT >= 1.
  NearestPointIndex(const float* x, const float* y, const float* z, std::int32_t count);
  ~NearestPointIndex();
  NearestPointIndex(const NearestPointIndex&) = delete;
  NearestPointIndex& operator=(const NearestPointIndex&) = delete;

  // The K (1 or 2) nearest indexed points to Q: indices in INDEX[0..K), squared distances
  // (m^2) in DIST2[0..K), nearest first. Returns how many were found. Thread-safe.
  int Nearest(const float q[3], int k, std::int32_t* index, float* dist2) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace contactlab
