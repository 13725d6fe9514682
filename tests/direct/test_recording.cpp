// What the engines record never changes what they integrate, and the run's time is split into the
// engine's and the recording's part (RunReport::engine_seconds, summary.json engine_seconds).
// A sink that takes no trajectory and no envelope (the benchmark's, timing the integrator alone)
// gets the same steps, evaluations, events and final state, to the last bit, as one that takes
// every row: samples come from the interpolant and never stop or steer the integrator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/constants.h"
#include "models/scaling.h"
#include "sim/engines/direct/direct_engine.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

// Counts what it receives and declares which rows it takes.
struct CountingSink : RunSink {
  CountingSink(bool rows, bool envelope) : rows_(rows), envelope_(envelope) {}
  bool wantsTrajectory() const override { return rows_; }
  bool wantsEnvelope() const override { return envelope_; }
  void trajectoryRow(const std::vector<double>&) override { ++rows; }
  void envelopeRow(const EnvelopeRow&) override { ++envelope; }
  long rows = 0, envelope = 0;

 private:
  bool rows_, envelope_;
};

Rig rigFrom(const std::string& yaml) {
  return loadRigText(yaml, "test.yaml");
}

// two detuned metronomes on a sliding board, and eight (the fixed-size paths N = 2 and N = 8)
const char* kPair = R"(units: scaled
epsilon: 0.073
platform: {friction: {law: coulomb, mu: 0.23}}
metronomes:
  - {nu: 0.65, J: 3.14, theta_c: 0.9, start: {A: 2.9, phi: 0.3}}
  - {nu: 0.65, J: 3.14, theta_c: 0.9, alpha: 0.1, start: {A: 2.5, phi: 0.0}}
simulation: {tau: 5}
)";

// n detuned metronomes for tau (at epsilon 0.05: tau / 0.05 / 2 pi fast periods)
std::string many(int n, double tau) {
  std::string s =
      "units: scaled\nepsilon: 0.05\nplatform: {friction: {law: coulomb, mu: 0.6}}\n"
      "metronomes:\n";
  for (int i = 0; i < n; ++i)
    s += "  - {nu: 0.65, J: 3.14, theta_c: 0.9, alpha: " + std::to_string(0.05 * i) +
         ", start: {A: 2.6, phi: " + std::to_string(0.8 * i) + "}}\n";
  return s + "simulation: {tau: " + std::to_string(tau) + "}\n";
}

std::string eight() {
  return many(8, 3);
}

void expectSameIntegration(const Rig& rig) {
  CountingSink all(true, true), none(false, false), rows_only(true, false);
  const RunReport a = runDirectModel(rig, all);
  const RunReport b = runDirectModel(rig, none);
  const RunReport c = runDirectModel(rig, rows_only);
  ASSERT_TRUE(a.complete && b.complete && c.complete);
  EXPECT_GT(all.rows, 10);
  EXPECT_GT(all.envelope, 2);
  EXPECT_EQ(none.rows, 0);
  EXPECT_EQ(none.envelope, 0);
  EXPECT_EQ(rows_only.envelope, 0);
  EXPECT_EQ(rows_only.rows, all.rows);
  for (const RunReport* r : {&b, &c}) {
    EXPECT_EQ(r->counts.steps, a.counts.steps);
    EXPECT_EQ(r->counts.events, a.counts.events);
    EXPECT_EQ(r->counts.escapements, a.counts.escapements);
    EXPECT_EQ(r->final_trajectory_row, a.final_trajectory_row);  // bit for bit
  }
  // the samples are taken on the recorder's own copy of each step: its interpolant's extra
  // stages are not the engine's evaluations
  EXPECT_EQ(b.counts.rhs_evals, a.counts.rhs_evals);
  EXPECT_EQ(c.counts.rhs_evals, a.counts.rhs_evals);
  for (const RunReport* r : {&a, &b, &c}) {
    EXPECT_GT(r->engine_seconds, 0.0);
    EXPECT_LE(r->engine_seconds, r->wall_seconds);
  }
}

TEST(Recording, NeverChangesWhatTheEngineIntegratesTwoMetronomes) {
  expectSameIntegration(rigFrom(kPair));
}

TEST(Recording, NeverChangesWhatTheEngineIntegratesEightMetronomes) {
  expectSameIntegration(rigFrom(eight()));
}

// A MemorySink that lets the run make its rows on a recording thread of its own.
struct ThreadedSink : MemorySink {
  RecordingThread recordingThread() const override { return RecordingThread::Always; }
};

void expectSameRows(const MemorySink& a, const MemorySink& b) {
  EXPECT_EQ(a.trajectory, b.trajectory);
  ASSERT_EQ(a.envelope.size(), b.envelope.size());
  for (size_t k = 0; k < a.envelope.size(); ++k) {
    EXPECT_EQ(a.envelope[k].tau, b.envelope[k].tau);
    EXPECT_EQ(a.envelope[k].A, b.envelope[k].A);
    EXPECT_EQ(a.envelope[k].psi, b.envelope[k].psi);
  }
  ASSERT_EQ(a.events.size(), b.events.size());
  for (size_t k = 0; k < a.events.size(); ++k) {
    EXPECT_EQ(a.events[k].first, b.events[k].first);
    EXPECT_EQ(a.events[k].second, b.events[k].second);
  }
  ASSERT_EQ(a.records.size(), b.records.size());
  for (size_t k = 0; k < a.records.size(); ++k) {
    EXPECT_EQ(a.records[k].kind, b.records[k].kind);
    EXPECT_EQ(a.records[k].metronome, b.records[k].metronome);
    EXPECT_EQ(a.records[k].before, b.records[k].before);
    EXPECT_EQ(a.records[k].after, b.records[k].after);
  }
}

// The recording thread makes the rows the run's thread would, to the bit, in the same order;
// the report (counts, final rows) is the same.
TEST(Recording, OnItsOwnThreadMakesTheSameRowsToTheBit) {
  for (const std::string& yaml : {std::string(kPair), eight()}) {
    MemorySink here;
    ThreadedSink there;
    const RunReport a = runDirectModel(rigFrom(yaml), here);
    const RunReport b = runDirectModel(rigFrom(yaml), there);
    ASSERT_TRUE(a.complete && b.complete);
    EXPECT_GT(here.trajectory.size(), 100u);
    EXPECT_GT(here.records.size(), 10u);
    expectSameRows(here, there);
    EXPECT_EQ(a.final_trajectory_row, b.final_trajectory_row);
    EXPECT_EQ(a.final_row.A, b.final_row.A);
    EXPECT_EQ(a.final_row.psi, b.final_row.psi);
    EXPECT_EQ(a.counts.steps, b.counts.steps);
    EXPECT_EQ(a.counts.rhs_evals, b.counts.rhs_evals);
  }
}

// Offered WhenLong, the engine takes a recording thread by the run's length in metronome-periods
// (500 and more, for at most 8 metronomes: sim/engines/direct/rig_recording.h) and says so before
// the first row; offered Always, always; offered Never, never.
struct JudgedSink : MemorySink {
  explicit JudgedSink(RecordingThread offer) : offer_(offer) {}
  RecordingThread recordingThread() const override { return offer_; }
  void recordingThreadStarted() override {
    EXPECT_TRUE(trajectory.empty());
    ++threaded;
  }
  int threaded = 0;

 private:
  RecordingThread offer_;
};

TEST(Recording, TheEngineTakesARecordingThreadByTheRunsLength) {
  using Offer = RunSink::RecordingThread;
  struct Case {
    std::string yaml;
    Offer offer;
    int threaded;
  };
  const Case cases[] = {
      {many(2, 3), Offer::WhenLong, 0},                                     // 2 x 9.5 periods
      {many(2, 90), Offer::WhenLong, 1},                                    // 2 x 286
      {many(2, 90), Offer::Never, 0},    {many(8, 3), Offer::WhenLong, 0},  // 8 x 9.5
      {many(8, 25), Offer::WhenLong, 1},                                    // 8 x 80
      {many(9, 25), Offer::WhenLong, 0},  // 9 x 80: long, too many for a thread
      {many(2, 3), Offer::Always, 1},
  };
  for (const Case& c : cases) {
    JudgedSink sink(c.offer);
    const RunReport r = runDirectModel(rigFrom(c.yaml), sink);
    ASSERT_TRUE(r.complete) << c.yaml;
    EXPECT_EQ(sink.threaded, c.threaded) << c.yaml;
    EXPECT_GT(sink.trajectory.size(), 100u);
  }
}

// What a sink throws while the rows are made on the recording thread (a full disk, a stop
// request) fails the run with its message, as on the run's thread; the files keep what came
// before.
struct FailingSink : MemorySink {
  explicit FailingSink(bool threaded) : threaded_(threaded) {}
  RecordingThread recordingThread() const override {
    return threaded_ ? RecordingThread::Always : RecordingThread::Never;
  }
  void trajectoryRow(const std::vector<double>& row) override {
    if (trajectory.size() == 100) throw std::runtime_error("no space left on device");
    MemorySink::trajectoryRow(row);
  }

 private:
  bool threaded_;
};

TEST(Recording, ASinksFailureOnTheRecordingThreadFailsTheRun) {
  for (bool threaded : {false, true}) {
    FailingSink sink(threaded);
    const RunReport r = runDirectModel(rigFrom(kPair), sink);
    EXPECT_FALSE(r.complete) << threaded;
    EXPECT_NE(r.failure.find("no space left on device"), std::string::npos) << r.failure;
    EXPECT_EQ(sink.trajectory.size(), 100u);
    EXPECT_FALSE(r.final_trajectory_row.empty());
  }
}

// ---- the envelope against a converged average of the same trajectory -----------------------

// The averages of A_i and exp(i phi_i) over [a, b] from samples (t, theta_i, thetadot_i, scaled)
// of a smooth stretch: the trapezoid rule.
struct Averages {
  std::vector<double> A, re, im;
  double span = 0.0;
};

void addTrapezoid(const std::vector<double>& r0, const std::vector<double>& r1, int n,
                  Averages& s) {
  auto unit = [](double t, double th, double w, double& re, double& im) {
    const double a = std::sqrt(th * th + w * w);
    re = (w * std::cos(t) + th * std::sin(t)) / a;  // (w + i th) / a * exp(-i t)
    im = (th * std::cos(t) - w * std::sin(t)) / a;
  };
  const double h = r1[0] - r0[0];
  for (int i = 0; i < n; ++i) {
    const double th0 = r0[3 + 2 * i], w0 = r0[4 + 2 * i], th1 = r1[3 + 2 * i], w1 = r1[4 + 2 * i];
    double re0, im0, re1, im1;
    unit(r0[0], th0, w0, re0, im0);
    unit(r1[0], th1, w1, re1, im1);
    s.A[i] += 0.5 * h * (std::hypot(th0, w0) + std::hypot(th1, w1));
    s.re[i] += 0.5 * h * (re0 + re1);
    s.im[i] += 0.5 * h * (im0 + im1);
  }
  s.span += h;
}

// Period averages from a dense trajectory (rows every `sample`) split at every event (the rows
// before and after it from the event records): the trapezoid rule on each smooth stretch.
std::vector<Averages> periodAverages(const MemorySink& m, int n, int periods) {
  std::vector<std::vector<double>> pts = m.trajectory;
  for (const EventRecord& e : m.records) {
    pts.push_back(e.before);
    pts.push_back(e.after);
  }
  // in time order, a jump's before ahead of its after (stable: records come in order)
  std::stable_sort(pts.begin(), pts.end(),
                   [](const auto& a, const auto& b) { return a[0] < b[0]; });
  std::vector<Averages> out(periods, Averages{std::vector<double>(n), std::vector<double>(n),
                                              std::vector<double>(n), 0.0});
  for (size_t k = 1; k < pts.size(); ++k) {
    const double t0 = pts[k - 1][0], t1 = pts[k][0];
    const int p = static_cast<int>(std::floor(0.5 * (t0 + t1) / kTwoPi));
    if (t1 > t0 && p < periods) addTrapezoid(pts[k - 1], pts[k], n, out[p]);
  }
  return out;
}

// The envelope's rows are the exact averages of the trajectory: against the trapezoid rule on
// rows 4096 and 8192 per period, extrapolated (Richardson: the trapezoid's error goes as h^2),
// they agree to 1e-10 (8.3e-12 measured), where the former trapezoid on 64 samples per period
// was 2.1e-5 off.
TEST(Recording, EnvelopeRowsAreTheConvergedAveragesOfTheTrajectory) {
  const int n = 2, periods = 6;
  // scaled times and intervals as the rig's seconds (t = t_scaled * time_scale_s)
  auto run = [&](double sample, MemorySink& m) {
    Rig rig = rigFrom(kPair);
    const double seconds = computeScaled(rig).time_scale_s;
    rig.sim.accuracy = 1e-12;
    rig.sim.t_end_s = kTwoPi * (periods + 0.5) * seconds;
    if (sample > 0) rig.sim.sample_s = sample * seconds;
    return runDirectModel(rig, m);
  };
  MemorySink env, coarse, fine, p64;
  ASSERT_TRUE(run(0.0, env).complete);
  ASSERT_TRUE(run(kTwoPi / 4096, coarse).complete);
  ASSERT_TRUE(run(kTwoPi / 8192, fine).complete);
  ASSERT_TRUE(run(kTwoPi / 64, p64).complete);
  ASSERT_GE(env.records.size(), 10u);  // ticks and slips: jumps inside the periods
  const auto c = periodAverages(coarse, n, periods), f = periodAverages(fine, n, periods),
             t64 = periodAverages(p64, n, periods);
  double worst = 0.0, worst64 = 0.0;
  for (int k = 0; k < periods; ++k) {
    const EnvelopeRow& row = env.envelope[k + 1];
    for (int i = 0; i < n; ++i) {
      const double ref = (4 * f[k].A[i] - c[k].A[i]) / 3 / f[k].span;
      worst = std::max(worst, std::abs(row.A[i] - ref));
      worst64 = std::max(worst64, std::abs(t64[k].A[i] / t64[k].span - ref));
    }
    auto phase = [&](int i) {  // the converged average's direction
      return std::atan2(4 * f[k].im[i] - c[k].im[i], 4 * f[k].re[i] - c[k].re[i]);
    };
    const double phi = phase(0) - phase(1);
    worst = std::max(worst, std::abs(std::remainder(row.psi[0] - phi, kTwoPi)));
  }
  std::printf("envelope against the converged average: %.2g (trapezoid on 64 samples: %.2g)\n",
              worst, worst64);
  EXPECT_LT(worst, 1e-10) << "the new envelope against the converged average (8.3e-12 measured)";
  EXPECT_GT(worst64, 1e-7) << "the trapezoid on 64 samples per period: the test can tell";
}

}  // namespace
}  // namespace metrosync
