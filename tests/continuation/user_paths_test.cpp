// `metrosync continue` where users start (issue 25): the experiment's rig through A = theta_c,
// the frictionless platform (mu = 0), the paper's f4.2 on its neutral family, --all without
// duplicates, a physical rig that reaches --to, sweep --boundaries keeping its map. Each checked
// against what does not come from the continuation: the slow flow's equations at the reported
// states (models/slow_flow.h), closed forms (the steady amplitude A_star, the stuck platform's
// |Z| <= mu), and the command's own contract (exit codes, files).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "base/constants.h"
#include "models/scaling.h"
#include "models/slow_flow.h"
#include "tests/common/run_metrosync.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

using testing_support::runMetrosync;
using testing_support::scratchDir;
using testing_support::shellQuote;
using testing_support::slurp;

std::string rig(const std::string& name) {
  return std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/" + name;
}

// A CSV as rows of named cells.
std::vector<std::map<std::string, std::string>> csv(const std::string& path) {
  std::istringstream in(slurp(path));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string c; std::getline(header, c, ',');) names.push_back(c);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::map<std::string, std::string> row;
    for (size_t k = 0; k < names.size(); ++k) std::getline(ss, row[names[k]], ',');
    rows.push_back(row);
  }
  return rows;
}

double num(const std::map<std::string, std::string>& row, const std::string& key) {
  return std::stod(row.at(key));
}

nlohmann::json summaryOf(const std::string& out) {
  return nlohmann::json::parse(slurp(out + "/summary.json"));
}

// The scaled parameters of a rig with one override.
ScaledParams paramsAt(const std::string& path, const std::string& key, double v) {
  char kv[128];
  std::snprintf(kv, sizeof kv, "%s=%.17g", key.c_str(), v);
  return computeScaled(loadRigFile(path, {kv}));
}

// The experiment's rig in the detuning: the branch turns at a fold, comes back to A_1 = theta_c
// and goes on along it (border states) to alpha = 3. Each border state is a locked state of the
// slow flow with metronome 1's escapement weighted: its amplitude rates vanish with either
// formula (they agree on the border), and its phase rates balance at the reported weight.
TEST(ContinueUserPaths, ExperimentRigThroughThetaC) {
  const std::string out = scratchDir("continue", "through-theta-c");
  const std::string path = rig("experiment-map.yaml");
  const auto r =
      runMetrosync("continue " + shellQuote(path) +
                   " --param metronomes.1.alpha --to 3 --no-cycles -q --out " + shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto branch = summaryOf(out)["branches"][0];
  EXPECT_NE(branch["end_forward"].get<std::string>().find("at p = 3"), std::string::npos) << branch;
  int border_states = 0;
  for (const auto& q : csv(out + "/branches.csv")) {
    if (q.at("weight").empty()) continue;
    ++border_states;
    const double alpha = num(q, "metronomes.1.alpha"), w = num(q, "weight");
    const ScaledParams sp = paramsAt(path, "metronomes.1.alpha", alpha);
    EXPECT_NEAR(num(q, "A_1"), sp.theta_c[0], 1e-9);
    EXPECT_GE(w, 0.0);
    EXPECT_LE(w, 1.0);
    const std::vector<double> phi = {0.0, -num(q, "psi_2")};
    // the engaged formula just above theta_c, the disengaged one on it
    const auto on = slowFlowPolarRates(sp, {sp.theta_c[0] * (1 + 1e-14), num(q, "A_2")}, phi);
    const auto off = slowFlowPolarRates(sp, {sp.theta_c[0], num(q, "A_2")}, phi);
    for (int i = 0; i < 2; ++i) {
      EXPECT_NEAR(on.dA[i], 0.0, 1e-6) << "alpha = " << alpha;
      EXPECT_NEAR(off.dA[i], 0.0, 1e-6) << "alpha = " << alpha;
    }
    const double dpsi_on = on.dphi[0] - on.dphi[1], dpsi_off = off.dphi[0] - off.dphi[1];
    EXPECT_NEAR(w * dpsi_on + (1 - w) * dpsi_off, 0.0, 1e-8) << "alpha = " << alpha;
  }
  EXPECT_GT(border_states, 5);
}

// mu = 0 (f4.1, the frictionless platform) is a start like any other, and a continuation in mu
// reaches it (f4.3 from 0.2 down): there the platform's response is beta = (1/2, 0), which leaves
// the in-phase pair's amplitude equation that of one metronome alone: A = A_star.
TEST(ContinueUserPaths, FromAndToMuZero) {
  const struct {
    std::string rig, to;
  } cases[] = {{"paper/f4.1.yaml", "0.8"}, {"paper/f4.3-mu0.2.yaml", "0"}};
  for (const auto& c : cases) {
    const std::string out = scratchDir("continue", "mu-zero");
    const auto r =
        runMetrosync("continue " + shellQuote(rig(c.rig)) + " --param platform.friction.mu --to " +
                     c.to + " --no-cycles -q --out " + shellQuote(out));
    ASSERT_EQ(r.code, 0) << c.rig << "\n" << r.err;
    const ScaledParams sp = paramsAt(rig(c.rig), "platform.friction.mu", 0.0);
    const double a_star = *steadyAmplitude(sp.nu[0], sp.J[0], sp.theta_c[0]);
    int at_zero = 0;
    for (const auto& q : csv(out + "/branches.csv")) {
      const double mu = num(q, "platform.friction.mu");
      EXPECT_GE(mu, 0.0) << c.rig;
      if (mu != 0.0) continue;
      ++at_zero;
      EXPECT_NEAR(num(q, "psi_2"), 0.0, 1e-9) << c.rig;  // in phase
      EXPECT_NEAR(num(q, "A_1"), a_star, 1e-9) << c.rig;
      EXPECT_NEAR(num(q, "A_2"), a_star, 1e-9) << c.rig;
    }
    EXPECT_EQ(at_zero, 1) << c.rig;
  }
}

// f4.2 settles where the platform sticks: the metronomes are uncoupled, every phase difference
// with |Z| <= mu is a locked state (a neutral family), each metronome at its own A_star. Its
// extent at each mu is the closed form 2 A_star |cos(psi / 2)| <= mu.
TEST(ContinueUserPaths, F42NeutralFamilyWithItsExtent) {
  const std::string out = scratchDir("continue", "f42-family");
  const std::string path = rig("paper/f4.2.yaml");
  const auto r = runMetrosync("continue " + shellQuote(path) +
                              " --param platform.friction.mu --to 0.8 -q --out " + shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto families = summaryOf(out)["families"];
  ASSERT_EQ(families.size(), 1u) << families;
  EXPECT_NE(families[0]["cause"].get<std::string>().find("stuck"), std::string::npos);
  const ScaledParams sp = paramsAt(path, "platform.friction.mu", 0.5);
  const double a = *steadyAmplitude(sp.nu[0], sp.J[0], sp.theta_c[0]);
  const auto rows = csv(out + "/families.csv");
  ASSERT_GT(rows.size(), 5u);
  double mu_max = 0;
  for (const auto& q : rows) {
    const double mu = num(q, "platform.friction.mu");
    mu_max = std::max(mu_max, mu);
    for (const char* key : {"A_1_min", "A_1_max", "A_2_min", "A_2_max"})
      EXPECT_NEAR(num(q, key), a, 1e-9) << key << " at mu = " << mu;
    const double edge = 2 * std::acos(mu / (2 * a));  // |Z| = mu
    EXPECT_NEAR(num(q, "psi_2_min"), edge, 1e-7) << "mu = " << mu;
    EXPECT_NEAR(num(q, "psi_2_max"), kTwoPi - edge, 1e-7) << "mu = " << mu;
  }
  EXPECT_EQ(mu_max, 0.8);
}

// --all follows each branch once and lists each bifurcation once: the paper's identical pair
// reaches its S-shaped in-phase branch from both of its states at mu = 0.2 and its branch points
// from both sides; every parameter value lies in the range (no -1e-300 at an end).
TEST(ContinueUserPaths, AllWithoutDuplicates) {
  const std::string out = scratchDir("continue", "all");
  const auto r = runMetrosync("continue " + shellQuote(rig("paper/f4.3-mu0.2.yaml")) +
                              " --param platform.friction.mu --to 0.6 --all --no-cycles -q "
                              "--out " +
                              shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto bif = nlohmann::json::parse(slurp(out + "/bifurcations.json"));
  for (size_t a = 0; a < bif.size(); ++a)
    for (size_t b = a + 1; b < bif.size(); ++b)
      EXPECT_FALSE(bif[a]["type"] == bif[b]["type"] &&
                   std::abs(bif[a]["value"].get<double>() - bif[b]["value"].get<double>()) < 1e-7)
          << bif[a]["type"] << " at " << bif[a]["value"] << " twice";
  // the upper in-phase state at mu = 0.2 (A = 1.8695) starts or ends exactly one branch
  std::set<std::string> on_it;
  for (const auto& q : csv(out + "/branches.csv")) {
    const double mu = num(q, "platform.friction.mu");
    EXPECT_GE(mu, 0.2);
    EXPECT_LE(mu, 0.6);
    if (mu == 0.2 && std::abs(num(q, "A_1") - 1.8695) < 1e-3 && std::abs(num(q, "psi_2")) < 1e-6)
      on_it.insert(q.at("branch"));
  }
  EXPECT_EQ(on_it.size(), 1u);
}

// Issue 37: --all promises every locked state at the start value, but its grid of seeds missed
// the experiment's own attractor (the stick-slip state near antiphase at mu = 0.00065, A = 2.911 /
// 2.892, psi = 3.125) that the default call starts from and `run --model slow` ends on. --all now
// follows the rig's start, settled, first. Checked against the slow flow's own run.
TEST(ContinueUserPaths, AllFindsTheRigsOwnAttractor) {
  const std::string dir = scratchDir("continue", "all-own", true);
  const auto run = runMetrosync("run " + shellQuote(rig("experiment.yaml")) +
                                " --model slow -q --no-plot --out " + shellQuote(dir + "/run"));
  ASSERT_EQ(run.code, 0) << run.err;
  const nlohmann::json fin = summaryOf(dir + "/run")["final"];
  const double a1 = fin["A"][0], a2 = fin["A"][1], psi = fin["psi"][0];
  EXPECT_NEAR(a1, 2.911, 2e-3);
  EXPECT_NEAR(a2, 2.892, 2e-3);
  EXPECT_NEAR(std::remainder(psi, kTwoPi), 3.125, 2e-3);
  const auto all = runMetrosync("continue " + shellQuote(rig("experiment.yaml")) +
                                " --param platform.friction.mu --to 0.01 --all -q --out " +
                                shellQuote(dir + "/all"));
  ASSERT_EQ(all.code, 0) << all.err;
  int found = 0;
  for (const auto& q : csv(dir + "/all/branches.csv")) {
    if (num(q, "platform.friction.mu") != 0.00065) continue;
    found += std::abs(num(q, "A_1") - a1) < 1e-3 && std::abs(num(q, "A_2") - a2) < 1e-3 &&
             std::abs(std::remainder(num(q, "psi_2") - psi, kTwoPi)) < 1e-3 &&
             q.at("stable") == "1";
  }
  EXPECT_EQ(found, 1) << slurp(dir + "/all/branches.csv").substr(0, 2000);
  EXPECT_NE(summaryOf(dir + "/all")["start"].get<std::string>().find("the rig's start, settled"),
            std::string::npos);
}

// The experiment's detuning with --all: the identical pair's antiphase states at alpha = 0 lie on
// a family that exists there only; nothing is reported at alpha ~ 1e-15 (no spurious folds), and
// a second key gives distinct fold curves.
TEST(ContinueUserPaths, AllAtAFamilyAndDistinctFoldCurves) {
  const std::string out = scratchDir("continue", "all-alpha");
  const auto r = runMetrosync("continue " + shellQuote(rig("experiment-map.yaml")) +
                              " --param metronomes.1.alpha --to 3 --all --no-cycles -q --out " +
                              shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  for (const auto& b : nlohmann::json::parse(slurp(out + "/bifurcations.json")))
    EXPECT_FALSE(b["type"] == "fold" && std::abs(b["value"].get<double>()) < 1e-6) << b;
  const std::string out2 = scratchDir("continue", "fold-curves");
  const auto r2 = runMetrosync("continue " + shellQuote(rig("paper/f4.3-mu0.2.yaml")) +
                               " --param platform.friction.mu --to 0.6 --all --no-cycles "
                               "--fold metronomes.1.alpha --to2 1 -q --out " +
                               shellQuote(out2));
  ASSERT_EQ(r2.code, 0) << r2.err;
  std::map<std::string, std::vector<std::pair<double, double>>> curves;
  for (const auto& q : csv(out2 + "/fold_curve.csv"))
    curves[q.at("fold")].push_back({num(q, "platform.friction.mu"), num(q, "metronomes.1.alpha")});
  ASSERT_GE(curves.size(), 1u);
  for (const auto& [a, pa] : curves)
    for (const auto& [b, pb] : curves) {
      if (a >= b) continue;
      size_t same = 0;
      for (const auto& x : pa)
        for (const auto& y : pb)
          if (std::abs(x.first - y.first) < 1e-4 && std::abs(x.second - y.second) < 1e-4) {
            ++same;
            break;
          }
      EXPECT_LT(same, pa.size() / 2) << "fold curves " << a << " and " << b << " coincide";
    }
}

// A physical rig: mu in its own units (6.5e-4 .. 0.01) is followed to --to; a branch stopped by
// --max-points says so on stdout.
TEST(ContinueUserPaths, PhysicalRigReachesToAndSaysWhenMaxPointsStops) {
  const std::string out = scratchDir("continue", "physical");
  const std::string cmd = "continue " + shellQuote(rig("experiment.yaml")) +
                          " --param platform.friction.mu --to 0.01 --no-cycles --out " +
                          shellQuote(out);
  const auto r = runMetrosync(cmd + " -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto branch = summaryOf(out)["branches"][0];
  EXPECT_NE(branch["end_forward"].get<std::string>().find("at p = 0.01"), std::string::npos)
      << branch;
  EXPECT_FALSE(branch["max_points"].get<bool>());
  const auto capped = runMetrosync(cmd + " --max-points 5");
  ASSERT_EQ(capped.code, 0) << capped.err;
  EXPECT_NE(capped.out.find("stopped by --max-points"), std::string::npos) << capped.out;
}

// sweep --boundaries over the experiment's (alpha, mu): the map and boundaries.csv are written and
// sweep.json is complete, whatever a curve does.
TEST(ContinueUserPaths, BoundariesKeepTheMap) {
  const std::string out = scratchDir("boundaries", "experiment-map");
  const auto r = runMetrosync("sweep " + shellQuote(rig("experiment-map.yaml")) +
                              " --model slow --vary metronomes.1.alpha=0:3:5 --vary "
                              "platform.friction.mu=0.01:1.5:5 --boundaries --no-plot -q --out " +
                              shellQuote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(out + "/regimes.csv"));
  EXPECT_TRUE(std::filesystem::exists(out + "/boundaries.csv"));
  const auto status = nlohmann::json::parse(slurp(out + "/sweep.json"));
  EXPECT_TRUE(status["complete"].get<bool>());
  EXPECT_TRUE(status["boundaries"].is_array());
  EXPECT_GT(status["boundaries"].size(), 0u);
}

}  // namespace
}  // namespace metrosync
