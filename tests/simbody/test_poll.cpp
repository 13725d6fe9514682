// A stop between two rows (RunSink::poll): the Simbody engine can take many steps between two
// rows (its grazing guard redoes a step smaller and smaller; hard/storm.yaml spent 2.3 s of wall
// time inside one fast period), and a stop request was seen only at rows. It now polls the sink
// after every step, and a throw from poll stops the run there, as one from a row does.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "sim/engines/engine.h"
#include "tests/simbody/rigs.h"

namespace metrosync {
namespace {

// Counts the rows and the polls; throws from the poll numbered `throw_at` (0: never).
struct PollingSink : RunSink {
  void trajectoryRow(const std::vector<double>& row) override {
    ++rows;
    last_row_t = row[0];
  }
  void envelopeRow(const EnvelopeRow&) override { ++rows; }
  void poll(double t) override {
    ++polls;
    last_poll_t = t;
    if (polls == throw_at)
      throw std::runtime_error("stop requested at poll " + std::to_string(polls));
  }
  long rows = 0, polls = 0, throw_at = 0;
  double last_row_t = -1.0, last_poll_t = -1.0;
};

Rig shortExperiment() {
  Rig rig = testrigs::experiment(0.2, 2.0);  // ~3 fast periods of stick-slip and ticks
  rig.sim.sample_s = 1.0;                    // rows far apart: steps between them
  return rig;
}

// Every step is polled (a step redone smaller polls again, at its earlier end), in the rows' unit
// (seconds for this physical rig).
TEST(SimbodyPoll, TheSinkIsPolledAfterEveryStep) {
  PollingSink sink;
  const RunReport r = findEngine("simbody")->run(shortExperiment(), sink);
  ASSERT_TRUE(r.complete) << r.failure;
  EXPECT_GE(sink.polls, r.counts.steps);  // every step the integrator took (and its redos)
  EXPECT_GT(sink.polls, 4 * sink.rows);   // many polls between two rows
  EXPECT_LE(sink.last_poll_t, 2.0);
  EXPECT_GT(sink.last_poll_t, 1.9);
}

// A throw from a poll between two rows stops the run at that step: incomplete, saying why, at a
// time before the run's end.
TEST(SimbodyPoll, AThrowFromAPollStopsTheRunThere) {
  PollingSink counted;
  ASSERT_TRUE(findEngine("simbody")->run(shortExperiment(), counted).complete);
  PollingSink sink;
  sink.throw_at = counted.polls / 2;
  const RunReport r = findEngine("simbody")->run(shortExperiment(), sink);
  EXPECT_FALSE(r.complete);
  EXPECT_NE(r.failure.find("stop requested at poll"), std::string::npos) << r.failure;
  EXPECT_LT(r.counts.steps, counted.polls);
  EXPECT_LT(sink.last_row_t, 2.0);  // its last row is where it stopped, not the end
}

}  // namespace
}  // namespace metrosync
