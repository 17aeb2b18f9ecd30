// A capability of contact models that stand for each body by a filling of its volume (the
// inner spheres' packings): how much of each body's volume the filling covers. The contact
// study asks a model for it (dynamic_cast) and writes it to summary.csv (fill_A, fill_B).
#pragma once

namespace contactlab {

class VolumeFill {
 public:
  virtual ~VolumeFill() = default;
  // The fraction of body A's and of body B's volume the model's filling covers.
  virtual double fill_A() const = 0;
  virtual double fill_B() const = 0;
};

}  // namespace contactlab
