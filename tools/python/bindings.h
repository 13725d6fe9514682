// The C++ side of the Python module `metrosync` (tools/python/metrosync/ is the API,
// docs/python.md): the CLI's own code called in-process with the interpreter's lock released, its
// results handed to Python as numpy arrays over the engine's numbers (tools/report/run_columns.h)
// and JSON text. module.cpp: the exceptions, the rig's checks, version; runs.cpp: run and compare;
// grids.cpp: sweep and basin; files.cpp: the commands that still write into a folder.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <vector>

#include "tools/report/run_columns.h"

namespace metrosync::python {

namespace py = pybind11;

// Runs `command` with the interpreter's lock released, metrosync's SIGINT/SIGTERM handlers in
// place of Python's (a signal asks the running simulation to stop) and Python's put back
// afterwards. A stop request raises KeyboardInterrupt once the command has ended.
void runReleased(const std::function<void()>& command);

// A table as (names, 2-D float64 array rows x columns) over its own numbers, moved, not copied.
py::tuple tableToPython(ColumnTable&& table);
// A vector of doubles as a 1-D float64 array, moved.
py::array vectorToPython(std::vector<double>&& values);

// The rig as a command takes it: rig_text (a dict's YAML; nullopt: the file at rig_path) and
// rig_path (the file, or the name standing for the dict in messages).
struct RigSource {
  std::optional<std::string> text;
  std::string path;
  std::vector<std::string> sets;
};

void bindRuns(py::module_& m);
void bindGrids(py::module_& m);
void bindFiles(py::module_& m);

}  // namespace metrosync::python
