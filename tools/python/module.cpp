// The C++ side of the Python module `metrosync` (tools/python/metrosync/__init__.py is the API):
// the CLI's own commands, called in-process with the interpreter's lock released, so that a result
// from Python is the CLI's result to the last bit (docs/python.md).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <signal.h>

#include <optional>
#include <string>
#include <vector>

#include "sim/analysis/fit/model_samples.h"
#include "sim/record/atomic_file.h"
#include "tools/cli/commands.h"
#include "tools/cli/continue.h"
#include "tools/cli/fit.h"
#include "tools/cli/sweep.h"
#include "tools/report/outputs.h"
#include "yaml/rig_loader.h"

namespace py = pybind11;
namespace cli = metrosync::cli;

namespace {

// The process's SIGINT/SIGTERM handlers (Python's own) put back after a command, which installs
// metrosync's (a signal asks the running simulation to stop, keeping its rows).
class SignalHandlersKept {
 public:
  SignalHandlersKept() {
    ::sigaction(SIGINT, nullptr, &int_);
    ::sigaction(SIGTERM, nullptr, &term_);
  }
  ~SignalHandlersKept() {
    ::sigaction(SIGINT, &int_, nullptr);
    ::sigaction(SIGTERM, &term_, nullptr);
  }

 private:
  struct sigaction int_ {
  }, term_{};
};

cli::Options options(const std::string& rig_path, const std::vector<std::string>& sets,
                     const std::string& out, const std::string& model, const std::string& engine) {
  cli::Options o;
  o.rig_path = rig_path;
  o.sets = sets;
  o.out = out;
  o.quiet = true;
  o.no_plot = true;  // the module reads the CSV and JSON files; `out` keeps them
  o.model = model;
  o.engine = engine;
  return o;
}

// Runs a command with the interpreter's lock released and Python's signal handlers put back
// afterwards; returns its exit code. A stop request (Ctrl-C: the command's own SIGINT handler)
// raises KeyboardInterrupt once the command has ended and kept its files.
template <class Command>
int released(Command command) {
  int code = 0;
  {
    py::gil_scoped_release release;
    SignalHandlersKept keep;
    metrosync::FileSink::clearStopRequest();
    code = command();
  }
  if (metrosync::FileSink::stopRequested()) {
    metrosync::FileSink::clearStopRequest();
    throw py::error_already_set([] {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      return py::error_already_set();
    }());
  }
  return code;
}

// Runs `run` or `compare` into `out`; returns the CLI's exit code (0, or 3: the simulation
// failed). A bad rig or command raises RigError with the CLI's message.
int runCommand(const std::string& command, const std::string& rig_path,
               const std::vector<std::string>& sets, const std::string& out,
               const std::string& model, const std::string& engine) {
  const cli::Options o = options(rig_path, sets, out, model, engine);
  return released(
      [&] { return command == "compare" ? cli::compareCommand(o) : cli::runCommand(o); });
}

// `metrosync sweep` into `out` (no maps unless `plot`); the exit code.
int sweepCommand(const std::string& rig_path, const std::vector<std::string>& sets,
                 const std::vector<std::string>& vary, const std::string& out,
                 const std::string& model, const std::string& engine, int jobs, bool plot) {
  cli::SweepOptions o;
  o.rig_path = rig_path;
  o.sets = sets;
  o.vary = vary;
  o.out = out;
  o.quiet = true;
  o.no_plot = !plot;
  o.model = model;
  o.engine = engine;
  o.jobs = jobs;
  return released([&] { return cli::sweepCommand(o); });
}

// `metrosync continue` into `out`; the exit code.
int continueCommand(const std::string& rig_path, const std::vector<std::string>& sets,
                    const std::string& param, double to, const std::string& out,
                    std::optional<double> from, const std::string& start, double step,
                    int max_points, bool all, const std::string& fold, double to2, bool no_cycles) {
  cli::ContinueOptions o;
  o.rig_path = rig_path;
  o.sets = sets;
  o.param = param;
  o.to = to;
  o.from = from;
  o.start = start;
  o.step = step;
  o.max_points = max_points;
  o.all = all;
  o.fold_key = fold;
  o.to2 = to2;
  o.no_cycles = no_cycles;
  o.out = out;
  o.quiet = true;
  return released([&] { return cli::continueCommand(o); });
}

// `metrosync fit` without its files: fit.json's text (tools/report/fit_files.h), the CLI's
// answer to the last bit. A bad rig, data file or key raises RigError; a model that fails at the
// starting values raises RuntimeError with the CLI's message.
std::string fitJsonText(const std::string& rig_path, const std::string& data_path,
                        const std::vector<std::string>& free, const std::vector<std::string>& sets,
                        const std::string& model, std::optional<double> noise, int starts,
                        bool local, bool profile) {
  cli::FitOptions o;
  o.rig_path = rig_path;
  o.data_path = data_path;
  o.free = free;
  o.sets = sets;
  o.model = model.empty() ? "full" : model;
  o.noise = noise;
  o.starts = starts;
  o.local = local;
  o.profile = profile;
  std::string text;
  released([&] {
    try {
      text = metrosync::fitJson(cli::runFit(o)).dump();
    } catch (const metrosync::ModelFailure& e) {
      throw std::runtime_error(std::string("the model fails at the starting values: ") + e.what());
    }
    return 0;
  });
  return text;
}

}  // namespace

PYBIND11_MODULE(_metrosync, m) {
  m.doc() = "metrosync's C++ core (use the package `metrosync`)";
  static py::exception<metrosync::RigError> rig_error(m, "RigError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const metrosync::RigError& e) {
      PyErr_SetString(rig_error.ptr(), e.what());
    } catch (const cli::UsageError& e) {
      PyErr_SetString(rig_error.ptr(), e.what());
    }
  });
  m.def("run_command", &runCommand, py::arg("command"), py::arg("rig_path"), py::arg("sets"),
        py::arg("out"), py::arg("model") = "", py::arg("engine") = "");
  m.def("sweep_command", &sweepCommand, py::arg("rig_path"), py::arg("sets"), py::arg("vary"),
        py::arg("out"), py::arg("model") = "", py::arg("engine") = "", py::arg("jobs") = 0,
        py::arg("plot") = false);
  m.def("continue_command", &continueCommand, py::arg("rig_path"), py::arg("sets"),
        py::arg("param"), py::arg("to"), py::arg("out"), py::arg("from_") = std::nullopt,
        py::arg("start") = "", py::arg("step") = 0.0, py::arg("max_points") = 500,
        py::arg("all") = false, py::arg("fold") = "", py::arg("to2") = 0.0,
        py::arg("no_cycles") = false);
  m.def("fit_json", &fitJsonText, py::arg("rig_path"), py::arg("data_path"), py::arg("free"),
        py::arg("sets"), py::arg("model") = "", py::arg("noise") = std::nullopt,
        py::arg("starts") = 6, py::arg("local") = false, py::arg("profile") = false);
  m.def(
      "scaled_json",
      [](const std::string& rig_path, const std::vector<std::string>& sets) {
        return cli::scaledJsonText(options(rig_path, sets, "", "", ""));
      },
      py::arg("rig_path"), py::arg("sets"));
  m.def("version", [] { return std::string(metrosync::metrosyncVersion()); });
}
