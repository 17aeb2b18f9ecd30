// The guard of a contact model's temporal coherence (Barbič & James 2008, sec. 3.4): the
// coherence assumes no point of one body moves faster than max_point_speed relative to the
// other, i.e. no more than max_point_speed * cycle_seconds per cycle. The guard measures the
// moving body's motion between consecutive contact queries, |dp| + |dtheta| * radius over
// cycle_seconds (radius: the body's bounding radius about its origin), and when it exceeds
// max_point_speed says the model must be reset (a full traversal that cycle; coherence restarts
// from it), counting such cycles. The haptic cycle and the experiment runner both guard with it.
// Header only; allocation-free and exception-free after construction.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

#include "geometry/pose.h"
#include "util/error.h"

namespace contactlab {

class CoherenceGuard {
 public:
  CoherenceGuard() = default;  // disabled: never asks for a reset
  // MAX_POINT_SPEED m/s (the scene's model.max_point_speed; <= 0 disables the guard),
  // CYCLE_SECONDS s (the cycle the coherence counts in, model.cycle_seconds), RADIUS m (the
  // moving body's bounding radius about its origin, TriangleMesh::MaxVertexRadius). Throws
  // Error naming WHERE when an enabled guard's values are not finite, the cycle not positive or
  // the radius negative.
  CoherenceGuard(double max_point_speed, double cycle_seconds, double radius, const std::string& where)
      : max_point_speed_(max_point_speed), cycle_seconds_(cycle_seconds), radius_(radius) {
    if (!(max_point_speed <= 0 || (std::isfinite(max_point_speed) && cycle_seconds > 0 && std::isfinite(cycle_seconds) &&
                                   radius >= 0 && std::isfinite(radius)))) {
      Fail(where, "max_point_speed, cycle_seconds and the body radius must be finite, cycle_seconds > 0 and the "
                  "radius >= 0");
    }
  }

  bool enabled() const { return max_point_speed_ > 0; }
  double max_point_speed() const { return max_point_speed_; }

  // Starts over with the moving body at X (its pose at the next query, or the last one made)
  // and no resets counted.
  void Start(const Pose& X) {
    last_ = X;
    resets_ = 0;
  }
  // The moving body is at X for this cycle's query. Returns true when its motion since the
  // previous query, as a bound on the speed of its points (stored in *POINT_SPEED, m/s, when
  // given; 0 when disabled), exceeds max_point_speed: the caller resets the model before the
  // query. Remembers X for the next cycle.
  bool Check(const Pose& X, double* point_speed = nullptr) {
    bool reset = false;
    double speed = 0;
    if (enabled()) {
      const double moved = (X.translation - last_.translation).norm() + X.rotation.angularDistance(last_.rotation) * radius_;
      speed = moved / cycle_seconds_;
      if (!(speed <= max_point_speed_)) {
        reset = true;
        ++resets_;
      }
    }
    last_ = X;
    if (point_speed != nullptr) *point_speed = speed;
    return reset;
  }
  // Cycles since Start whose motion exceeded max_point_speed.
  std::int64_t resets() const { return resets_; }

 private:
  double max_point_speed_ = 0;
  double cycle_seconds_ = 1e-3;
  double radius_ = 0;
  Pose last_;
  std::int64_t resets_ = 0;
};

}  // namespace contactlab
