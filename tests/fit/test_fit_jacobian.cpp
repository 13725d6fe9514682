// The fit's exact Jacobian (issue 36; sim/analysis/fit/model_jacobian.h) against central
// differences of the model's samples, for every key a physical rig has, on runs with escapement
// ticks and stick-slip of the platform (and the other laws: static friction above kinetic,
// viscous; a spring; the rig's other spellings of damping and impulse).
//
// Tolerance: each key's column (2-norm over the samples) within kAgree = 1e-5 of the
// differences'; measured 1.4e-8 to 9e-7, the larger where a key moves the board more than the
// phases. The differences are taken at accuracy 1e-12 over kStep = 1e-6 of each key's scale (ten
// times its value for those board keys, whose effect on x (~1e-5 m) over 1e-6 of them the
// engine's error would swamp): truncation O(kStep^2 (omega t)^2) ~ 1e-8, the engine's error (which
// does not follow a key smoothly: its steps change) ~1e-6 of a column at worst. The exact side's
// own error is ~1e-8 (Y read between steps by cubic Hermite interpolation). Longer steps are
// worse, not better: over 1e-4 of a key that sets a frequency, a few samples fall between an
// event's two times and see the tick's kink in x (2e-3). A wrong term of a jump leaves a column
// off by O(1): the parameters' term of a tick's theta_c and of the static bound with its sign
// flipped gave 2.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sim/analysis/fit/fit_observations.h"
#include "sim/analysis/fit/model_jacobian.h"
#include "sim/analysis/fit/model_samples.h"
#include "sim/analysis/periodic_orbit/engine_trace.h"
#include "sim/engines/engine.h"
#include "tests/fit/fit_data.h"
#include "yaml/rig_loader.h"
#include "yaml/rig_writer.h"

namespace metrosync {
namespace {

constexpr double kStep = 1e-6;
constexpr double kAgree = 1e-5;
constexpr double kDuration = 4.0;  // s
constexpr double kRowDt = 0.0025;  // s, the fit's rows for a 100 Hz record

// The experiment's pair with the paper's keys (tests/fit/fit_data.h), mu-bar high enough that the
// board sticks and slips between ticks, 4 s at accuracy 1e-12.
const std::vector<std::string> kPairSets = {"platform.friction.mu=2e-3",
                                            "metronomes.1.start={angle: -0.6, rate: 1.5}",
                                            "simulation.duration=4", "simulation.accuracy=1e-12"};

// A free key, its value and its scale (the differences' unit; |value| when 0). A key that moves
// the board more than the phases takes ten times its value: over 1e-6 of it the board's x
// (~1e-5 m) moves by less than the engine's error lets a difference see.
struct Key {
  std::string name;
  double value = 0.0, scale = 0.0;
};

// A fit problem over `keys` of `rig` (with `sets`), each started at its given value, sampled at
// 100 Hz: the angles of both metronomes and x.
struct Case {
  std::string rig;
  std::vector<std::string> sets, keys;
  std::vector<FreeParameter> free;
  FitProblem problem;
  FitData data;
  std::vector<double> values;

  Case(const std::vector<std::string>& more_sets, const std::vector<Key>& keys_)
      : rig(fit_testing::kFiveKeyRig), sets(kPairSets) {
    sets.insert(sets.end(), more_sets.begin(), more_sets.end());
    for (const Key& k : keys_) {
      FreeParameter f;
      f.name = k.name;
      f.keys = {k.name};
      f.start = k.value;
      f.scale = k.scale > 0 ? k.scale : std::abs(k.value);
      free.push_back(f);
      keys.push_back(k.name);
      values.push_back(k.value);
    }
    problem.free = free;
    problem.engine = &selectEngine("direct", "full", "");
    problem.rig = [this](const std::vector<double>& v) {
      std::vector<std::string> s = sets;
      for (std::size_t j = 0; j < keys.size(); ++j)
        s.push_back(keys[j] + "=" + exactNumberText(v[j]));
      return loadRigText(rig, "rig.yaml", s);
    };
    data.quantity_names = {"theta_1", "theta_2", "x"};
    data.metronome = {0, 1, -1};
    for (int i = 0; i <= static_cast<int>(kDuration * 100 + 0.5); ++i)
      for (int q = 0; q < 3; ++q) data.observations.push_back({0.01 * i, q, q == 2, 0.0});
  }

  std::vector<double> samples(const std::vector<double>& v) const {
    const ModelTrajectory run(*problem.engine, problem.rig(v), kDuration, kRowDt);
    std::vector<double> out;
    for (const Observation& o : data.observations)
      out.push_back(run.at(o.t_s, data.metronome[o.quantity]));
    return out;
  }
};

// Central differences of the samples over kStep of each key's scale, against the exact columns.
void expectExactColumns(Case& c) {
  const ModelTrajectory run(*c.problem.engine, c.problem.rig(c.values), kDuration, kRowDt);
  const int n = static_cast<int>(c.data.observations.size());
  const orbit::Mat J =
      modelJacobian(c.problem, c.values, run, c.data, n, std::vector<bool>(c.keys.size(), true));
  for (std::size_t j = 0; j < c.keys.size(); ++j) {
    std::vector<double> hi = c.values, lo = c.values;
    const double h = kStep * c.free[j].scale;
    hi[j] += h;
    lo[j] -= h;
    const std::vector<double> a = c.samples(hi), b = c.samples(lo);
    orbit::Vec fd(n);
    for (int i = 0; i < n; ++i) fd(i) = (a[i] - b[i]) / (2 * h);
    const double rel = (J.col(j) - fd).norm() / fd.norm();
    EXPECT_LT(rel, kAgree) << c.keys[j] << ": |exact| " << J.col(j).norm() << ", |differences| "
                           << fd.norm();
    EXPECT_GT(fd.norm(), 0.0) << c.keys[j];
  }
}

// The run has what the test is about: ticks of both metronomes, the board sticking and slipping.
void expectTicksAndStickSlip(const Case& c) {
  const ModelTrajectory run(*c.problem.engine, c.problem.rig(c.values), kDuration, kRowDt);
  const orbit::PhysicalModel m(run.rig());
  const orbit::EngineTrace trace = orbit::traceOfRecords(m, run.events(), 0.0);
  int ticks[2] = {0, 0}, sticks = 0, slips = 0;
  for (const orbit::EngineWindow& w : trace.windows) {
    for (int j : w.ticked) ++ticks[j];
    sticks += w.mode_after == PlatformMode::Stuck && w.mode_before != PlatformMode::Stuck;
    slips += w.mode_before == PlatformMode::Stuck && w.mode_after != PlatformMode::Stuck;
  }
  EXPECT_GT(ticks[0], 10);
  EXPECT_GT(ticks[1], 10);
  EXPECT_GT(sticks, 10);
  EXPECT_GT(slips, 10);
}

TEST(FitJacobian, EveryKeyOfACoulombBoardWithTicksAndStickSlip) {
  Case c({"metronomes.*.pendulum.inertia=1.2e-5"}, {{"platform.friction.mu", 2e-3},
                                                    {"platform.mass", 0.1432},
                                                    {"gravity", 9.81},
                                                    {"metronomes.0.box_mass", 0.0602},
                                                    {"metronomes.0.pendulum.mass", 0.0226},
                                                    {"metronomes.0.pendulum.length", 0.0225},
                                                    {"metronomes.0.pendulum.inertia", 1.2e-5},
                                                    {"metronomes.0.pendulum.damping", 0.0226},
                                                    {"metronomes.1.pendulum.damping", 0.0226},
                                                    {"metronomes.1.escapement.angle", 0.244},
                                                    {"metronomes.0.escapement.impulse", 1.4844e-5},
                                                    {"metronomes.1.escapement.impulse", 1.4844e-5},
                                                    {"metronomes.0.start.angle", 0.785},
                                                    {"metronomes.1.start.rate", 1.5}});
  expectTicksAndStickSlip(c);
  expectExactColumns(c);
}

// Static friction above kinetic, a spring to ground, a start that moves, and the keys a rig may
// write as a decay rate and a steady amplitude.
TEST(FitJacobian, StaticFrictionASpringAndTheOtherSpellings) {
  Case c({"metronomes.0.pendulum={mass: 0.0226, length: 0.0225, decay_rate: 0.5}",
          "metronomes.1.escapement={angle: 0.244, steady_amplitude: 0.785}"},
         {{"platform.friction.mu", 2e-3},
          {"platform.friction.mu_static", 3e-3, 3e-2},
          {"platform.spring.k", 2.0, 20.0},
          {"start.x", 1e-4, 1e-2},
          {"start.v", -1e-3, 1e-1},
          {"metronomes.0.pendulum.decay_rate", 0.5},
          {"metronomes.1.escapement.steady_amplitude", 0.785}});
  expectTicksAndStickSlip(c);
  expectExactColumns(c);
}

TEST(FitJacobian, ViscousBoard) {
  Case c({"platform.friction={law: viscous, c: 0.05}"},
         {{"platform.friction.c", 0.05, 0.5},
          {"metronomes.0.pendulum.damping", 0.0226},
          {"metronomes.1.escapement.impulse", 1.4844e-5}});
  expectExactColumns(c);
}

}  // namespace
}  // namespace metrosync
