// The engine registry (sim/engines/engine.h) and `--engine` on every command: the defaults, the
// meaningless combinations (exit 2, nothing written), and that an engine run through the registry
// is the engine itself (the same numbers as its entry point, and the two full-model engines agree).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "models/scaling.h"
#include "sim/engines/direct/direct_engine.h"
#include "sim/engines/engine.h"
#include "sim/engines/simbody/simbody_engine.h"
#include "tests/common/run_metrosync.h"
#include "yaml/rig_loader.h"

namespace {

namespace fs = std::filesystem;
using metrosync::Engine;
using metrosync::EngineSelectionError;
using metrosync::findEngine;
using metrosync::selectEngine;
using metrosync::testing_support::runMetrosync;
using metrosync::testing_support::scratchDir;
using metrosync::testing_support::shellQuote;
using metrosync::testing_support::slurp;

// The two full-model engines integrate the same equations to simulation.accuracy 1e-10: their
// envelopes after a few periods agree far below this (tests/direct/test_agreement.cpp holds them
// to 1e-8 on every shipped rig), far above rounding.
constexpr double kEngineAgreement = 1e-6;

TEST(EngineRegistry, NamesModelsAndIntegrators) {
  ASSERT_EQ(metrosync::engines().size(), 3u);
  const Engine* direct = findEngine("direct");
  const Engine* simbody = findEngine("simbody");
  const Engine* slow = findEngine("slowflow");
  ASSERT_TRUE(direct && simbody && slow);
  EXPECT_EQ(findEngine("warp"), nullptr);
  EXPECT_EQ(direct->model(), "full");
  EXPECT_EQ(simbody->model(), "full");
  EXPECT_EQ(slow->model(), "slow");
  EXPECT_EQ(direct->integrators(), metrosync::directIntegratorNames());
  EXPECT_EQ(simbody->integrators(), metrosync::simbodyIntegratorNames());
  EXPECT_TRUE(slow->integrators().empty());
  // no integrator name belongs to two engines, or the rig's key could not choose the engine
  for (const auto& n : direct->integrators())
    for (const auto& m : simbody->integrators()) EXPECT_NE(n, m);
}

TEST(EngineRegistry, Defaults) {
  EXPECT_EQ(selectEngine("", "", "").name(), "direct");
  EXPECT_EQ(selectEngine("", "full", "").name(), "direct");
  EXPECT_EQ(selectEngine("", "slow", "").name(), "slowflow");
  EXPECT_EQ(selectEngine("slowflow", "", "").name(), "slowflow");
  // a Simbody integrator in the rig chooses Simbody; the direct engine's keep the default
  EXPECT_EQ(selectEngine("", "full", "rk-merson").name(), "simbody");
  EXPECT_EQ(selectEngine("", "full", "verner76").name(), "direct");
  // the slow flow has its own integrator: a full-model name in the rig is for compare's run
  EXPECT_EQ(selectEngine("", "slow", "rk-merson").name(), "slowflow");
}

// `expect_integrator`: the error is the rig's simulation.integrator (else the command line's).
void expectRejected(const std::string& engine, const std::string& model,
                    const std::string& integrator, bool expect_integrator) {
  try {
    selectEngine(engine, model, integrator);
    ADD_FAILURE() << engine << "/" << model << "/" << integrator << " accepted";
  } catch (const EngineSelectionError& e) {
    EXPECT_EQ(e.about_integrator, expect_integrator) << e.what();
  }
}

TEST(EngineRegistry, MeaninglessCombinationsAreRejected) {
  expectRejected("warp", "", "", false);
  expectRejected("simbody", "slow", "", false);
  expectRejected("direct", "slow", "", false);
  expectRejected("slowflow", "full", "", false);
  expectRejected("", "medium", "", false);
  expectRejected("direct", "full", "rk-merson", true);
  expectRejected("simbody", "full", "verner76", true);
  expectRejected("", "full", "no-such-integrator", true);
  expectRejected("", "slow", "no-such-integrator", true);
}

metrosync::Rig shortRig(const std::string& integrator) {
  metrosync::Rig rig = metrosync::defaultRig({"simulation.duration=1", "simulation.accuracy=1e-10",
                                              "simulation.integrator=" + integrator});
  return rig;
}

struct LastRow : metrosync::RunSink {
  void envelopeRow(const metrosync::EnvelopeRow& row) override { last = row; }
  metrosync::EnvelopeRow last;
};

TEST(EngineRegistry, RunIsTheEngineItself) {
  const metrosync::Rig rig = shortRig("verner76");
  LastRow via_registry, direct_call;
  const auto a = findEngine("direct")->run(rig, via_registry);
  const auto b = metrosync::runDirectModel(rig, direct_call);
  ASSERT_TRUE(a.complete && b.complete);
  EXPECT_EQ(a.engine, "direct");
  EXPECT_EQ(a.counts.steps, b.counts.steps);
  ASSERT_FALSE(via_registry.last.A.empty());
  EXPECT_EQ(via_registry.last.A, direct_call.last.A);  // bit for bit: a thin wrapper

  // and the other full-model engine, chosen by name, integrates the same model
  LastRow simbody_sink;
  const auto s = findEngine("simbody")->run(shortRig("rk-merson"), simbody_sink);
  ASSERT_TRUE(s.complete) << s.failure;
  EXPECT_EQ(s.engine, "simbody");
  ASSERT_EQ(simbody_sink.last.A.size(), via_registry.last.A.size());
  for (size_t i = 0; i < simbody_sink.last.A.size(); ++i)
    EXPECT_NEAR(simbody_sink.last.A[i], via_registry.last.A[i], kEngineAgreement) << i;
}

// ---- the command line --------------------------------------------------------------------------

TEST(CliEngines, MeaninglessCombinationsExit2AndWriteNothing) {
  const std::string cwd = scratchDir("engines", "combos", true);
  const std::string out = " --out " + shellQuote(cwd + "/out");
  const char* vary = " --vary platform.friction.mu=0:0.4:2 --set simulation.duration=1";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"run --model slow --engine simbody", "simbody"},
      {"run --model slow --engine direct", "direct"},
      {"run --engine slowflow --model full", "slowflow"},
      {"run --engine warp", "warp"},
      {"run --engine direct --set simulation.integrator=rk-merson", "rk-merson"},
      {"run --engine simbody --set simulation.integrator=verner76", "verner76"},
      {"compare --engine slowflow", "slowflow"},
      {std::string("sweep --model slow --engine direct") + vary, "direct"},
      {std::string("sweep --model full --engine slowflow") + vary, "slowflow"},
      {"validate --engine slowflow", "slowflow"},
      {"validate --engine warp", "warp"},
  };
  for (const auto& [args, named] : cases) {
    const auto r = runMetrosync(args + out, {cwd, ""});
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("metrosync: error: ", 0), 0u) << args << ": " << r.err;
    EXPECT_NE(r.err.find(named), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(cwd + "/out")) << args;
  }
  EXPECT_FALSE(fs::exists(cwd + "/runs"));
}

// `--engine slowflow` is `--model slow`: the same engine, so the same bytes.
TEST(CliEngines, EngineSlowflowIsModelSlow) {
  const std::string d = scratchDir("engines", "slowflow", true);
  const std::string common = " -q --set simulation.duration=20 --out ";
  ASSERT_EQ(runMetrosync("run --engine slowflow" + common + shellQuote(d + "/a")).code, 0);
  ASSERT_EQ(runMetrosync("run --model slow" + common + shellQuote(d + "/b")).code, 0);
  const std::string a = slurp(d + "/a/envelope.csv");
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, slurp(d + "/b/envelope.csv"));
  EXPECT_NE(slurp(d + "/a/summary.json").find("\"slowflow\""), std::string::npos);
}

TEST(CliEngines, EveryCommandTakesEngine) {
  for (const char* cmd : {"run", "compare", "sweep", "validate"}) {
    const auto r = runMetrosync(std::string(cmd) + " --help");
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_NE(r.out.find("--engine"), std::string::npos) << cmd;
  }
}

}  // namespace
