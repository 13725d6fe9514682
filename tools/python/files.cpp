// The commands Python still runs into a folder and reads back (docs/python.md says which, and
// why): continue, fit, and run on a network of platforms. Each takes a rig file's path and
// returns the CLI's exit code.
#include <pybind11/stl.h>

#include "tools/cli/commands.h"
#include "tools/cli/continue.h"
#include "tools/cli/fit.h"
#include "tools/python/bindings.h"

namespace metrosync::python {

namespace {

namespace cli = metrosync::cli;

// `metrosync run` of a network rig file into `out`, with run's options (--model, --engine).
int networkRun(const std::string& rig_path, const std::vector<std::string>& sets,
               const std::string& model, const std::string& engine, const std::string& out,
               bool plot) {
  cli::Options o;
  o.rig_path = rig_path;
  o.sets = sets;
  o.model = model;  // refused as the CLI refuses it (--model slow: single-platform)
  o.engine = engine;
  o.out = out;
  o.quiet = true;
  o.no_plot = !plot;
  int code = 0;
  runReleased([&] { code = cli::runCommand(o); });
  return code;
}

// `metrosync continue` into `out`.
int continueCommand(const std::string& rig_path, const std::vector<std::string>& sets,
                    const std::string& model, const std::string& param, double to,
                    const std::string& out, std::optional<double> from, const std::string& start,
                    double step, int max_points, bool all, bool no_cycles, const std::string& fold,
                    double to2) {
  cli::ContinueOptions o;
  o.rig_path = rig_path;
  o.sets = sets;
  o.model = model;
  o.param = param;
  o.to = to;
  o.from = from;
  o.start = start;
  o.step = step;
  o.max_points = max_points;
  o.all = all;
  o.no_cycles = no_cycles;
  o.fold_key = fold;
  o.to2 = to2;
  o.out = out;
  o.quiet = true;
  int code = 0;
  runReleased([&] { code = cli::continueCommand(o); });
  return code;
}

// `metrosync fit` into `out`.
int fitCommand(const std::string& rig_path, const std::string& data_path,
               const std::vector<std::string>& free, const std::vector<std::string>& sets,
               const std::string& model, const std::string& out, bool plot,
               std::optional<double> noise, int starts, bool local, bool profile) {
  cli::FitOptions o;
  o.rig_path = rig_path;
  o.data_path = data_path;
  o.free = free;
  o.sets = sets;
  o.model = model;
  o.noise = noise;
  o.starts = starts;
  o.local = local;
  o.profile = profile;
  o.out = out;
  o.quiet = true;
  o.no_plot = !plot;
  int code = 0;
  runReleased([&] { code = cli::fitCommand(o); });
  return code;
}

}  // namespace

void bindFiles(py::module_& m) {
  m.def("network_run", &networkRun, py::arg("rig_path"), py::arg("sets"), py::arg("model"),
        py::arg("engine"), py::arg("out"), py::arg("plot"));
  m.def("continue_command", &continueCommand, py::arg("rig_path"), py::arg("sets"),
        py::arg("model"), py::arg("param"), py::arg("to"), py::arg("out"),
        py::arg("from_") = std::nullopt, py::arg("start") = "", py::arg("step") = 0.0,
        py::arg("max_points") = 500, py::arg("all") = false, py::arg("no_cycles") = false,
        py::arg("fold") = "", py::arg("to2") = 0.0);
  m.def("fit_command", &fitCommand, py::arg("rig_path"), py::arg("data_path"), py::arg("free"),
        py::arg("sets"), py::arg("model"), py::arg("out"), py::arg("plot"),
        py::arg("noise") = std::nullopt, py::arg("starts") = 6, py::arg("local") = false,
        py::arg("profile") = false);
}

}  // namespace metrosync::python
