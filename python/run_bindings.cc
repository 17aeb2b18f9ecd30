// contactlab.run: an experiment config run as `contactlab run` runs it (src/cli/run_commands.cc),
// with the GIL released; contactlab.register_model: a model written in Python.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "experiment/experiment_config.h"
#include "experiment/runner.h"
#include "experiment/study.h"
#include "python_contact_model.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/input_files.h"
#include "util/output_target.h"

namespace py = pybind11;

namespace contactlab::python {
namespace {

std::string Run(const std::string& config_path, std::optional<std::string> out, const std::vector<std::string>& overrides,
                const std::string& profile, const std::vector<int>& jobs, int parallel, std::optional<std::string> cache,
                bool use_cache, bool progress) {
  const InputFileRecord inputs;  // no file this run reads is one of its outputs
  // Loading parses and checks every sweep point before anything runs.
  const ExperimentConfig config = LoadExperimentConfig(RequireDataFile(config_path), overrides, profile);
  if (parallel < 0) Fail("run", "parallel must be >= 0 (0: all cores)");
  RunOptions options;
  options.out_dir = out ? std::filesystem::path(*out) : std::filesystem::path("results") / config.name;
  if (jobs.size() == 1 && !out) options.out_dir /= "job-" + std::to_string(jobs.front());
  // The results folder and its files are checked before any job runs.
  const Study& study = StudyOf(config);
  CheckOutputFolderWritable(options.out_dir, "out");
  for (const std::string& file : study.Files()) {
    CheckOutputTarget(options.out_dir / file, "out");
    CheckOutputIsNoRecordedInput(options.out_dir / file, "out");
  }
  if (cache) options.assets.cache_dir = *cache;
  options.assets.use_cache = use_cache;
  options.assets.verbose = false;
  options.parallel_jobs = parallel;
  options.progress = progress;
  {
    // Jobs run on worker threads; a model written in Python takes the GIL in each query.
    py::gil_scoped_release release;
    study.run(config, options, jobs);
  }
  return options.out_dir.string();
}

}  // namespace

void BindRun(py::module_& m) {
  m.def("_run", &Run, py::arg("config"), py::arg("out"), py::arg("overrides"), py::arg("profile"), py::arg("jobs"),
        py::arg("parallel"), py::arg("cache"), py::arg("use_cache"), py::arg("progress"),
        "Runs an experiment config as `contactlab run` does; contactlab.run is the keyword interface.");
  m.def(
      "register_model",
      [](const std::string& name, py::object fn, const std::string& description) {
        RegisterPythonContactModel(name, description, std::move(fn));
      },
      py::arg("name"), py::arg("fn"), py::arg("description") = "",
        "Registers FN(X_WA, X_WB) -> wrench (6,) or (wrench, K_B (6, 6)) as contact model NAME, made by name "
        "like the built-in models (Scene.model, experiment configs, contactlab.run). NOT REAL TIME: each "
        "query takes the GIL and runs Python; for prototyping and offline comparison only. Poses are (7,) "
        "arrays (x, y, z, qw, qx, qy, qz); the wrench is on B about its origin, world frame.");
  m.def(
      "_set_installed_root", [](const std::string& root) { SetInstalledRoot(root); }, py::arg("root"),
      "Names the share/contactlab folder of the data search path (done by the package at import).");
  // Python callables held by the registry are dropped while the interpreter still runs.
  py::module_::import("atexit").attr("register")(py::cpp_function([] { ReleasePythonContactModels(); }));
}

}  // namespace contactlab::python
