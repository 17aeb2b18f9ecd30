// A contact model written in Python, registered with the model registry (contact/model_registry.h)
// so that scenes, `contactlab.run` and experiment configs make it by name beside the built-in
// models. NOT REAL TIME: every Evaluate takes the GIL and runs the interpreter (microseconds to
// milliseconds, unbounded), which a 1 kHz haptic loop must never do; it is for prototyping a
// force law and comparing it offline.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

namespace contactlab::python {

// Registers model NAME whose Evaluate calls FN(X_WA, X_WB), the poses as (7,) arrays (x, y, z,
// qw, qx, qy, qz), holding the GIL. FN returns the wrench on B about its origin in the world
// frame, a 6-sequence (force, torque), or a pair (wrench, K_B) with K_B 6x6 (otherwise zero).
// Throws Error when NAME is a built-in model's (a Python model's name may be registered again,
// replacing it). When FN raises or returns something else, Evaluate throws Error naming the
// model and what FN did: the experiment's job fails with that message.
void RegisterPythonContactModel(const std::string& name, const std::string& description, pybind11::object fn);

// Drops the Python callables of every registered Python model (at interpreter exit, with the
// GIL held); their models then throw Error when evaluated.
void ReleasePythonContactModels();

}  // namespace contactlab::python
