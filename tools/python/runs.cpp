// run and compare for Python: the CLI's commands (tools/cli/commands.h) with the rows kept in
// memory, and files only into `out`.
#include <pybind11/stl.h>

#include "tools/cli/commands.h"
#include "tools/python/bindings.h"

namespace metrosync::python {

namespace {

namespace cli = metrosync::cli;

cli::Options runOptions(const RigSource& rig, const std::string& model, const std::string& engine,
                        const std::optional<std::string>& out) {
  cli::Options o;
  o.rig_path = rig.path;
  o.rig_text = rig.text;
  o.sets = rig.sets;
  o.model = model;
  o.engine = engine;
  o.quiet = true;
  o.no_files = !out;  // no folder, no plot: the rows stay here
  o.out = out.value_or("");
  return o;
}

// One model's rows: {"trajectory": (names, array) or None, "envelope": ..., "events": (names,
// array, kinds, who) or None}.
py::dict rowsToPython(RunColumns&& rows, bool full) {
  py::dict d;
  d["trajectory"] = full ? py::object(tableToPython(std::move(rows.trajectory))) : py::none();
  d["envelope"] = tableToPython(std::move(rows.envelope));
  if (full) {
    py::tuple events = tableToPython(std::move(rows.events));
    d["events"] = py::make_tuple(events[0], events[1], rows.event_kinds, rows.event_who);
  } else {
    d["events"] = py::none();
  }
  return d;
}

// `run`: {"code", "summary" (summary.json's text), "model", and its rows (rowsToPython)}.
py::dict run(const RigSource& rig, const std::string& model, const std::string& engine,
             const std::optional<std::string>& out) {
  cli::RunOutcome r;
  runReleased([&] { r = cli::runKeepingRows(runOptions(rig, model, engine, out)); });
  const bool full = r.summary.value("model", "") == "full";
  py::dict d = rowsToPython(std::move(*r.rows), full);
  d["code"] = r.code;
  d["summary"] = r.summary.dump();
  return d;
}

// `compare`: {"code", "summary", "full": rows, "slow": rows, "comparison": (names, array)}.
py::dict compare(const RigSource& rig, const std::string& engine,
                 const std::optional<std::string>& out) {
  cli::RunOutcome r;
  runReleased([&] { r = cli::compareKeepingRows(runOptions(rig, "", engine, out)); });
  py::dict d;
  d["code"] = r.code;
  d["summary"] = r.summary.dump();
  d["full"] = rowsToPython(std::move(*r.rows), true);
  d["slow"] = rowsToPython(std::move(*r.slow_rows), false);
  d["comparison"] = tableToPython(std::move(r.comparison));
  return d;
}

}  // namespace

void bindRuns(py::module_& m) {
  m.def("run", &run, py::arg("rig"), py::arg("model") = "", py::arg("engine") = "",
        py::arg("out") = std::nullopt);
  m.def("compare", &compare, py::arg("rig"), py::arg("engine") = "", py::arg("out") = std::nullopt);
}

}  // namespace metrosync::python
