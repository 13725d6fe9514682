// metrosync_bench: speed against error of the full model's engines (issues "Speed against
// error", 11 and 23).
//   precision  work-precision on rig files: every engine:integrator at every accuracy (Siconos's
//              Moreau-Jean peer at every step size; the careful peer, a separate program, as
//              peer:dopri5 and peer:rkf78), against a reference run at the tightest tolerance
//              that a second integrator cross-checks; CSV, Markdown, gnuplot PNG, the time ratios
//              of the engines at equal error, and the verdict against the peer (ratios.md)
//   ratios     the verdict recomputed from precision's CSV files
//   peer       where the careful peer is, or why it is missing
//   nscale     cost per fast period against the number of metronomes N, per engine
//   runcost    `metrosync run` (the built binary) against its engine: wall_seconds /
//   engine_seconds,
//              and wall_seconds against the same engine with recording off
//   process    the whole `metrosync run` process against its wall_seconds, phase by phase
//   eventcost  the direct engine's cost per step and per event against one RHS evaluation
//   fitcost    one fit's wall and CPU time on the fit bench, against one run of the same rig
//   continue   `metrosync continue ... --all`'s wall time
//   maps       the wall time of the 64 x 64 full-model and 100 x 100 slow-flow regime maps
//   summary    the summary of one run of tools/bench/speed.sh, and README.md's speed paragraph
// Timings are medians of --repeat runs in this process (no process start-up in them; the careful
// peer's inside its own process; runcost and maps time whole processes); before each timed run
// the tool waits until the 1-minute load average is below --max-load, because the machine is
// shared, and it records the load it saw.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <random>
#include <sstream>
#include <thread>

#include "base/constants.h"
#include "base/number_text.h"
#include "tools/bench/bench_measure.h"
#include "tools/bench/bench_report.h"
#include "tools/bench/bench_run.h"
#include "tools/bench/careful_peer.h"
#include "tools/bench/continue_cost.h"
#include "tools/bench/event_cost.h"
#include "tools/bench/fit_cost.h"
#include "tools/bench/map_timing.h"
#include "tools/bench/peer_scene.h"
#include "tools/bench/peer_verdict_report.h"
#include "tools/bench/process_cost.h"
#include "tools/bench/run_cost.h"
#include "tools/bench/run_method.h"
#include "tools/bench/run_verdict.h"
#include "tools/bench/siconos_peer.h"
#include "tools/bench/speed_summary.h"
#include "tools/bench/wp_csv.h"
#include "tools/report/outputs.h"

namespace mb = metrosync::bench;
using metrosync::Notation;
using metrosync::numberText;

namespace {

using Common = mb::BenchOptions;

// The methods of `c.engine` only (all of them when it is empty); none left is an error.
std::vector<mb::Method> ofEngine(std::vector<mb::Method> methods, const Common& c) {
  if (c.engine.empty()) return methods;
  if (!mb::engineAvailable(c.engine))
    throw std::invalid_argument("--engine " + c.engine +
                                ": not a full-model engine of this build (direct, simbody" +
                                (mb::siconosAvailable() ? ", siconos)" : ")"));
  methods.erase(std::remove_if(methods.begin(), methods.end(),
                               [&](const mb::Method& m) { return m.engine != c.engine; }),
                methods.end());
  if (methods.empty())
    throw std::invalid_argument("--engine " + c.engine + ": none of --methods is of that engine");
  return methods;
}

// A comma-separated list of numbers; std::invalid_argument naming the item that is not one.
std::vector<double> parseList(const std::string& s) {
  std::vector<double> v;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');) {
    if (item.empty()) continue;
    size_t used = 0;
    try {
      v.push_back(std::stod(item, &used));
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size())
      throw std::invalid_argument("'" + item + "' in the list '" + s + "' is not a number");
  }
  return v;
}

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> v;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) v.push_back(item);
  return v;
}

std::string loadRange(const std::vector<mb::Record>& recs) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& r : recs)
    if (r.runs > 0) lo = std::min(lo, r.load_min), hi = std::max(hi, r.load_max);
  return std::isfinite(lo)
             ? numberText(lo, 2, Notation::Fixed) + " ... " + numberText(hi, 2, Notation::Fixed)
             : "n/a";
}

// c.out/NAME.csv (unless `csv` is empty) and c.out/NAME.md, the Markdown on stdout when `print`
// and not quiet.
void writeReport(const Common& c, const std::string& name, const std::string& csv,
                 const std::string& md, bool print = true) {
  std::filesystem::create_directories(c.out);
  if (!csv.empty()) metrosync::writeFileAtomically(c.out + "/" + name + ".csv", csv);
  metrosync::writeFileAtomically(c.out + "/" + name + ".md", md);
  if (print && !c.quiet) std::cout << md << "\n";
}

// The verdict against the peer over `scenes`: ratios.md, ratios.csv, nslope.csv in c.out, the page
// on stdout, its failed guards on stderr. Nothing (and a note) when no scene has both sides (or
// the peer's reason for not running it) and fewer than two scenes of the N-slope were measured.
void writeVerdict(const std::vector<mb::VerdictScene>& scenes, const mb::VerdictOptions& o,
                  const Common& c) {
  // `run` against its engine at each of its points: runpoints.csv and .md, peer or no peer
  if (const auto over = mb::runOverheads(scenes); !over.empty())
    writeReport(c, "runpoints", mb::runPointsCsv(over), mb::runPointsMarkdown(over), false);
  // the ratio tables need both sides (or a scene the peer could not run); the N-slope only
  // metrosync's points on two or more of its scenes
  int both = 0, slope_scenes = 0;
  for (const mb::VerdictScene& s : scenes) {
    both += !s.ours.empty() && (!s.peer.empty() || !s.peer_skipped.empty());
    slope_scenes +=
        !s.ours.empty() && std::count(o.slope_scenes.begin(), o.slope_scenes.end(), s.name) > 0;
  }
  if (both == 0 && slope_scenes < 2) {
    if (!c.quiet)
      std::cerr << "(no scene has timed points of both " << o.sides.ours << " and " << o.sides.peer
                << ", nor two N-slope scenes: no verdict)\n";
    return;
  }
  const mb::VerdictPages p = mb::verdictPages(scenes, o);
  std::filesystem::create_directories(c.out);
  metrosync::writeFileAtomically(c.out + "/ratios.md", p.markdown);
  metrosync::writeFileAtomically(c.out + "/ratios.csv", p.ratios_csv);
  metrosync::writeFileAtomically(c.out + "/nslope.csv", p.slope_csv);
  metrosync::writeFileAtomically(c.out + "/verdicts.md", p.verdicts_markdown);
  if (!c.quiet) std::cout << p.markdown << "\n";
  for (const std::string& w : p.warnings) std::cerr << "metrosync_bench: warning: " << w << "\n";
  if (!c.quiet) std::cerr << p.verdict_line << "\n";
}

// The command line as typed, for the pages (arguments with spaces or quotes single-quoted).
std::string commandLine(int argc, char** argv) {
  std::string s;
  for (int k = 0; k < argc; ++k) {
    std::string a = argv[k];
    if (a.empty() || a.find_first_of(" '\"$*?") != std::string::npos) {
      std::string q = "'";
      for (char ch : a) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
      a = q + "'";
    }
    s += (k ? " " : "") + a;
  }
  return s;
}

// ---------------------------------------------------------------------------------------------
struct PrecisionOptions {
  std::vector<std::string> scenes, sets;
  std::string methods;     // "" = every integrator of every available engine
  std::string run_scenes;  // the scenes (names) the run methods are timed on ("" = all)
  std::string accuracies = "1e-3,1e-4,1e-5,1e-6,1e-7,1e-8,1e-9,1e-10";
  std::string simbody_accuracies;  // "" = accuracies
  std::string siconos_steps = "64,128,256,512,1024,2048,4096,8192,16384";
  std::string reference = "direct:verner76:1e-12";
  std::vector<std::string> cross_checks = {"simbody:rk-merson:1e-12"};
  double ref_budget_s = 1800;
  mb::VerdictOptions verdict;
};

// What precision runs: the methods, their settings, the reference and its cross-checks.
struct PrecisionPlan {
  std::vector<mb::Method> methods;
  std::vector<double> accuracies, simbody_accuracies, siconos_steps;
  mb::Method reference;
  std::vector<mb::Method> cross_checks;
  const std::vector<double>& settingsOf(const mb::Method& m) const {
    if (m.engine == "siconos") return siconos_steps;
    return m.engine == "simbody" ? simbody_accuracies : accuracies;
  }
};

PrecisionPlan precisionPlan(const PrecisionOptions& o, const Common& c) {
  PrecisionPlan plan;
  if (o.methods.empty()) {
    for (const char* e : {"direct", "simbody", "siconos", "odeint", "peer"})
      if (mb::engineAvailable(e))
        for (const auto& i : mb::integratorsOf(e))
          plan.methods.push_back(mb::parseMethod(std::string(e) + ":" + i));
  } else {
    for (const auto& s : splitList(o.methods)) {
      const size_t star = s.find(":*");  // ENGINE:* = every integrator of the engine
      if (star == std::string::npos || star + 2 != s.size()) {
        plan.methods.push_back(mb::parseMethod(s));
        continue;
      }
      const std::string e = s.substr(0, star);
      mb::parseMethod(e);  // an unknown or missing engine: its message
      for (const auto& i : mb::integratorsOf(e))
        plan.methods.push_back(mb::parseMethod(e + ":" + i));
    }
  }
  plan.methods = ofEngine(std::move(plan.methods), c);
  plan.accuracies = parseList(o.accuracies);
  plan.simbody_accuracies =
      o.simbody_accuracies.empty() ? plan.accuracies : parseList(o.simbody_accuracies);
  plan.siconos_steps = parseList(o.siconos_steps);
  plan.reference = mb::parseMethod(o.reference);
  if (plan.reference.engine == "peer")
    throw std::invalid_argument("--reference " + o.reference +
                                ": the careful peer reports no envelope; give it as a "
                                "--cross-check of an in-process reference");
  for (const auto& s : o.cross_checks) plan.cross_checks.push_back(mb::parseMethod(s));
  return plan;
}

// A record for a point that was not run (why: its status).
mb::Record notRun(const mb::Scene& scene, const mb::Method& m, const std::string& status,
                  const std::string& note = "") {
  mb::Record r;
  r.scene = scene.name;
  r.n_metronomes = static_cast<int>(scene.rig.metronomes.size());
  r.periods = scene.periods;
  r.method = m;
  r.status = status;
  r.note = note;
  return r;
}

// One method over its settings, in order; a setting predicted to exceed the budget (from the
// growth of the last two) and every one after it is skipped.
void measureSettings(const mb::Scene& scene, const mb::Method& base_m,
                     const std::vector<double>& settings, const mb::RunResult& ref, const Common& c,
                     std::vector<mb::Record>& recs, const std::function<void()>& save) {
  double prev_wall = 0, last_wall = 0;
  bool stop = false;
  for (double s : settings) {
    mb::Method m = base_m;
    (m.engine == "siconos" ? m.steps_per_period : m.accuracy) = s;
    if (stop) {
      recs.push_back(notRun(scene, m, "skipped (predicted over budget)"));
      continue;
    }
    mb::Record r = mb::measure(scene, m, &ref, c, c.budget_s, c.repeat, true);
    recs.push_back(r);
    save();
    if (r.status == "over budget") {
      stop = true;
      continue;
    }
    if (r.status != "ok") continue;
    prev_wall = last_wall;
    last_wall = r.wall_median_s;
    // the next setting costs about as much more as this one did over the previous one
    const double growth = prev_wall > 0 ? std::max(1.0, last_wall / prev_wall) : 1.0;
    if (last_wall * growth > 3 * c.budget_s) stop = true;
  }
}

// The scene's wp-<scene>.md (table and ratios), -equal-error.csv and .png.
void writeSceneReport(const mb::Scene& scene, const mb::Method& ref_method,
                      const std::vector<mb::Record>& recs, const std::string& base,
                      const Common& c) {
  std::string ratio_csv;
  const std::string ratios = mb::ratiosMarkdown(recs, ratio_csv);
  metrosync::writeFileAtomically(base + "-equal-error.csv",
                                 "scene,a,b,error,time_a_s,time_b_s,ratio\n" + ratio_csv);
  std::ostringstream md;
  md << "### " << scene.name << "\n\n"
     << "`" << (scene.path.empty() ? scene.name : scene.path)
     << "`: N = " << scene.rig.metronomes.size()
     << ", epsilon = " << numberText(scene.scaled.epsilon, 4)
     << ", tau_end = " << numberText(scene.scaled.tau_end, 4) << " ("
     << numberText(scene.periods, 0, Notation::Fixed) << " fast periods, "
     << numberText(scene.rig.sim.t_end_s, 4) << " s). Reference " << ref_method.label() << " at "
     << ref_method.setting() << "; 1-minute load during the "
     << "timed runs " << loadRange(recs) << ".\n\n"
     << mb::precisionTable(recs) << "\nTime ratios at equal error (CPU medians, a / b; < 1: a "
     << "is faster):\n\n"
     << ratios << "\n![work-precision " << scene.name << "](wp-" << scene.name << ".png)\n";
  metrosync::writeFileAtomically(base + ".md", md.str());
  mb::plotWorkPrecision(base + ".png", recs,
                        "work-precision: " + scene.name +
                            " (N = " + std::to_string(scene.rig.metronomes.size()) + ", " +
                            numberText(scene.periods, 0, Notation::Fixed) + " fast periods)");
  if (!c.quiet) std::cout << md.str() << "\n";
}

// One scene: the reference (timed once: it is not on the curves) and its cross-checks, every
// method over its settings, the scene's files. 3 if the reference did not finish, else 0.
int precisionScene(const mb::Scene& scene, const PrecisionPlan& plan, const PrecisionOptions& o,
                   const Common& c, std::vector<mb::Record>& recs) {
  if (!c.quiet)
    std::cerr << scene.name << ": N = " << scene.rig.metronomes.size() << ", "
              << numberText(scene.periods, 0, Notation::Fixed)
              << " fast periods, tau_end = " << numberText(scene.scaled.tau_end, 4)
              << ", epsilon = " << numberText(scene.scaled.epsilon, 4) << "\n";
  const std::string base = c.out + "/wp-" + scene.name;
  const std::function<void()> save = [&]() {
    metrosync::writeFileAtomically(base + ".csv", mb::recordsCsv(recs));
  };
  mb::RunResult ref;
  mb::Record rr = mb::measure(scene, plan.reference, nullptr, c, o.ref_budget_s, 1, false, &ref);
  if (rr.status != "ok") {
    std::cerr << "metrosync_bench: " << scene.name << ": the reference run "
              << plan.reference.label() << " " << plan.reference.setting()
              << " did not finish: " << rr.note << "\n";
    return 3;
  }
  rr.status = "reference";
  recs.push_back(rr);
  for (const mb::Method& m : plan.cross_checks) {
    if (m.engine == "peer" && !mb::peerUnsupported(scene).empty()) {
      recs.push_back(notRun(scene, m, "not run", mb::peerUnsupported(scene)));
      continue;
    }
    mb::Record cr = mb::measure(scene, m, &ref, c, o.ref_budget_s, 1, false);
    if (cr.status == "ok") cr.status = "cross-check";
    recs.push_back(cr);
    save();
  }
  for (const mb::Method& m : plan.methods) {
    if (m.engine == "siconos" && !mb::siconosUnsupported(scene.rig).empty()) {
      recs.push_back(notRun(scene, m, "not run", mb::siconosUnsupported(scene.rig)));
      continue;
    }
    if (m.engine == "peer" && !mb::peerUnsupported(scene).empty()) {
      recs.push_back(notRun(scene, m, "not run", mb::peerUnsupported(scene)));
      continue;
    }
    const std::vector<std::string> run_on = splitList(o.run_scenes);
    if (m.engine == "run" && !run_on.empty() &&
        std::find(run_on.begin(), run_on.end(), scene.name) == run_on.end())
      continue;  // --run-scenes: `run` is timed elsewhere
    measureSettings(scene, m, plan.settingsOf(m), ref, c, recs, save);
  }
  save();
  writeSceneReport(scene, plan.reference, recs, base, c);
  return 0;
}

int precision(const PrecisionOptions& o, const Common& c) {
  if (c.repeat < mb::kMinRunsForResult)
    std::cerr << "metrosync_bench: warning: --repeat " << c.repeat << " < " << mb::kMinRunsForResult
              << ": medians of fewer runs than issue 11 asks for; the "
              << "ratio table will not be a result\n";
  const PrecisionPlan plan = precisionPlan(o, c);
  std::filesystem::create_directories(c.out);
  std::vector<mb::VerdictScene> verdict_scenes;  // read back from each scene's CSV
  for (const std::string& path : o.scenes) {
    const mb::Scene scene = mb::loadScene(path, o.sets);
    std::vector<mb::Record> recs;
    if (const int rc = precisionScene(scene, plan, o, c, recs)) return rc;
    const std::string csv = c.out + "/wp-" + scene.name + ".csv";
    for (auto& v : mb::parseWorkPrecisionCsv(mb::recordsCsv(recs), csv, o.verdict.sides))
      verdict_scenes.push_back(std::move(v));
  }
  writeVerdict(verdict_scenes, o.verdict, c);
  return 0;
}

// ---------------------------------------------------------------------------------------------
// The verdict recomputed from precision's CSV files (*-equal-error.csv files are skipped).
int ratios(const std::vector<std::string>& files, const mb::VerdictOptions& o, const Common& c) {
  std::vector<mb::VerdictScene> scenes;
  for (const std::string& f : files) {
    const std::string tail = "-equal-error.csv";
    if (f.size() >= tail.size() && f.compare(f.size() - tail.size(), tail.size(), tail) == 0)
      continue;
    std::ifstream in(f);
    if (!in) throw std::invalid_argument(f + ": cannot be read");
    std::stringstream text;
    text << in.rdbuf();
    for (auto& v : mb::parseWorkPrecisionCsv(text.str(), f, o.sides)) {
      for (const auto& s : scenes)
        if (s.name == v.name) throw std::invalid_argument(f + ": scene " + v.name + " given twice");
      scenes.push_back(std::move(v));
    }
  }
  writeVerdict(scenes, o, c);
  return 0;
}

// ---------------------------------------------------------------------------------------------
struct NScaleOptions {
  std::string ns = "1,2,4,8,16,32,64,100";
  double periods = 20;
  std::string methods = "direct:verner65:1e-8,simbody:rk-merson:1e-8,siconos:moreau-jean:256";
  double mu_bar = 1e-4;
  double board_kg = 0.8;
  unsigned seed = 7;
};

// N Wittner metronomes as in yaml/rigs/experiment.yaml on a board of board_kg (epsilon N < 1 for
// any N in physical units: epsilon N = N m / (M_board + N m_metronome) < m / m_metronome = 0.27),
// started at 45 degrees with phases drawn from a fixed seed.
metrosync::Rig nRig(int n, const NScaleOptions& o) {
  metrosync::Rig rig;
  rig.name = "n" + std::to_string(n);
  rig.platform.mass_kg = o.board_kg;
  rig.platform.friction = metrosync::FrictionLaw::coulomb(o.mu_bar);
  std::mt19937 gen(o.seed);
  std::uniform_real_distribution<double> phase(0.0, metrosync::kTwoPi);
  for (int i = 0; i < n; ++i) {
    metrosync::MetronomeSpec m;
    m.name = "M" + std::to_string(i + 1);
    m.box_mass_kg = 0.0602;
    m.pendulum_mass_kg = 0.0226;
    m.length_m = 0.0225;
    m.inertia_kgm2 = m.pendulum_mass_kg * m.length_m * m.length_m;
    m.damping_kg_s = 2 * 0.5 * m.inertia_kgm2 / (m.length_m * m.length_m);  // decay rate 0.5/s
    m.theta_c_rad = 0.244;
    m.impulse_Nms = 1.49e-5;  // steady amplitude ~0.785 rad alone on a still table
    const double phi = phase(gen), w0 = std::sqrt(9.81 / m.length_m);
    m.start_angle_rad = 0.785 * std::sin(phi);
    m.start_rate_rad_s = 0.785 * w0 * std::cos(phi);
    rig.metronomes.push_back(m);
  }
  const double omega0 = std::sqrt(9.81 / 0.0225);
  rig.sim.t_end_s = o.periods * metrosync::kTwoPi / omega0;
  return rig;
}

int nscale(const NScaleOptions& o, const Common& c) {
  std::vector<mb::Method> methods;
  for (const auto& s : splitList(o.methods)) methods.push_back(mb::parseMethod(s));
  methods = ofEngine(std::move(methods), c);
  std::filesystem::create_directories(c.out);
  std::vector<mb::Record> recs;
  std::vector<bool> stopped(methods.size(), false);
  for (double nd : parseList(o.ns)) {
    const int n = static_cast<int>(nd);
    const mb::Scene scene = mb::sceneFromRig("n" + std::to_string(n), nRig(n, o));
    for (size_t k = 0; k < methods.size(); ++k) {
      if (stopped[k]) continue;  // a larger N would only take longer
      mb::Record r = mb::measure(scene, methods[k], nullptr, c, c.budget_s, c.repeat, false);
      recs.push_back(r);
      if (r.status == "over budget") stopped[k] = true;
      metrosync::writeFileAtomically(c.out + "/nscale.csv", mb::recordsCsv(recs));
    }
  }
  std::ostringstream md;
  md << "Cost per fast period (median wall time of the run / " << numberText(o.periods)
     << " fast periods, milliseconds) against N; board " << o.board_kg << " kg, mu-bar " << o.mu_bar
     << ", phases from seed " << o.seed << "; 1-minute load during the timed runs "
     << loadRange(recs) << ".\n\n"
     << mb::nscaleTable(recs);
  metrosync::writeFileAtomically(c.out + "/nscale.md", md.str());
  mb::plotNScaling(c.out + "/nscale.png", recs,
                   "cost per fast period against N (" + numberText(o.periods) + " periods)");
  if (!c.quiet) std::cout << md.str();
  return 0;
}

// ---------------------------------------------------------------------------------------------
// 3 when a row failed, else 0
template <class Rows>
int failedRows(const Rows& rows) {
  for (const auto& r : rows)
    if (!r.failure.empty()) return 3;
  return 0;
}

int runCost(const mb::RunCostOptions& o, const Common& c, const std::string& command) {
  if (o.scenes.empty()) throw std::invalid_argument("runcost: no --scene");
  const std::vector<mb::RunCostRow> rows = mb::measureRunCost(o, c);
  writeReport(c, "run", mb::runCostCsv(rows), mb::runCostMarkdown(rows, command));
  return failedRows(rows);
}

int maps(const mb::MapOptions& o, const Common& c) {
  const std::vector<mb::MapRow> rows = mb::timeMaps(o, c);
  writeReport(c, "maps", mb::mapsCsv(rows), mb::mapsMarkdown(rows));
  return failedRows(rows);
}

int processCost(const mb::ProcessOptions& o, const Common& c, const std::string& command) {
  const mb::ProcessMeasurement m = mb::measureProcess(o, c);
  if (!m.failure.empty()) {
    writeReport(c, "process", "", "**The whole process was not measured: " + m.failure + ".**\n");
    return 3;
  }
  writeReport(c, "process", mb::processCsv(m.breakdown, o.scene, m.load_min, m.load_max),
              mb::processMarkdown(m.breakdown, m.command) + "\nThe bench's command:\n\n    " +
                  command + "\n");
  return 0;
}

struct EventCostArgs {
  std::vector<std::string> scenes;
  std::string accuracies = "1e-6,1e-9";
};

int eventCost(const EventCostArgs& a, const Common& c, const std::string& command) {
  if (a.scenes.empty()) throw std::invalid_argument("eventcost: no --scene");
  const double load0 = mb::loadAverage1();
  const std::vector<mb::EventCostRow> rows =
      mb::measureEventCost({a.scenes, parseList(a.accuracies)}, c);
  const double load1 = mb::loadAverage1();
  writeReport(c, "eventcost",
              mb::eventCostCsv(rows, std::fmin(load0, load1), std::fmax(load0, load1)),
              mb::eventCostMarkdown(rows, command));
  return failedRows(rows);
}

int fitCost(const mb::FitCostOptions& o, const Common& c) {
  const mb::FitCost f = mb::measureFitCost(o, c);
  writeReport(c, "fit", mb::fitCostCsv(f), mb::fitCostMarkdown(f, o));
  return f.failure.empty() ? 0 : 3;
}

int continueCost(const mb::ContinueCostOptions& o, const Common& c) {
  const std::vector<mb::ContinueCostRow> rows = mb::measureContinueCost(o, c);
  writeReport(c, "continuation", mb::continueCostCsv(rows), mb::continueCostMarkdown(rows));
  for (const auto& r : rows)
    if (!r.failure.empty() && !r.timed_out) return 3;
  return 0;
}

struct SummaryOptions {
  std::string dir = "docs/bench/speed";
  std::string readme;  // README.md to rewrite between the markers ("" = none)
  std::string date, commit;
};

// DIR/README.md and the paragraph (stdout); README.md's marked block rewritten when asked.
int summary(const SummaryOptions& o, const Common& c) {
  mb::SpeedInputs in = mb::readSpeedInputs(o.dir);
  in.date = o.date;
  in.commit = o.commit;
  in.folder = o.dir;
  const mb::SpeedFacts f = mb::speedFacts(in);
  const std::string paragraph = mb::speedParagraph(f, in);
  metrosync::writeFileAtomically(o.dir + "/README.md", mb::speedPage(f, in));
  if (!o.readme.empty()) {
    std::ifstream r(o.readme);
    if (!r) throw std::invalid_argument(o.readme + ": cannot be read");
    std::stringstream text;
    text << r.rdbuf();
    metrosync::writeFileAtomically(
        o.readme, mb::replaceBetweenMarkers(text.str(), mb::kSpeedBegin, mb::kSpeedEnd, paragraph));
  }
  if (!c.quiet) std::cout << paragraph;
  return 0;
}

void addCommon(CLI::App* cmd, Common& c) {
  cmd->add_option("--engine", c.engine,
                  "time only this engine's methods (direct, simbody, siconos when built in)");
  cmd->add_option("--repeat", c.repeat, "timed runs per point (median)")->capture_default_str();
  cmd->add_option("--budget", c.budget_s,
                  "seconds a run may take; longer runs are stopped and the tighter settings of "
                  "that integrator skipped")
      ->capture_default_str();
  cmd->add_option("--max-load", c.max_load,
                  "wait before each timed run until the 1-minute load average is below this "
                  "(0: never wait)")
      ->capture_default_str();
  cmd->add_option("--max-wait", c.max_wait_s, "seconds to wait for the load at most, per run")
      ->capture_default_str();
  cmd->add_option("--out", c.out, "output directory")->capture_default_str();
  cmd->add_flag("-q,--quiet", c.quiet, "no progress on stderr, no tables on stdout");
  cmd->add_option("--envelopes", c.envelopes,
                  "write the envelope of every measured point (its first run) to DIR/*.csv")
      ->type_name("DIR");
}

// The verdict's options as typed (lists as comma-separated strings).
struct VerdictArgs {
  std::string errors = "1e-5,1e-6,1e-7,1e-8,1e-9";
  std::string slope_scenes = "experiment-short,n8,n32,n128";
  std::string slope_errors = "1e-5,1e-6,1e-8";
  std::string peer_engine = "peer";
  mb::VerdictOptions options(const std::string& command) const {
    mb::VerdictOptions o;
    o.errors = parseList(errors);
    o.slope_scenes = splitList(slope_scenes);
    o.slope_errors = parseList(slope_errors);
    o.sides.peer = peer_engine;
    o.command = command;
    return o;
  }
};

void addVerdictOptions(CLI::App* cmd, VerdictArgs& v) {
  cmd->add_option("--ratio-errors", v.errors,
                  "errors of the ratio table's columns (metrosync against the peer)")
      ->capture_default_str();
  cmd->add_option("--peer-engine", v.peer_engine,
                  "the engine the verdict compares metrosync's direct engine with: peer (the "
                  "careful peer, a separate program) or odeint (the bench's in-process peer)")
      ->capture_default_str();
  cmd->add_option("--slope-scenes", v.slope_scenes,
                  "the scenes that differ only in N: the N-slope's points")
      ->capture_default_str();
  cmd->add_option("--slope-errors", v.slope_errors, "errors at which the N-slope is fitted")
      ->capture_default_str();
}

// Every subcommand's options, as the command line sets them.
struct Args {
  Common common;
  PrecisionOptions po;
  VerdictArgs verdict;
  std::string peer_path, metrosync_path;
  std::vector<std::string> ratio_files;
  NScaleOptions no;
  mb::RunCostOptions ro;
  std::vector<std::string> variants;
  mb::MapOptions mo;
  SummaryOptions so;
  mb::ProcessOptions process;
  EventCostArgs event_cost;
  mb::FitCostOptions fit;
  mb::ContinueCostOptions cont;
};

CLI::App* addPrecisionCommand(CLI::App& app, Args& a) {
  PrecisionOptions& po = a.po;
  CLI::App* pc = app.add_subcommand("precision", "work-precision on rig files");
  pc->add_option("--scene", po.scenes, "rig file (repeatable)")->required();
  pc->add_option("--set", po.sets, "override a rig key of every scene (KEY=VALUE)");
  pc->add_option("--methods", po.methods,
                 "engine:integrator list, ENGINE:* for every integrator of ENGINE (default: "
                 "every integrator of every engine built in)");
  pc->add_option("--simbody-accuracies", po.simbody_accuracies,
                 "accuracies of the simbody engine (default: --accuracies); its runs cost "
                 "seconds each, the direct engine's milliseconds");
  pc->add_option("--accuracies", po.accuracies, "accuracies (simbody, direct, odeint, peer)")
      ->capture_default_str();
  pc->add_option("--siconos-steps", po.siconos_steps,
                 "Moreau-Jean steps per fast period (h = 2 pi / omega0 / this)")
      ->capture_default_str();
  pc->add_option("--reference", po.reference, "engine:integrator:accuracy of the reference")
      ->capture_default_str();
  pc->add_option("--cross-check", po.cross_checks,
                 "engine:integrator:accuracy checked against the reference (repeatable)");
  pc->add_option("--ref-budget", po.ref_budget_s, "seconds the reference runs may take")
      ->capture_default_str();
  addVerdictOptions(pc, a.verdict);
  addCommon(pc, a.common);
  pc->add_option("--metrosync", a.metrosync_path,
                 "the metrosync binary of the run methods (run:INTEGRATOR, `metrosync run` "
                 "itself); default: metrosync beside this program");
  pc->add_option("--run-scenes", po.run_scenes,
                 "the scenes (names, comma-separated) the run methods are timed on (default: "
                 "every scene)");
  pc->add_option("--peer", a.peer_path,
                 "the careful peer's binary (methods peer:dopri5, peer:rkf78); default: "
                 "$METROSYNC_PEER, else what shared/peer/build.sh beside the source tree (not part "
                 "of this repository) "
                 "builds");
  return pc;
}

CLI::App* addRatiosCommand(CLI::App& app, Args& a) {
  CLI::App* rc = app.add_subcommand(
      "ratios", "the verdict against the peer recomputed from precision's wp-*.csv files");
  rc->add_option("csv", a.ratio_files, "wp-<scene>.csv files (*-equal-error.csv are skipped)")
      ->required()
      ->check(CLI::ExistingFile);
  rc->add_option("--out", a.common.out,
                 "output directory of ratios.md, ratios.csv, nslope.csv, verdicts.md (default: "
                 "the first file's)");
  rc->add_flag("-q,--quiet", a.common.quiet, "no tables on stdout");
  addVerdictOptions(rc, a.verdict);
  return rc;
}

CLI::App* addNScaleCommand(CLI::App& app, Args& a) {
  NScaleOptions& no = a.no;
  CLI::App* nc = app.add_subcommand("nscale", "cost per fast period against N");
  nc->add_option("--n", no.ns, "numbers of metronomes")->capture_default_str();
  nc->add_option("--periods", no.periods, "fast periods per run")->capture_default_str();
  nc->add_option("--methods", no.methods, "engine:integrator:setting list")->capture_default_str();
  nc->add_option("--mu", no.mu_bar, "platform mu-bar")->capture_default_str();
  nc->add_option("--board", no.board_kg, "board mass, kg")->capture_default_str();
  nc->add_option("--seed", no.seed, "seed of the start phases")->capture_default_str();
  addCommon(nc, a.common);
  return nc;
}

CLI::App* addRunCostCommand(CLI::App& app, Args& a) {
  CLI::App* uc = app.add_subcommand(
      "runcost", "`metrosync run` against its engine: wall_seconds / engine_seconds, the process");
  uc->add_option("--metrosync", a.ro.metrosync, "the metrosync binary")->capture_default_str();
  uc->add_option("--scene", a.ro.scenes, "rig file (repeatable)")->required();
  uc->add_option("--variant", a.variants,
                 "space-separated KEY=VALUE overrides (--set) of one variant, and env:NAME=VALUE "
                 "for the run's environment, \"\" for none (repeatable; default: none, and "
                 "simulation.sample=100)");
  uc->add_option("--tmp", a.ro.tmp,
                 "where the runs write their files (default: the system's temporary directory)");
  addCommon(uc, a.common);
  return uc;
}

CLI::App* addMapsCommand(CLI::App& app, Args& a) {
  CLI::App* mc =
      app.add_subcommand("maps", "wall time of the full 64 x 64 and slow 100 x 100 maps");
  mc->add_option("--metrosync", a.mo.metrosync, "the metrosync binary")->capture_default_str();
  mc->add_option("--rig", a.mo.rig, "the map's rig")->capture_default_str();
  mc->add_option("--maps", a.mo.maps, "which maps: full, slow")->capture_default_str();
  mc->add_option("--jobs", a.mo.jobs, "the sweep's --jobs")->capture_default_str();
  mc->add_option("--tmp", a.mo.tmp, "where the sweeps write");
  addCommon(mc, a.common);
  return mc;
}

CLI::App* addProcessCommand(CLI::App& app, Args& a) {
  CLI::App* pc = app.add_subcommand(
      "process", "the whole `metrosync run` process against its wall_seconds, phase by phase");
  pc->add_option("--metrosync", a.process.metrosync, "the metrosync binary")->capture_default_str();
  pc->add_option("--scene", a.process.scene, "the rig file")->capture_default_str();
  addCommon(pc, a.common);
  return pc;
}

CLI::App* addEventCostCommand(CLI::App& app, Args& a) {
  CLI::App* ec = app.add_subcommand(
      "eventcost", "the direct engine's cost per step and per event against one RHS evaluation");
  ec->add_option("--scene", a.event_cost.scenes, "rig file (repeatable)")->required();
  ec->add_option("--accuracies", a.event_cost.accuracies, "accuracies")->capture_default_str();
  addCommon(ec, a.common);
  return ec;
}

CLI::App* addFitCostCommand(CLI::App& app, Args& a) {
  mb::FitCostOptions& f = a.fit;
  CLI::App* fc = app.add_subcommand(
      "fitcost", "one fit's wall and CPU time on the fit bench, against one run of the same rig");
  fc->add_option("--fit-bench", f.fit_bench, "the fit bench's binary")->capture_default_str();
  fc->add_option("--metrosync", f.metrosync, "the metrosync binary")->capture_default_str();
  fc->add_option("--records", f.records, "records fitted (the full bench: 50)")
      ->capture_default_str();
  fc->add_option("--duration", f.duration_s, "seconds per record")->capture_default_str();
  fc->add_option("--seed", f.seed, "the fit bench's seed")->capture_default_str();
  fc->add_option("--run-repeat", f.run_repeat, "timed runs of each record's rig")
      ->capture_default_str();
  addCommon(fc, a.common);
  return fc;
}

CLI::App* addContinueCommand(CLI::App& app, Args& a) {
  mb::ContinueCostOptions& o = a.cont;
  CLI::App* cc = app.add_subcommand("continue", "`metrosync continue ... --all`'s wall time");
  cc->add_option("--metrosync", o.metrosync, "the metrosync binary")->capture_default_str();
  cc->add_option("--rig", o.rigs, "rig file (repeatable)")->capture_default_str();
  cc->add_option("--timeout", o.timeout_s, "stop a run after this many seconds (0: never)")
      ->capture_default_str();
  addCommon(cc, a.common);
  return cc;
}

CLI::App* addSummaryCommand(CLI::App& app, Args& a) {
  CLI::App* sc = app.add_subcommand(
      "summary",
      "the speed summary of one run of tools/bench/speed.sh: DIR/README.md, the "
      "paragraph on stdout, and README.md's marked block rewritten with --readme");
  sc->add_option("--dir", a.so.dir, "the folder speed.sh wrote")->capture_default_str();
  sc->add_option("--readme", a.so.readme,
                 "a README.md whose text between the markers '<!-- speed:begin' and '<!-- "
                 "speed:end' is replaced by the paragraph");
  sc->add_option("--date", a.so.date, "the date of the measurement, for the text");
  sc->add_option("--commit", a.so.commit, "the commit measured, for the text");
  sc->add_flag("-q,--quiet", a.common.quiet, "no paragraph on stdout");
  return sc;
}

CLI::App* addPeerCommand(CLI::App& app, Args& a) {
  CLI::App* lc = app.add_subcommand(
      "peer",
      "where the careful peer is (its path on stdout, exit 0), or why it is missing "
      "(exit 1); builds it if its build script is found");
  lc->add_option("--peer", a.peer_path, "the peer's binary (as for precision)");
  return lc;
}

int peerCommand() {
  const mb::PeerLocation& loc = mb::peerLocation();
  if (loc.path.empty()) {
    std::cerr << "metrosync_bench: " << loc.missing << "\n";
    return 1;
  }
  std::cout << loc.path << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"metrosync_bench: work-precision and N-scaling of the full model's engines"};
  app.require_subcommand(1);
  Args a;
  CLI::App* pc = addPrecisionCommand(app, a);
  CLI::App* lc = addPeerCommand(app, a);
  CLI::App* rc = addRatiosCommand(app, a);
  addNScaleCommand(app, a);
  CLI::App* uc = addRunCostCommand(app, a);
  CLI::App* mc = addMapsCommand(app, a);
  CLI::App* sc = addSummaryCommand(app, a);
  CLI::App* process = addProcessCommand(app, a);
  CLI::App* event_cost = addEventCostCommand(app, a);
  CLI::App* fit = addFitCostCommand(app, a);
  CLI::App* cont = addContinueCommand(app, a);
  CLI11_PARSE(app, argc, argv);
  try {
    if (!a.peer_path.empty()) mb::setPeerPath(a.peer_path);
    if (!a.metrosync_path.empty()) mb::setMetrosyncPath(a.metrosync_path);
    if (lc->parsed()) return peerCommand();
    if (pc->parsed() || rc->parsed()) a.po.verdict = a.verdict.options(commandLine(argc, argv));
    if (pc->parsed()) return precision(a.po, a.common);
    if (uc->parsed()) {
      if (!a.variants.empty()) a.ro.variants = a.variants;
      a.ro.repeat = a.common.repeat;
      return runCost(a.ro, a.common, commandLine(argc, argv));
    }
    if (mc->parsed()) {
      a.mo.repeat = mc->count("--repeat") ? a.common.repeat : 1;  // a map takes a minute
      return maps(a.mo, a.common);
    }
    if (sc->parsed()) return summary(a.so, a.common);
    if (process->parsed()) {
      a.process.repeat = process->count("--repeat") ? a.common.repeat : 21;
      return processCost(a.process, a.common, commandLine(argc, argv));
    }
    if (event_cost->parsed()) return eventCost(a.event_cost, a.common, commandLine(argc, argv));
    if (fit->parsed()) return fitCost(a.fit, a.common);
    if (cont->parsed()) {
      a.cont.repeat = cont->count("--repeat") ? a.common.repeat : 1;  // a run takes a minute
      return continueCost(a.cont, a.common);
    }
    if (rc->parsed()) {
      if (rc->count("--out") == 0)
        a.common.out = std::filesystem::path(a.ratio_files.front()).parent_path().string();
      if (a.common.out.empty()) a.common.out = ".";
      return ratios(a.ratio_files, a.po.verdict, a.common);
    }
    return nscale(a.no, a.common);
  } catch (const std::exception& e) {
    std::cerr << "metrosync_bench: error: " << e.what() << "\n";
    return 2;
  }
}
