// The parts of the contactlab Python module (contactlab._core), each adding its classes and
// functions to the module; module.cc calls them in order.
#pragma once

#include <pybind11/pybind11.h>

namespace contactlab::python {

// contactlab.Error (a RuntimeError), contactlab.ArgumentError (a contactlab.Error and a
// ValueError), and the translation of contactlab::Error and ArgumentError into them.
void BindErrors(pybind11::module_& m);
// Scene and Body (scene_bindings.cc).
void BindScene(pybind11::module_& m);
// Model, models() (model_bindings.cc).
void BindModel(pybind11::module_& m);
// run(), register_model() (run_bindings.cc).
void BindRun(pybind11::module_& m);
// World, a scene of many bodies (world_bindings.cc).
void BindWorld(pybind11::module_& m);

}  // namespace contactlab::python
