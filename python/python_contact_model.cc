// A contact model calling back into Python (python/python_contact_model.h). Not real time.
#include "python_contact_model.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include "contact/model_registry.h"
#include "poses.h"
#include "util/error.h"

namespace py = pybind11;

namespace contactlab::python {
namespace {

// A Python callable shared by a registry entry and the models made from it; emptied at
// interpreter exit (with the GIL held) so that no reference is dropped after Python is gone.
struct PythonCallable {
  py::object fn;
};

std::mutex registry_mutex;
std::vector<std::shared_ptr<PythonCallable>>& Callables() {
  static auto* callables = new std::vector<std::shared_ptr<PythonCallable>>();  // outlives the interpreter
  return *callables;
}
std::set<std::string>& PythonModelNames() {
  static std::set<std::string> names;
  return names;
}

class PythonContactModel final : public ContactModel {
 public:
  PythonContactModel(std::string name, std::shared_ptr<PythonCallable> callable)
      : name_(std::move(name)), callable_(std::move(callable)) {}

  std::string_view name() const override { return name_; }

  // Takes the GIL and calls the Python function (unlike the built-in models, this allocates
  // and may throw: Error naming the model when the function raises or returns a wrong shape).
  ContactResult Evaluate(const ContactQuery& query) override {
    py::gil_scoped_acquire gil;
    if (!callable_->fn) Fail(name_, "its Python function is gone (the interpreter has shut down)");
    ContactResult r;
    try {
      const py::object out = callable_->fn(PoseToArray(query.X_WA), PoseToArray(query.X_WB));
      py::object wrench = out, K;
      if (py::isinstance<py::tuple>(out) && py::len(out) == 2) {
        wrench = out[py::int_(0)];
        K = out[py::int_(1)];
      }
      // Real numbers only, converted as the arguments of a call are (poses.h); a wrong type or
      // shape is this model's error, not the caller's.
      const DoubleArray w = DoublesFromObject(wrench, "its Python function's wrench");
      if (w.size() != 6) Fail(name_, "its Python function must return a wrench (6 numbers) or (wrench, K_B)");
      for (int i = 0; i < 3; ++i) r.on_B.force[i] = w.data()[i], r.on_B.torque[i] = w.data()[3 + i];
      if (K && !K.is_none()) {
        const DoubleArray k = DoublesFromObject(K, "its Python function's K_B");
        if (k.ndim() != 2 || k.shape(0) != 6 || k.shape(1) != 6) Fail(name_, "its Python function's K_B must be 6x6");
        for (int i = 0; i < 6; ++i) {
          for (int j = 0; j < 6; ++j) r.K_B(i, j) = k.data()[6 * i + j];
        }
      }
    } catch (py::error_already_set& e) {
      Fail(name_, std::string("its Python function raised ") + e.what());
    } catch (const py::builtin_exception& e) {
      Fail(name_, std::string("returned no numbers: ") + e.what());
    } catch (const ArgumentError& e) {
      Fail(name_, std::string("returned no numbers: ") + e.what());
    }
    r.stats.points_in_contact = r.on_B.force.squaredNorm() > 0 ? 1 : 0;
    return r;
  }

  void Reset() override {}

 private:
  std::string name_;
  std::shared_ptr<PythonCallable> callable_;
};

}  // namespace

void RegisterPythonContactModel(const std::string& name, const std::string& description, py::object fn) {
  if (!PyCallable_Check(fn.ptr())) Fail("register_model", "'" + name + "': the model must be a callable");
  if (name.empty()) Fail("register_model", "a model needs a name");
  std::lock_guard<std::mutex> lock(registry_mutex);
  if (FindContactModel(name) != nullptr && PythonModelNames().count(name) == 0) {
    Fail("register_model", "'" + name + "' is a built-in contact model; choose another name");
  }
  auto callable = std::make_shared<PythonCallable>(PythonCallable{std::move(fn)});
  Callables().push_back(callable);
  PythonModelNames().insert(name);
  ContactModelEntry entry;
  entry.name = name;
  entry.description = (description.empty() ? std::string("a model written in Python") : description) +
                      " (Python, not real time)";
  entry.make = [name, callable](const ContactModelInputs&) -> std::unique_ptr<ContactModel> {
    return std::make_unique<PythonContactModel>(name, callable);
  };
  RegisterContactModel(std::move(entry));
}

void ReleasePythonContactModels() {
  std::lock_guard<std::mutex> lock(registry_mutex);
  for (const auto& c : Callables()) c->fn = py::object();
}

}  // namespace contactlab::python
