// The module `_metrosync` (tools/python/bindings.h): its exceptions, the rig's checks and the
// shared helpers of runs.cpp, grids.cpp and files.cpp.
#include <pybind11/stl.h>
#include <signal.h>

#include "sim/analysis/sweep.h"
#include "sim/record/atomic_file.h"
#include "tools/cli/commands.h"
#include "tools/python/bindings.h"
#include "tools/report/outputs.h"
#include "yaml/network_loader.h"
#include "yaml/rig_loader.h"

namespace metrosync::python {

namespace cli = metrosync::cli;

namespace {

// The process's SIGINT/SIGTERM handlers (Python's own), put back when a command ends.
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

cli::Options scaleOptions(const RigSource& rig) {
  cli::Options o;
  o.rig_path = rig.path;
  o.rig_text = rig.text;
  o.sets = rig.sets;
  o.quiet = true;
  return o;
}

// Is the rig a network that is not a single rig (the commands' test, yaml/network_loader.h)?
bool isNetwork(const RigSource& rig) {
  const std::string text = rig.text ? *rig.text : readRigFile(rig.path);
  return loadPlatformsNetwork(text, rig.path, rig.sets).has_value();
}

std::string resolvedJson(const RigSource& rig) {
  return resolvedRigJson(rig.text ? *rig.text : readRigFile(rig.path), rig.path, rig.sets);
}

}  // namespace

void runReleased(const std::function<void()>& command) {
  {
    py::gil_scoped_release release;
    SignalHandlersKept keep;
    FileSink::clearStopRequest();
    command();
  }
  if (FileSink::stopRequested()) {
    FileSink::clearStopRequest();
    throw py::error_already_set([] {
      PyErr_SetNone(PyExc_KeyboardInterrupt);
      return py::error_already_set();
    }());
  }
}

py::array vectorToPython(std::vector<double>&& values) {
  auto* owned = new std::vector<double>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>({static_cast<py::ssize_t>(owned->size())}, owned->data(), owner);
}

py::tuple tableToPython(ColumnTable&& table) {
  const auto cols = static_cast<py::ssize_t>(table.names.size());
  const auto rows = static_cast<py::ssize_t>(table.rows());
  auto* owned = new std::vector<double>(std::move(table.values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  const py::ssize_t row_bytes = cols * static_cast<py::ssize_t>(sizeof(double));
  py::array_t<double> a({rows, cols}, {row_bytes, static_cast<py::ssize_t>(sizeof(double))},
                        owned->data(), owner);
  return py::make_tuple(table.names, a);
}

}  // namespace metrosync::python

using namespace metrosync;
using namespace metrosync::python;

PYBIND11_MODULE(_metrosync, m) {
  m.doc() = "metrosync's C++ core (use the package `metrosync`)";
  static py::exception<RigError> rig_error(m, "RigError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const RigError& e) {
      PyErr_SetString(rig_error.ptr(), e.what());
    } catch (const cli::UsageError& e) {
      PyErr_SetString(rig_error.ptr(), e.what());
    } catch (const SweepInputError& e) {
      PyErr_SetString(rig_error.ptr(), e.what());
    }
  });
  py::class_<RigSource>(m, "RigSource")
      .def(py::init<std::optional<std::string>, std::string, std::vector<std::string>>(),
           py::arg("text"), py::arg("path"), py::arg("sets"));
  m.def(
      "scaled_json", [](const RigSource& rig) { return cli::scaledJsonText(scaleOptions(rig)); },
      py::arg("rig"));
  m.def("resolved_json", &resolvedJson, py::arg("rig"));
  m.def("is_network", &isNetwork, py::arg("rig"));
  m.def("version", [] { return std::string(metrosyncVersion()); });
  bindRuns(m);
  bindGrids(m);
  bindFiles(m);
}
