// contactlab._core: the C++ half of the `contactlab` Python package (pybind11). NumPy arrays in
// and out; contactlab::Error raised as contactlab.Error with its message (file, line, key), a
// bad argument as contactlab.ArgumentError (also a ValueError).
#include <pybind11/pybind11.h>

#include "argument_error.h"
#include "bindings.h"
#include "contact/register_contact_models.h"
#include "util/error.h"

namespace py = pybind11;

namespace contactlab::python {

void BindErrors(py::module_& m) {
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  error.doc() = "An error of ContactLab: its message names the file (line, key) and what is wrong.";
  // A bad argument of a call is a contactlab.Error and, as NumPy's are, a ValueError.
  static py::exception<ArgumentError> argument_error(m, "ArgumentError", py::make_tuple(error, py::handle(PyExc_ValueError)));
  argument_error.doc() =
      "A call's argument that is not what it takes (shape, a value that is not finite, a pose that is no rigid "
      "transform): a contactlab.Error and a ValueError; its message names the argument.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ArgumentError& e) {
      argument_error(e.what());
    } catch (const Error& e) {
      error(e.what());
    }
  });
}

}  // namespace contactlab::python

PYBIND11_MODULE(_core, m) {
  m.doc() = "ContactLab's C++ library: scenes, contact models, experiments (see the contactlab package).";
  // The baselines register their models as the command does at start-up.
  contactlab::RegisterContactModels();
  contactlab::python::BindErrors(m);
  contactlab::python::BindScene(m);
  contactlab::python::BindModel(m);
  contactlab::python::BindRun(m);
  contactlab::python::BindWorld(m);
  m.attr("__version__") = CONTACTLAB_VERSION;
}
