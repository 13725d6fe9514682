// Rig files (SPEC section 1): what loads, into what, and every validation rule with the message
// it gives (file:line:col, key path, value, what is wrong). Rigs are written inline; a test that
// needs a bad value replaces one numbered line of a valid rig, so the expected line is explicit.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "base/constants.h"
#include "contact/law_registry.h"
#include "models/scaling.h"
#include "yaml/rig_loader.h"

namespace metrosync {
namespace {

// A valid physical rig; line numbers are in the margin comments of the tests below.
const char* const kPhysical = R"(units: physical
platform:
  mass: 0.15
  friction: {law: coulomb, mu: 6.5e-4}
metronomes:
  - box_mass: 0.06
    pendulum: {mass: 0.0226, length: 0.0225, damping: 0.0226}
    escapement: {angle: 0.244, impulse: 1.5e-5}
    start: {angle: 0.5, rate: 0.0}
  - box_mass: 0.06
    pendulum:
      mass: 0.0226
      length: 0.0225
      decay_rate: 0.5
    escapement: {angle: 0.244, steady_amplitude: 0.785}
simulation:
  duration: 100
)";

// A valid scaled rig.
const char* const kScaled = R"(units: scaled
epsilon: 0.073
platform:
  friction: {law: coulomb, mu: 0.4}
metronomes:
  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 1.9, phi: 0.03}}
  - nu: 0.7
    J: 2.8
    theta_c: 0.9
    alpha: 0.1
    start: {theta: 0.5, thetadot: -1.0}
simulation:
  tau: 300
)";

// `text` with line `line` (1-based) replaced by `with` (which may hold several lines, or none).
std::string withLine(const std::string& text, int line, const std::string& with) {
  std::istringstream in(text);
  std::string out, l;
  for (int n = 1; std::getline(in, l); ++n) {
    if (n == line) {
      if (!with.empty()) out += with + "\n";
    } else {
      out += l + "\n";
    }
  }
  return out;
}

// The message of the RigError that loading must raise ("" and a test failure if it loads).
std::string errorOf(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  try {
    loadRigText(yaml, "rig.yaml", overrides);
  } catch (const RigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "loaded without error:\n" << yaml;
  return "";
}

// The message starts with `start` (file:line:col or --set) and contains every piece in `parts`.
void expectError(const std::string& yaml, const std::string& start,
                 std::initializer_list<std::string> parts,
                 const std::vector<std::string>& overrides = {}) {
  const std::string msg = errorOf(yaml, overrides);
  EXPECT_EQ(msg.rfind(start, 0), 0u) << "message: " << msg << "\nexpected start: " << start;
  for (const std::string& p : parts)
    EXPECT_NE(msg.find(p), std::string::npos) << "message: " << msg << "\nmissing: " << p;
}

// ------------------------------------------------------------------------------------------
// what loads

TEST(RigLoader, PhysicalRigLoads) {
  const Rig rig = loadRigText(kPhysical, "rigs/pair.yaml");
  EXPECT_EQ(rig.name, "pair");  // the file's stem, no name key
  EXPECT_EQ(rig.units, Units::Physical);
  EXPECT_EQ(rig.gravity_m_s2, 9.81);
  EXPECT_EQ(rig.platform.mass_kg, 0.15);
  EXPECT_EQ(rig.platform.friction, FrictionLaw::coulomb(6.5e-4));
  EXPECT_EQ(rig.platform.spring_N_m, 0.0);
  ASSERT_EQ(rig.metronomes.size(), 2u);
  const MetronomeSpec& a = rig.metronomes[0];
  EXPECT_EQ(a.name, "1");
  EXPECT_EQ(a.box_mass_kg, 0.06);
  EXPECT_EQ(a.pendulum_mass_kg, 0.0226);
  EXPECT_EQ(a.length_m, 0.0225);
  EXPECT_EQ(a.inertia_kgm2, 0.0226 * 0.0225 * 0.0225);  // default m L^2
  EXPECT_EQ(a.damping_kg_s, 0.0226);
  EXPECT_EQ(a.theta_c_rad, 0.244);
  EXPECT_EQ(a.impulse_Nms, 1.5e-5);
  EXPECT_EQ(a.start_angle_rad, 0.5);
  EXPECT_FALSE(a.locked);
  const MetronomeSpec& b = rig.metronomes[1];
  EXPECT_EQ(b.name, "2");
  // decay_rate beta: nu-bar = 2 beta I / L^2 (= 2 beta m for a point pendulum); one rounding
  EXPECT_NEAR(b.damping_kg_s, 2 * 0.5 * 0.0226, 1e-17);
  EXPECT_EQ(b.start_angle_rad, 0.0);  // no start: at rest
  EXPECT_EQ(b.start_rate_rad_s, 0.0);
  EXPECT_EQ(rig.sim.t_end_s, 100.0);
  EXPECT_EQ(rig.sim.accuracy, 1e-8);
  EXPECT_EQ(rig.sim.integrator, "");
  EXPECT_EQ(rig.sim.sample_s, 0.0);
}

TEST(RigLoader, SteadyAmplitudeGivesTheImpulseThatSettlesThere) {
  const Rig rig = loadRigText(kPhysical, "rig.yaml");
  const ScaledParams p = computeScaled(rig);
  // metronome 2 was given steady_amplitude 0.785 rad: its scaled A_star must be 0.785/sqrt(eps)
  // (J_estimate and A_star are inverse; rounding in J-bar <-> J only: 1e-12 relative)
  ASSERT_TRUE(p.A_star[1].has_value());
  EXPECT_NEAR(*p.A_star[1], 0.785 / std::sqrt(p.epsilon), 1e-12);
  EXPECT_GT(rig.metronomes[1].impulse_Nms, 0.0);
}

TEST(RigLoader, ScaledRigLoadsAsItsEquivalentSystem) {
  const Rig rig = loadRigText(kScaled, "scaled.yaml");
  EXPECT_EQ(rig.units, Units::Scaled);
  EXPECT_EQ(rig.name, "scaled");
  const ScaledParams p = computeScaled(rig);
  // the inputs come back through rigFromScaled/computeScaled to rounding (see test_scaling):
  // 1e-13 absolute on O(1) values, alpha (recovered / eps) 1e-12
  EXPECT_NEAR(p.epsilon, 0.073, 1e-15);
  EXPECT_NEAR(*p.friction.value("mu"), 0.4, 1e-13);
  EXPECT_NEAR(p.nu[0], 0.7, 1e-13);
  EXPECT_NEAR(p.J[1], 2.8, 1e-13);
  EXPECT_NEAR(p.theta_c[1], 0.9, 1e-13);
  EXPECT_NEAR(p.alpha[1], 0.1, 1e-12);
  EXPECT_NEAR(p.zeta[1], 0.0, 1e-12);
  // {A, phi}: theta = A sin phi, thetadot = A cos phi
  EXPECT_NEAR(p.theta0[0], 1.9 * std::sin(0.03), 1e-13);
  EXPECT_NEAR(p.thetadot0[0], 1.9 * std::cos(0.03), 1e-13);
  EXPECT_NEAR(p.theta0[1], 0.5, 1e-13);
  EXPECT_NEAR(p.thetadot0[1], -1.0, 1e-13);
  EXPECT_NEAR(p.tau_end, 300.0, 1e-10);
  EXPECT_NEAR(rig.sim.t_end_s, 300.0 / 0.073, 1e-9);
}

TEST(RigLoader, SpecExamplesLoad) {
  // SPEC 1a, with metronome B written out and the optional keys it mentions
  const Rig a = loadRigText(R"(units: physical
name: wittner-pair
gravity: 9.81
platform:
  mass: 0.1432
  friction: {law: coulomb, mu: 6.5e-4}
  spring: {k: 30.0}
metronomes:
  - name: A
    box_mass: 0.0602
    pendulum:
      mass: 0.0226
      length: 0.0225
      inertia: 1.144e-5
      damping: 0.0226
    escapement:
      angle: 0.244
      impulse: 1.49e-5
    start: {angle: 0.785, rate: 0.0}
  - name: B
    box_mass: 0.0602
    pendulum: {mass: 0.0226, length: 0.0225, decay_rate: 0.5}
    escapement: {angle: 0.244, steady_amplitude: 0.785}
    locked: true
start: {x: 0.0, v: 0.0}
simulation:
  duration: 200
  accuracy: 1e-9
  integrator: rk45
  sample: 0.01
)",
                            "spec.yaml");
  EXPECT_EQ(a.name, "wittner-pair");
  EXPECT_EQ(a.platform.spring_N_m, 30.0);
  // 1.144e-5 is m L^2 = 1.1441e-5 rounded: accepted, and raised to m L^2
  EXPECT_EQ(a.metronomes[0].inertia_kgm2, 0.0226 * 0.0225 * 0.0225);
  EXPECT_TRUE(a.metronomes[1].locked);
  EXPECT_EQ(a.sim.accuracy, 1e-9);
  EXPECT_EQ(a.sim.integrator, "rk45");
  EXPECT_EQ(a.sim.sample_s, 0.01);

  // SPEC 1b as written
  const Rig b = loadRigText(R"(units: scaled
epsilon: 0.073
platform:
  friction: {law: coulomb, mu: 0.4}      # scaled mu
metronomes:
  - {nu: 0.7, J: 2.8, theta_c: 0.9, start: {A: 1.9, phi: 0.03}}
  - {nu: 0.7, J: 2.8, theta_c: 0.9, alpha: 0.0, start: {A: 1.9, phi: 0.0}}
simulation:
  tau: 300
)",
                            "spec-scaled.yaml");
  EXPECT_EQ(b.metronomes.size(), 2u);
}

TEST(RigLoader, FrictionLaws) {
  const Rig v = loadRigText(withLine(kPhysical, 4, "  friction: {law: viscous, c: 0.05}"), "r");
  EXPECT_EQ(v.platform.friction, FrictionLaw::viscous(0.05));
  EXPECT_EQ(loadRigText(withLine(kPhysical, 4, "  friction: {law: none}"), "r").platform.friction,
            FrictionLaw::none());
  EXPECT_EQ(loadRigText(withLine(kPhysical, 4, "  friction: {law: fixed}"), "r").platform.friction,
            FrictionLaw::fixed());
  const Rig s = loadRigText(withLine(kScaled, 4, "  friction: {law: viscous, c: 0.3}"), "r");
  EXPECT_NEAR(*computeScaled(s).friction.value("c"), 0.3, 1e-13);  // back to rounding
  // static friction above kinetic: the keys choose the law, in either units
  const Rig st = loadRigText(
      withLine(kPhysical, 4, "  friction: {law: coulomb, mu: 6.5e-4, mu_static: 1e-3}"), "r");
  EXPECT_EQ(st.platform.friction, FrictionLaw(staticCoulombLaw(), {6.5e-4, 1e-3}));
  const Rig ss =
      loadRigText(withLine(kScaled, 4, "  friction: {law: coulomb, mu: 0.4, mu_static: 0.4}"), "r");
  EXPECT_NEAR(*computeScaled(ss).friction.value("mu_static"), 0.4, 1e-13);
  const Rig set = loadRigText(kPhysical, "r", {"platform.friction.mu_static=2e-3"});
  EXPECT_EQ(set.platform.friction, FrictionLaw(staticCoulombLaw(), {6.5e-4, 2e-3}));
}

TEST(RigLoader, NoEscapementMeansNoImpulse) {
  const Rig rig = loadRigText(withLine(kPhysical, 8, ""), "r");
  EXPECT_EQ(rig.metronomes[0].impulse_Nms, 0.0);
  EXPECT_EQ(rig.metronomes[0].theta_c_rad, 0.0);
  EXPECT_FALSE(computeScaled(rig).A_star[0].has_value());
}

TEST(RigLoader, NameKeyOrStem) {
  EXPECT_EQ(loadRigText("name: duo\n" + std::string(kPhysical), "x/y/z.yaml").name, "duo");
  EXPECT_EQ(loadRigText(kPhysical, "x/y/z.yaml").name, "z");
  expectError("name: a/b\n" + std::string(kPhysical),
              "rig.yaml:1:7: ", {"name = a/b", "must not contain '/'"});
  expectError("name: ''\n" + std::string(kPhysical), "rig.yaml:1:7: ", {"name = ''", "empty"});
}

TEST(RigLoader, MissingFile) {
  try {
    loadRigFile("/nonexistent/dir/rig.yaml");
    FAIL();
  } catch (const RigError& e) {
    EXPECT_EQ(std::string(e.what()),
              "/nonexistent/dir/rig.yaml: cannot open the rig file (No such file or directory)");
  }
}

// ------------------------------------------------------------------------------------------
// the default rig

bool sameRig(const Rig& a, const Rig& b, std::string& why) {
  std::ostringstream os;
  auto cmp = [&](const char* what, auto x, auto y) {
    if (!(x == y)) os << what << ": " << x << " vs " << y << "\n";
  };
  cmp("name", a.name, b.name);
  cmp("units", static_cast<int>(a.units), static_cast<int>(b.units));
  cmp("gravity", a.gravity_m_s2, b.gravity_m_s2);
  cmp("platform.mass", a.platform.mass_kg, b.platform.mass_kg);
  cmp("friction", a.platform.friction.toJson().dump(), b.platform.friction.toJson().dump());
  cmp("spring", a.platform.spring_N_m, b.platform.spring_N_m);
  cmp("x0", a.platform.start_x_m, b.platform.start_x_m);
  cmp("v0", a.platform.start_v_m_s, b.platform.start_v_m_s);
  cmp("N", a.metronomes.size(), b.metronomes.size());
  for (std::size_t i = 0; i < std::min(a.metronomes.size(), b.metronomes.size()); ++i) {
    const MetronomeSpec &x = a.metronomes[i], &y = b.metronomes[i];
    cmp("name", x.name, y.name);
    cmp("box", x.box_mass_kg, y.box_mass_kg);
    cmp("m", x.pendulum_mass_kg, y.pendulum_mass_kg);
    cmp("L", x.length_m, y.length_m);
    cmp("I", x.inertia_kgm2, y.inertia_kgm2);
    cmp("damping", x.damping_kg_s, y.damping_kg_s);
    cmp("theta_c", x.theta_c_rad, y.theta_c_rad);
    cmp("impulse", x.impulse_Nms, y.impulse_Nms);
    cmp("locked", x.locked, y.locked);
    cmp("angle", x.start_angle_rad, y.start_angle_rad);
    cmp("rate", x.start_rate_rad_s, y.start_rate_rad_s);
  }
  cmp("t_end", a.sim.t_end_s, b.sim.t_end_s);
  cmp("accuracy", a.sim.accuracy, b.sim.accuracy);
  cmp("integrator", a.sim.integrator, b.sim.integrator);
  cmp("sample", a.sim.sample_s, b.sim.sample_s);
  why = os.str();
  return why.empty();
}

TEST(DefaultRig, IsThePapersExperiment) {
  const Rig rig = defaultRig();
  EXPECT_EQ(rig.name, "experiment");
  EXPECT_EQ(rig.units, Units::Physical);
  EXPECT_EQ(rig.platform.mass_kg, 0.1432);
  EXPECT_EQ(rig.platform.friction, FrictionLaw::coulomb(6.5e-4));
  ASSERT_EQ(rig.metronomes.size(), 2u);
  EXPECT_NEAR(rig.totalMass(), 0.3088, 1e-12);  // "M = 308.8 g"
  for (const MetronomeSpec& m : rig.metronomes) {
    EXPECT_EQ(m.box_mass_kg, 0.0602);
    EXPECT_EQ(m.pendulum_mass_kg, 0.0226);
    EXPECT_EQ(m.length_m, 0.0225);
    EXPECT_EQ(m.inertia_kgm2, 0.0226 * 0.0225 * 0.0225);
    EXPECT_NEAR(m.damping_kg_s, 2 * 0.5 * 0.0226, 1e-17);  // decay rate 0.5 1/s
    EXPECT_EQ(m.theta_c_rad, 0.244);
  }
  EXPECT_EQ(rig.metronomes[0].start_angle_rad, 0.785);
  EXPECT_EQ(rig.metronomes[1].start_angle_rad, -0.785);
  EXPECT_EQ(rig.metronomes[1].start_rate_rad_s, 0.25);
  EXPECT_EQ(rig.sim.t_end_s, 200.0);

  // started near antiphase: scaled phases phi = atan2(theta, thetadot) differ by ~pi
  const ScaledParams p = computeScaled(rig);
  const double psi =
      std::atan2(p.theta0[0], p.thetadot0[0]) - std::atan2(p.theta0[1], p.thetadot0[1]);
  EXPECT_NEAR(std::remainder(psi, 2 * kPi), kPi, 0.3);
  EXPECT_LT(std::abs(std::remainder(psi, 2 * kPi)) - kPi, 0.0);  // near, not at, antiphase
  // both settle to 45 deg alone on a still table
  EXPECT_NEAR(*p.A_star[0], 0.785 / std::sqrt(p.epsilon), 1e-12);
}

TEST(DefaultRig, ShippedFileIsTheBuiltInRig) {
  const std::string path = std::string(METROSYNC_SOURCE_DIR) + "/yaml/rigs/experiment.yaml";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), defaultRigYaml()) << "edit both yaml/rigs/experiment.yaml and "
                                             "defaultRigYaml() in yaml/rig_loader.cpp";
  std::string why;
  EXPECT_TRUE(sameRig(loadRigFile(path), defaultRig(), why)) << why;
  // and the comparison can fail
  EXPECT_FALSE(sameRig(loadRigFile(path, {"metronomes.1.start.rate=0.3"}), defaultRig(), why));
}

TEST(DefaultRig, SectionThreeNumbersThroughTheLoader) {
  // the high-friction rollers (mu-bar = 4.6e-3) with 14 deg = 0.244 rad: the paper's section 3
  // numbers, to the digits it prints (tolerance: half a unit in the last printed digit)
  const ScaledParams p = computeScaled(defaultRig({"platform.friction.mu=4.6e-3"}));
  EXPECT_NEAR(p.epsilon, 0.073, 0.0005);
  EXPECT_NEAR(p.theta_c[0], 0.9, 0.05);
  EXPECT_NEAR(p.nu[0], 0.65, 0.005);
  EXPECT_NEAR(*p.friction.value("mu"), 0.23, 0.005);
  EXPECT_NEAR(*p.A_star[0], 2.9, 0.05);
  EXPECT_NEAR(p.J[0], 3.14, 0.005);
}

// ------------------------------------------------------------------------------------------
// validation. Errors must point at the offending text itself: expectErrorAt finds `token` on
// line `line` of the rig and expects the message to start with rig.yaml:line:column.

std::string at(const std::string& yaml, int line, const std::string& token) {
  std::istringstream in(yaml);
  std::string l;
  for (int n = 1; std::getline(in, l); ++n) {
    if (n != line) continue;
    const std::size_t col = l.find(token);
    if (col == std::string::npos) break;
    return "rig.yaml:" + std::to_string(line) + ":" + std::to_string(col + 1) + ": ";
  }
  ADD_FAILURE() << "no '" << token << "' on line " << line << " of\n" << yaml;
  return "?";
}

void expectErrorAt(const std::string& yaml, int line, const std::string& token,
                   std::initializer_list<std::string> parts,
                   const std::vector<std::string>& overrides = {}) {
  expectError(yaml, at(yaml, line, token), parts, overrides);
}

// `text` with lines first..last (1-based) replaced by `with`.
std::string withLines(const std::string& text, int first, int last, const std::string& with) {
  std::string out = withLine(text, first, with);
  for (int n = first + 1; n <= last; ++n) out = withLine(out, with.empty() ? first : first + 1, "");
  return out;
}

TEST(RigValidation, YamlSyntaxErrorHasLineAndColumn) {
  // an unclosed flow map: yaml-cpp reports where it gave up (the next line)
  expectError(withLine(kPhysical, 4, "  friction: {law: coulomb, mu: 6.5e-4"),
              "rig.yaml:5:", {"YAML syntax error"});
  // a value after a flow list at a deeper indent
  const std::string bad = withLine(kPhysical, 2, "platform: [0.15]");
  expectErrorAt(bad, 3, "mass", {"YAML syntax error"});
}

TEST(RigValidation, EmptyOrNotAMap) {
  expectError("", "rig.yaml:1:1: ", {"the rig is empty"});
  expectError("- 1\n- 2\n", "rig.yaml:1:1: ", {"the rig is a list"});
  // kPhysical has 17 lines: the second document starts at the '---' of line 18
  expectError(std::string(kPhysical) + "---\nunits: scaled\n",
              "rig.yaml:18:1: ", {"a second YAML document starts here"});
}

TEST(RigValidation, Units) {
  expectError(withLine(kPhysical, 1, ""), "rig.yaml:1:1: ", {"units: missing"});
  const std::string metric = withLine(kPhysical, 1, "units: metric");
  expectErrorAt(metric, 1, "metric", {"units = metric", "must be physical or scaled"});
}

TEST(RigValidation, UnknownKeysSuggestTheClosest) {
  expectError("gravty: 9.8\n" + std::string(kPhysical),
              "rig.yaml:1:1: ", {"gravty = 9.8", "unknown key", "did you mean 'gravity'?"});
  const std::string damp = withLine(kPhysical, 14, "      dampnig: 0.02");
  expectErrorAt(damp, 14, "dampnig",
                {"metronomes.1.pendulum.dampnig = 0.02", "did you mean 'damping'?"});
  const std::string acc = withLine(kPhysical, 17, "  acuracy: 1e-9");
  expectErrorAt(acc, 17, "acuracy", {"simulation.acuracy", "did you mean 'accuracy'?"});
  // a key one level too high
  const std::string high = withLine(kPhysical, 6, "  - mass: 0.06");
  expectErrorAt(high, 6, "mass", {"metronomes.0.mass = 0.06", "did you mean 'pendulum.mass'?"});
  // nothing close: the valid keys are listed
  const std::string colour = withLine(kPhysical, 3, "  colour: red");
  expectErrorAt(colour, 3, "colour",
                {"platform.colour = red", "expected one of: mass, friction, spring"});
}

TEST(RigValidation, KeysOfTheOtherUnits) {
  expectError("epsilon: 0.07\n" + std::string(kPhysical),
              "rig.yaml:1:1: ", {"epsilon = 0.07", "only with units: scaled"});
  const std::string mass = withLine(kScaled, 3, "platform:\n  mass: 0.2");
  expectErrorAt(mass, 4, "mass", {"platform.mass = 0.2", "only with units: physical"});
  const std::string spring = withLine(kScaled, 3, "platform:\n  spring: {k: 30}");
  expectErrorAt(spring, 4, "spring", {"platform.spring", "only with units: physical"});
  const std::string locked = withLine(kScaled, 10, "    locked: true");
  expectErrorAt(locked, 10, "locked", {"metronomes.1.locked = true", "only with units: physical"});
  const std::string tau = withLine(kPhysical, 17, "  tau: 100");
  expectErrorAt(tau, 17, "tau", {"simulation.tau = 100", "only with units: scaled"});
  const std::string duration = withLine(kScaled, 13, "  duration: 3");
  expectErrorAt(duration, 13, "duration", {"simulation.duration = 3", "only with units: physical"});
}

TEST(RigValidation, DuplicateKey) {
  const std::string twice = withLine(kPhysical, 3, "  mass: 0.15\n  mass: 0.2");
  expectErrorAt(twice, 4, "mass", {"'mass' appears twice", "first at line 3"});
}

TEST(RigValidation, WrongTypes) {
  const std::string word = withLine(kPhysical, 12, "      mass: heavy");
  expectErrorAt(word, 12, "heavy", {"metronomes.1.pendulum.mass = heavy", "must be a number"});
  const std::string map = withLine(kPhysical, 12, "      mass: {kg: 0.02}");
  expectErrorAt(map, 12, "{",
                {"metronomes.1.pendulum.mass = (a map)", "must be a number, not a map"});
  const std::string empty = withLine(kPhysical, 12, "      mass:");
  expectErrorAt(empty, 12, "mass", {"metronomes.1.pendulum.mass: has no value", "a number"});
  // a map where a list belongs
  const std::string named = R"(units: physical
platform: {mass: 0.1, friction: {law: none}}
metronomes:
  A: {box_mass: 0.06}
simulation: {duration: 1}
)";
  expectErrorAt(named, 4, "A", {"metronomes = (a map)", "must be a list", "not a map"});
  // a list where a map belongs
  const std::string list = withLines(kPhysical, 2, 4, "platform: [0.15]");
  expectErrorAt(list, 2, "[", {"platform = (a list)", "must be a map of keys, not a list"});
  const std::string maybe = withLine(kPhysical, 9, "    locked: maybe");
  expectErrorAt(maybe, 9, "maybe", {"metronomes.0.locked = maybe", "must be true or false"});
  const std::string inf = withLine(kPhysical, 3, "  mass: .inf");
  expectErrorAt(inf, 3, ".inf", {"platform.mass = .inf", "must be a finite number"});
  const std::string nan = withLine(kPhysical, 3, "  mass: .nan");
  expectErrorAt(nan, 3, ".nan", {"platform.mass = .nan", "must be a finite number"});
  const std::string big = withLine(kPhysical, 3, "  mass: 1e999");
  expectErrorAt(big, 3, "1e999", {"platform.mass = 1e999", "must be a finite number"});
}

TEST(RigValidation, MissingRequiredKeys) {
  // missing keys point at the map that should hold them
  const std::string no_mass = withLine(kPhysical, 3, "");
  expectErrorAt(no_mass, 3, "friction", {"platform.mass: missing", "kg"});
  const std::string no_friction = withLine(kPhysical, 4, "");
  expectErrorAt(no_friction, 3, "mass", {"platform.friction: missing"});
  const std::string no_law = withLine(kPhysical, 4, "  friction: {mu: 0.1}");
  expectErrorAt(no_law, 4, "{",
                {"platform.friction.law: missing", "coulomb, viscous, none, fixed or stribeck"});
  const std::string no_mu = withLine(kPhysical, 4, "  friction: {law: coulomb}");
  expectErrorAt(no_mu, 4, "{", {"platform.friction.mu: missing"});
  const std::string no_c = withLine(kPhysical, 4, "  friction: {law: viscous}");
  expectErrorAt(no_c, 4, "{", {"platform.friction.c: missing"});
  const std::string no_length = withLine(kPhysical, 13, "");
  expectErrorAt(no_length, 12, "mass", {"metronomes.1.pendulum.length: missing"});
  const std::string no_damping = withLine(kPhysical, 14, "");
  expectErrorAt(no_damping, 12, "mass", {"metronomes.1.pendulum.damping: missing", "decay_rate"});
  const std::string no_box = withLine(kPhysical, 10, "  - name: B");
  expectErrorAt(no_box, 10, "name", {"metronomes.1.box_mass: missing"});
  const std::string no_pendulum = withLines(kPhysical, 11, 14, "");
  expectErrorAt(no_pendulum, 10, "box_mass", {"metronomes.1.pendulum: missing"});
  const std::string no_angle = withLine(kPhysical, 15, "    escapement: {steady_amplitude: 0.785}");
  expectErrorAt(no_angle, 15, "{", {"metronomes.1.escapement.angle: missing"});
  const std::string no_impulse = withLine(kPhysical, 15, "    escapement: {angle: 0.244}");
  expectErrorAt(no_impulse, 15, "{",
                {"metronomes.1.escapement.impulse: missing", "steady_amplitude"});
  expectError(withLines(kPhysical, 16, 17, ""), "rig.yaml:1:1: ", {"simulation: missing"});
  const std::string no_duration = withLine(kPhysical, 17, "  accuracy: 1e-9");
  expectErrorAt(no_duration, 17, "accuracy", {"simulation.duration: missing"});
  expectError("units: physical\nsimulation: {duration: 1}\n",
              "rig.yaml:1:1: ", {"platform: missing"});
  expectError(R"(units: physical
platform: {mass: 0.1, friction: {law: none}}
simulation: {duration: 1}
)",
              "rig.yaml:1:1: ", {"metronomes: missing"});
  expectError(withLine(kScaled, 2, ""), "rig.yaml:1:1: ", {"epsilon: missing"});
  const std::string no_nu = withLine(kScaled, 7, "  - name: B");
  expectErrorAt(no_nu, 7, "name", {"metronomes.1.nu: missing"});
  const std::string no_tau = withLine(kScaled, 13, "  accuracy: 1e-9");
  expectErrorAt(no_tau, 13, "accuracy", {"simulation.tau: missing"});
}

TEST(RigValidation, ExactlyOneOfTwoKeys) {
  const std::string both = withLine(kPhysical, 14, "      decay_rate: 0.5\n      damping: 0.02");
  expectErrorAt(both, 14, "0.5",
                {"metronomes.1.pendulum.decay_rate = 0.5", "damping or decay_rate, not both"});
  const std::string kick = withLine(
      kPhysical, 8, "    escapement: {angle: 0.244, impulse: 1e-5, steady_amplitude: 0.7}");
  expectErrorAt(kick, 8, "0.7}",
                {"metronomes.0.escapement.steady_amplitude = 0.7", "impulse or steady_amplitude"});
}

// One rule: line `line` of a valid rig replaced by `with`; the error points at `token` on line
// `error_line` (the same line if 0) and names the key, the value and the rule.
struct RangeCase {
  int line;
  const char* with;
  const char* token;
  const char* key_value;
  const char* rule;
  int error_line = 0;
};

void checkCases(const char* rig, std::initializer_list<RangeCase> cases) {
  for (const RangeCase& c : cases) {
    SCOPED_TRACE(c.key_value);
    const std::string yaml = withLine(rig, c.line, c.with);
    expectErrorAt(yaml, c.error_line ? c.error_line : c.line, c.token, {c.key_value, c.rule});
  }
}

TEST(RigValidation, FrictionLawAndItsCoefficient) {
  checkCases(kPhysical, {{4, "  friction: {law: colomb, mu: 0.1}", "colomb",
                          "platform.friction.law = colomb", "did you mean 'coulomb'?"},
                         {4, "  friction: {law: viscous, c: 0.1, mu: 0.2}", "0.2",
                          "platform.friction.mu = 0.2", "only with law: coulomb"},
                         {4, "  friction: {law: coulomb, c: 0.1, mu: 0.2}", "0.1",
                          "platform.friction.c = 0.1", "only with law: viscous"},
                         {4, "  friction: {law: none, mu: 0.1}", "0.1",
                          "platform.friction.mu = 0.1", "only with law: coulomb"},
                         {4, "  friction: {law: fixed, c: 0.1}", "0.1", "platform.friction.c = 0.1",
                          "only with law: viscous"},
                         {4, "  friction: {law: coulomb, mu: -0.1}", "-0.1",
                          "platform.friction.mu = -0.1", "must be >= 0"},
                         {4, "  friction: {law: viscous, c: -2}", "-2", "platform.friction.c = -2",
                          "must be >= 0"},
                         {4, "  friction: {law: viscous, c: 0.1, mu_static: 0.2}", "0.2",
                          "platform.friction.mu_static = 0.2", "only with law: coulomb"},
                         {4, "  friction: {law: coulomb, mu: 0.2, mu_static: 0.1}", "0.1",
                          "platform.friction.mu_static = 0.1", "must be >= mu"},
                         {4, "  friction: {law: coulomb, mu: 0.2, mu_static: -0.3}", "-0.3",
                          "platform.friction.mu_static = -0.3", "must be >= 0"},
                         {4, "  friction: {law: coulomb, mu: -0.2, mu_static: 0.3}", "-0.2",
                          "platform.friction.mu = -0.2", "must be >= 0"},
                         {4, "  friction: {law: coulomb, mu_static: 0.3}", "{",
                          "platform.friction.mu: missing", "kinetic"}});
}

TEST(RigValidation, PhysicalRanges) {
  checkCases(
      kPhysical,
      {{3, "  mass: 0", "0", "platform.mass = 0", "must be > 0"},
       {3, "  mass: 1e-999", "1e-999", "platform.mass = 1e-999", "must be > 0"},  // underflow
       {12, "      mass: -0.02", "-0.02", "metronomes.1.pendulum.mass = -0.02", "must be > 0"},
       {13, "      length: -1", "-1", "metronomes.1.pendulum.length = -1", "must be > 0"},
       {13, "      length: 0\n      inertia: 1e-5", "0", "metronomes.1.pendulum.length = 0",
        "must be > 0"},
       {13, "      length: 0.0225\n      inertia: 1.1e-5", "1.1e-5",
        "metronomes.1.pendulum.inertia = 1.1e-5", "must be >= mass * length^2 = 1.14412e-05", 14},
       {10, "  - box_mass: -0.06", "-0.06", "metronomes.1.box_mass = -0.06", "must be > 0"},
       {14, "      decay_rate: -0.5", "-0.5", "metronomes.1.pendulum.decay_rate = -0.5",
        "must be >= 0"},
       {7, "    pendulum: {mass: 0.0226, length: 0.0225, damping: -1}", "-1",
        "metronomes.0.pendulum.damping = -1", "must be >= 0"},
       {8, "    escapement: {angle: 0, impulse: 1.5e-5}", "0,", "metronomes.0.escapement.angle = 0",
        "must be in (0, pi)"},
       {8, "    escapement: {angle: 3.2, impulse: 1.5e-5}", "3.2",
        "metronomes.0.escapement.angle = 3.2", "must be in (0, pi)"},
       {8, "    escapement: {angle: 0.244, impulse: -1e-5}", "-1e-5",
        "metronomes.0.escapement.impulse = -1e-5", "must be >= 0"},
       {15, "    escapement: {angle: 0.244, steady_amplitude: 0.3}", "0.3",
        "metronomes.1.escapement.steady_amplitude = 0.3",
        "must be in [sqrt(2) * angle, pi) = [0.345068"},
       {15, "    escapement: {angle: 0.244, steady_amplitude: 3.5}", "3.5",
        "metronomes.1.escapement.steady_amplitude = 3.5", "must be in [sqrt(2) * angle, pi)"},
       {14, "      damping: 0", "0.785", "metronomes.1.escapement.steady_amplitude = 0.785",
        "needs damping > 0", 15},
       {17, "  duration: 0", "0", "simulation.duration = 0", "must be > 0"},
       {17, "  duration: 10\n  accuracy: 0", "0", "simulation.accuracy = 0", "must be in (0, 1)",
        18},
       {17, "  duration: 10\n  accuracy: 1", "1", "simulation.accuracy = 1", "must be in (0, 1)",
        18},
       {17, "  duration: 10\n  sample: -0.1", "-0.1", "simulation.sample = -0.1", "must be > 0",
        18},
       {1, "units: physical\ngravity: -9.81", "-9.81", "gravity = -9.81", "must be > 0", 2},
       {3, "  mass: 0.15\n  spring: {k: -3}", "-3", "platform.spring.k = -3", "must be >= 0", 4}});
  // N >= 1
  const std::string none = R"(units: physical
platform: {mass: 0.1, friction: {law: none}}
metronomes: []
simulation: {duration: 1}
)";
  expectErrorAt(none, 3, "[]", {"metronomes = (a list)", "must hold at least one metronome"});
}

TEST(RigValidation, ScaledRanges) {
  checkCases(
      kScaled,
      {{2, "epsilon: 0", "0", "epsilon = 0", "must be in (0, 1)"},
       {2, "epsilon: 1", "1", "epsilon = 1", "must be in (0, 1)"},
       {2, "epsilon: -0.1", "-0.1", "epsilon = -0.1", "must be in (0, 1)"},
       // pendulums of mass 1 and (1 + 0.6 * 0.1) outweigh M = 1 / 0.6: no platform mass left
       {2, "epsilon: 0.6", "0.6", "epsilon = 0.6", "too large for 2 metronomes"},
       {6, "  - {nu: -0.7, J: 2.8, theta_c: 0.9}", "-0.7", "metronomes.0.nu = -0.7",
        "must be >= 0"},
       {8, "    J: -1", "-1", "metronomes.1.J = -1", "must be >= 0"},
       {9, "    theta_c: 0", "0", "metronomes.1.theta_c = 0",
        "must be in (0, pi / sqrt(epsilon)) = (0, 11.6276)"},
       {9, "    theta_c: 12", "12", "metronomes.1.theta_c = 12",
        "must be in (0, pi / sqrt(epsilon))"},
       {10, "    alpha: -20", "-20", "metronomes.1.alpha = -20",
        "must be > -1 / epsilon = -13.6986"},
       {10, "    zeta: -14", "-14", "metronomes.1.zeta = -14", "must be > -1 / epsilon"},
       {6, "  - {nu: 0.7, J: 2.8, theta_c: 0.9, alpha: 0.1}", "0.1}", "metronomes.0.alpha = 0.1",
        "must be 0: metronome 1 is the reference"},
       {6, "  - {nu: 0.7, J: 2.8, theta_c: 0.9, zeta: -0.2}", "-0.2", "metronomes.0.zeta = -0.2",
        "must be 0: metronome 1 is the reference"},
       {11, "    start: {A: 1.0, theta: 0.5}", "0.5", "metronomes.1.start.theta = 0.5",
        "{A, phi} or as {theta, thetadot}, not both"},
       {11, "    start: {A: -1.0, phi: 0}", "-1.0", "metronomes.1.start.A = -1.0", "must be >= 0"},
       {11, "    start: {A: 1.0}", "{", "metronomes.1.start.phi: missing", "phase"},
       {13, "  tau: -3", "-3", "simulation.tau = -3", "must be > 0"},
       {4, "  friction: {law: coulomb, mu: -0.4}", "-0.4", "platform.friction.mu = -0.4",
        "must be >= 0"}});
  // metronome 1 may spell out its zeros
  EXPECT_NO_THROW(loadRigText(
      withLine(kScaled, 6, "  - {nu: 0.7, J: 2.8, theta_c: 0.9, alpha: 0, zeta: 0}"), "r"));
}

// ------------------------------------------------------------------------------------------
// --set

TEST(RigOverrides, ChangeAddAndReplace) {
  const Rig rig =
      loadRigText(kPhysical, "r",
                  {"platform.friction.mu=4.6e-3", "simulation.accuracy=1e-10",
                   "metronomes.0.name=left", "platform.spring.k=30",
                   "metronomes.1.start={angle: -0.5, rate: 0.1}", "gravity=9.8", "gravity=9.7"});
  EXPECT_EQ(rig.platform.friction, FrictionLaw::coulomb(4.6e-3));
  EXPECT_EQ(rig.sim.accuracy, 1e-10);  // a valid key absent from the file
  EXPECT_EQ(rig.metronomes[0].name, "left");
  EXPECT_EQ(rig.platform.spring_N_m, 30.0);  // an absent map is created on the way
  EXPECT_EQ(rig.metronomes[1].start_angle_rad, -0.5);
  EXPECT_EQ(rig.metronomes[1].start_rate_rad_s, 0.1);
  EXPECT_EQ(rig.gravity_m_s2, 9.7);  // later overrides win

  // a whole map as the value: switching the friction law
  const Rig v = loadRigText(kPhysical, "r", {"platform.friction={law: viscous, c: 0.05}"});
  EXPECT_EQ(v.platform.friction, FrictionLaw::viscous(0.05));

  // SPEC's examples on a scaled rig
  const ScaledParams p = computeScaled(
      loadRigText(kScaled, "r", {"platform.friction.mu=0.3", "metronomes.0.start.phi=3.54"}));
  EXPECT_NEAR(*p.friction.value("mu"), 0.3, 1e-13);
  EXPECT_NEAR(p.theta0[0], 1.9 * std::sin(3.54), 1e-13);
}

TEST(RigOverrides, UnitsFromSet) {
  // a rig without units: the override supplies them, and the path is checked against both
  const Rig rig = loadRigText(withLine(kPhysical, 1, ""), "r", {"units=physical"});
  EXPECT_EQ(rig.units, Units::Physical);
  // switching the units of a rig that has them would reinterpret every other key: the --set is
  // the culprit, not the file's keys
  expectError(kPhysical,
              "rig.yaml: --set units=scaled: ", {"the rig is written in units: physical (line 1)"},
              {"units=scaled"});
  // repeating the file's own units is harmless
  EXPECT_EQ(loadRigText(kPhysical, "r", {"units=physical"}).units, Units::Physical);
}

TEST(RigOverrides, BadPaths) {
  expectError(kPhysical, "rig.yaml: --set platform.frcition.mu=0.3: ",
              {"platform.frcition: unknown key (did you mean 'friction'?)"},
              {"platform.frcition.mu=0.3"});
  expectError(kPhysical, "rig.yaml: --set metronomes.2.pendulum.mass=0.1: ",
              {"metronomes.2: index 2 is out of range (metronomes has 2 entries"},
              {"metronomes.2.pendulum.mass=0.1"});
  expectError(kPhysical, "rig.yaml: --set metronomes.first.box_mass=0.1: ",
              {"metronomes is a list: expected an index from 0"},
              {"metronomes.first.box_mass=0.1"});
  expectError(kPhysical, "rig.yaml: --set epsilon=0.1: ", {"epsilon: only with units: scaled"},
              {"epsilon=0.1"});
  expectError(kPhysical,
              "rig.yaml: --set gravity.x=1: ", {"gravity is a single value, it has no key 'x'"},
              {"gravity.x=1"});
  expectError(kPhysical, "rig.yaml: --set platform.friction.mu: ", {"expected KEY=VALUE"},
              {"platform.friction.mu"});
  expectError(kPhysical, "rig.yaml: --set platform..mu=1: ", {"empty key"}, {"platform..mu=1"});
  expectError(kPhysical, "rig.yaml: --set metronomes.0.start.A=1: ",
              {"metronomes.0.start.A: only with units: scaled"}, {"metronomes.0.start.A=1"});
  expectError(kPhysical,
              "rig.yaml: --set platform.mass=[1: ", {"platform.mass: the value is not valid YAML"},
              {"platform.mass=[1"});
}

TEST(RigOverrides, BadValuesSayTheyCameFromSet) {
  expectError(kPhysical, "rig.yaml: --set metronomes.1.pendulum.mass=-0.02: ",
              {"metronomes.1.pendulum.mass = -0.02: must be > 0"},
              {"metronomes.1.pendulum.mass=-0.02"});
  expectError(kPhysical, "rig.yaml: --set platform.friction.mu=lots: ",
              {"platform.friction.mu = lots: must be a number"}, {"platform.friction.mu=lots"});
  expectError(kPhysical, "rig.yaml: --set platform.spring=: ",
              {"platform.spring: has no value (expected a map of keys)"}, {"platform.spring="});
  // a map from --set that lacks a key
  expectError(kPhysical, "rig.yaml: --set platform.friction={law: viscous}: ",
              {"platform.friction.c: missing"}, {"platform.friction={law: viscous}"});
  // an unknown key inside a map given by --set
  expectError(kPhysical, "rig.yaml: --set platform.spring={kk: 3}: ",
              {"platform.spring.kk = 3: unknown key (did you mean 'k'?)"},
              {"platform.spring={kk: 3}"});
  // a value from the file made wrong by a --set elsewhere still points into the file
  expectErrorAt(kPhysical, 4, "6.5e-4", {"platform.friction.mu = 6.5e-4", "only with law: coulomb"},
                {"platform.friction.law=viscous"});
}

}  // namespace
}  // namespace metrosync
