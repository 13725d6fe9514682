#include "tools/bench/run_verdict.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tools/bench/bench_metrics.h"

namespace metrosync::bench {

namespace {

// "integrator:setting" of "engine:integrator:setting"
std::string afterEngine(const std::string& method) {
  const size_t colon = method.find(':');
  return colon == std::string::npos ? method : method.substr(colon + 1);
}

}  // namespace

std::string runPointsMarkdown(const std::vector<RunOverhead>& rows) {
  std::ostringstream os;
  const std::string target = benchNumber(kRunOverEngineTarget, 2, Notation::Fixed);
  const auto mark = [](double v) {
    const std::string t = benchNumber(v, 2, Notation::Fixed);
    return !std::isfinite(v) || v <= kRunOverEngineTarget ? t : "**" + t + "**";
  };
  os << "| scene | method | wall_seconds | engine_seconds | wall / engine | engine alone | wall / "
        "engine alone |\n|---|---|---|---|---|---|---|\n";
  for (const RunOverhead& o : rows)
    os << "| " << o.scene << " | " << o.method << " | " << benchNumber(1e3 * o.wall_s, 3)
       << " ms | " << benchNumber(1e3 * o.engine_s, 3) << " ms | " << mark(o.wall_over_engine)
       << " | " << (std::isfinite(o.alone_s) ? benchNumber(1e3 * o.alone_s, 3) + " ms" : "-")
       << " | " << mark(o.overAlone()) << " |\n";
  os << "\nwall / engine: the median over the runs of each run's wall_seconds / engine_seconds "
        "(summary.json); engine alone: the direct engine in the bench's process at the same "
        "integrator and accuracy with recording off (its final-state runs, wall median). Target "
        "<= "
     << target << " for both (**bold**: above it).\n";
  return os.str();
}

std::string runPointsCsv(const std::vector<RunOverhead>& rows) {
  std::string s =
      "scene,method,wall_seconds,engine_seconds,wall_over_engine,engine_alone_s,wall_over_alone,"
      "target\n";
  for (const RunOverhead& o : rows)
    s += csvField(o.scene) + "," + o.method + "," + benchNumber(o.wall_s, 6) + "," +
         benchNumber(o.engine_s, 6) + "," + benchNumber(o.wall_over_engine, 6) + "," +
         benchNumber(o.alone_s, 6) + "," + benchNumber(o.overAlone(), 6) + "," +
         benchNumber(kRunOverEngineTarget, 2, Notation::Fixed) + "\n";
  return s;
}

std::vector<VerdictScene> runAsOurs(const std::vector<VerdictScene>& scenes) {
  std::vector<VerdictScene> out;
  for (const VerdictScene& s : scenes) {
    if (s.run.empty()) continue;
    VerdictScene r = s;
    r.ours = s.run;
    r.our_methods = s.run_methods;
    out.push_back(std::move(r));
  }
  return out;
}

std::vector<RunOverhead> runOverheads(const std::vector<VerdictScene>& scenes) {
  std::vector<RunOverhead> rows;
  for (const VerdictScene& s : scenes)
    for (const SidePoint& p : s.run) {
      RunOverhead o{s.name, p.method, p.wall_s, p.engine_s, p.wall_over_engine, NAN};
      for (const SidePoint& q : s.ours)
        if (afterEngine(q.method) == afterEngine(p.method))
          o.alone_s = std::isfinite(q.wall_final_s) ? q.wall_final_s : q.wall_s;
      rows.push_back(o);
    }
  return rows;
}

}  // namespace metrosync::bench
