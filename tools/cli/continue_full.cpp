#include "tools/cli/continue_full.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>

#include "base/number_text.h"
#include "sim/analysis/periodic_orbit/full_continuation.h"
#include "tools/cli/commands.h"
#include "tools/cli/option_keys.h"
#include "tools/report/full_continuation_report.h"
#include "yaml/rig_loader.h"

namespace metrosync::cli {

namespace {

// The options of the slow flow's continuation that mean nothing for the full model.
void checkOptions(const ContinueOptions& opt) {
  auto refuse = [](const std::string& option, const std::string& why) {
    throw UsageError(option + ": not with --model full (" + why + ")");
  };
  if (!opt.start.empty()) refuse("--start", "the start is the rig's own run, settled");
  if (opt.all) refuse("--all", "the full model follows the orbit the rig's start settles to");
  if (!opt.fold_key.empty()) refuse("--fold", "two-parameter curves are the slow flow's");
  if (opt.no_cycles) refuse("--no-cycles", "the full model's locked states are its cycles");
  if (opt.step < 0) throw UsageError("--step " + roundTripText(opt.step) + ": must be > 0");
  if (opt.max_points < 2) throw UsageError("--max-points: must be >= 2");
}

// The rig with KEY = p, the key as --set applies it (a '*' sets every element: docs/keys.md).
Rig rigAt(const ContinueOptions& opt, double p) {
  return loadContinueRig(opt, {opt.param + "=" + roundTripText(p)});
}

// Whether two rigs have the same equations (starts and run settings aside).
bool sameDynamics(const Rig& a, const Rig& b) {
  const PlatformSpec &pa = a.platform, &pb = b.platform;
  if (a.gravity_m_s2 != b.gravity_m_s2 || pa.mass_kg != pb.mass_kg || pa.friction != pb.friction ||
      pa.spring_N_m != pb.spring_N_m || a.metronomes.size() != b.metronomes.size())
    return false;
  for (size_t i = 0; i < a.metronomes.size(); ++i) {
    const MetronomeSpec &x = a.metronomes[i], &y = b.metronomes[i];
    if (x.box_mass_kg != y.box_mass_kg || x.pendulum_mass_kg != y.pendulum_mass_kg ||
        x.length_m != y.length_m || x.inertia_kgm2 != y.inertia_kgm2 ||
        x.damping_kg_s != y.damping_kg_s || x.theta_c_rad != y.theta_c_rad ||
        x.impulse_Nms != y.impulse_Nms || x.locked != y.locked)
      return false;
  }
  return true;
}

// (the full model's: epsilon is a key it depends on; continue.cpp's startValue refuses it)
double fullStartValue(const ContinueOptions& opt) {
  const std::string display = opt.rig_path.empty() ? "<default rig>" : opt.rig_path;
  // the rig itself must load, and take the derivatives
  requireDerivatives(loadContinueRig(opt, {}), display, "continue --model full");
  const std::string text = opt.rig_path.empty() ? defaultRigYaml() : readRigFile(opt.rig_path);
  // the one key resolver (docs/keys.md); a key with '*': the rig's value at its first element
  const RigKey key = resolveOptionKey({text, display, opt.sets}, "--param", opt.param, false).key;
  const std::optional<double> in_rig = rigNumber(text, display, opt.sets, key.paths[0].text());
  if (!opt.from && !in_rig) {
    rigAt(opt, opt.to);  // an unknown key, or a value the rig refuses, says so here
    throw UsageError(display + ": --param " + opt.param +
                     ": the key is not set in the rig (its default applies); give --from VALUE");
  }
  const double from = opt.from ? *opt.from : *in_rig;
  if (!std::isfinite(opt.to) || !std::isfinite(from) || opt.to == from)
    throw UsageError("--to " + roundTripText(opt.to) + ": must differ from the start value " +
                     opt.param + " = " + roundTripText(from));
  if (sameDynamics(rigAt(opt, from), rigAt(opt, opt.to)))
    throw UsageError("--param " + opt.param + ": has no effect on the full model's equations " +
                     "(the rig's parameters are the same at " + roundTripText(from) + " and " +
                     roundTripText(opt.to) + ")");
  return from;
}

void printSummary(const orbit::FullContinuation& r, const std::string& dir) {
  size_t points = 0;
  for (const orbit::Family& f : r.families) points += f.points.size();
  std::cout << "continue (full model) " << r.param << " from " << r.from << " to " << r.to << ": "
            << r.families.size() << " branch(es), " << points << " periodic orbits (section "
            << r.section_name << "), " << r.wall_seconds << " s\n";
  for (size_t b = 0; b < r.families.size(); ++b) {
    for (const auto& s : r.families[b].special)
      std::cout << "  " << s.type << " at " << r.param << " = " << numberText(s.point.p, 10)
                << " (branch " << b << "): " << s.detail << "\n";
    std::cout << "  branch " << b << " ends: " << r.families[b].end_backward << "; "
              << r.families[b].end_forward << "\n";
  }
  std::cout << "files in " << dir << "\n";
}

}  // namespace

int continueFullCommand(const ContinueOptions& opt) {
  checkOptions(opt);
  const double from = fullStartValue(opt);
  const Rig rig = rigAt(opt, from);
  orbit::FamilySettings s;
  s.p_min = std::min(from, opt.to);
  s.p_max = std::max(from, opt.to);
  s.step = opt.step;
  s.max_points = opt.max_points;
  orbit::FullContinuation result;
  try {
    result =
        orbit::continueFull([&](double p) { return rigAt(opt, p); }, opt.param, from, opt.to, s);
  } catch (const orbit::NoOrbit& e) {
    throw UsageError(std::string(opt.rig_path.empty() ? "<default rig>" : opt.rig_path) + ": " +
                     e.what());
  }
  const OutputDir dir(opt.out.empty() ? "runs/" + rig.name + "-continue" : opt.out);
  writeFullContinuation(dir, result, rig.name);
  if (!opt.quiet) printSummary(result, dir.path());
  return kSuccess;
}

}  // namespace metrosync::cli
