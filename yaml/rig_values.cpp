#include "yaml/rig_values.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "base/constants.h"
#include "models/scaling.h"
#include "yaml/rig_limits.h"

namespace metrosync::rigfile {

namespace {

// Slack on inertia >= m L^2: inputs rounded to 4 significant digits (the SPEC's own example,
// 1.144e-5 against 0.0226 * 0.0225^2 = 1.1441e-5) must pass; a value in the slack is raised to
// m L^2, which is what it stands for.
constexpr double kInertiaSlack = 1e-3;

// start: {x, v}, both units
void readPlatformStart(const Reader& top, double& x, double& v) {
  if (auto s = top.optMap("start")) {
    x = s->optNumber("x").value_or(0.0);
    v = s->optNumber("v").value_or(0.0);
  }
}

// simulation: {duration | tau, accuracy, integrator, sample}
void readSimulation(const Reader& top, const char* duration_key, const std::string& what,
                    double& duration, double& accuracy, std::string& integrator, double& sample) {
  const Reader s = top.map("simulation", std::string("at least ") + duration_key);
  duration = positive(s, duration_key, what);
  if (auto a = s.optNumber("accuracy")) {
    if (!(*a > 0 && *a < 1)) s.bad("accuracy", "must be in (0, 1)");
    if (*a < kMinAccuracy)
      s.bad("accuracy",
            "must be >= " + numberText(kMinAccuracy) +
                ": no integrator can meet a smaller relative error in double precision");
    accuracy = *a;
  }
  if (auto name = s.optText("integrator")) integrator = *name;  // the engine checks the name
  if (auto dt = s.optNumber("sample")) {
    if (!(*dt > 0)) s.bad("sample", "must be > 0");
    sample = *dt;
  }
}

// `top` holds the list; `list_path` names it in messages (platforms.1.metronomes in a network).
const Node& readMetronomeList(const Reader& holder, const std::string& list_path,
                              const std::string& what) {
  const std::size_t dot = list_path.rfind('.');
  const Reader top = holder.withPath(dot == std::string::npos ? "" : list_path.substr(0, dot));
  if (!top.has("metronomes")) top.missing("metronomes", what);
  const Node& list = *top.find("metronomes");
  if (list.seq.empty()) top.bad("metronomes", "must hold at least one metronome");
  if (list.seq.size() > kMaxMetronomes)
    top.bad("metronomes", "holds " + std::to_string(list.seq.size()) + " metronomes (at most " +
                              std::to_string(kMaxMetronomes) + ", see docs/rig-limits.md)");
  return list;
}

// pendulum: mass, length, inertia (>= m L^2), damping or decay_rate (e1.1a), air_drag (>= 0)
void readPhysicalPendulum(const Reader& m, MetronomeSpec& mt) {
  const Reader p = m.map("pendulum", "mass, length and damping or decay_rate");
  mt.pendulum_mass_kg = positive(p, "mass", "kg");
  mt.length_m = positive(p, "length", "m, pivot to centre of mass");
  const double point_inertia = mt.pendulum_mass_kg * mt.length_m * mt.length_m;
  mt.inertia_kgm2 = point_inertia;
  if (auto I = p.optNumber("inertia")) {
    if (!(*I >= point_inertia * (1.0 - kInertiaSlack)))
      p.bad("inertia", "must be >= mass * length^2 = " + numberText(point_inertia) +
                           " (parallel-axis theorem)");
    mt.inertia_kgm2 = std::max(*I, point_inertia);
  }
  const bool has_damping = p.has("damping"), has_decay = p.has("decay_rate");
  if (has_damping && has_decay) p.bad("decay_rate", "give damping or decay_rate, not both");
  if (!has_damping && !has_decay)
    p.missing("damping", "nu-bar in kg/s, or decay_rate in 1/s; damping: 0 for none");
  if (has_damping) {
    mt.damping_kg_s = nonNegative(p, "damping", *p.optNumber("damping"));
  } else {
    // theta-bar'' + (nu-bar L^2 / I) theta-bar' + ...: the amplitude decays at rate
    // nu-bar L^2 / (2 I) (paper s3, beta = nu-bar / 2m for I = m L^2)
    const double rate = nonNegative(p, "decay_rate", *p.optNumber("decay_rate"));
    mt.damping_kg_s = 2.0 * rate * mt.inertia_kgm2 / (mt.length_m * mt.length_m);
  }
  // the air's drag on the swinging pendulum: torque -air_drag thetadot |thetadot| (N m s^2)
  if (auto d = p.optNumber("air_drag")) mt.air_drag_Nms2 = nonNegative(p, "air_drag", *d);
}

// escapement: critical angle and impulse, or a steady amplitude that sets the impulse later
// (`amplitude` keeps its reader until the scaled parameters are known)
void readPhysicalEscapement(const Reader& m, MetronomeSpec& mt, std::optional<Reader>& amplitude) {
  if (auto e = m.optMap("escapement")) {
    mt.theta_c_rad = e->number("angle", "rad, the critical angle theta_c");
    if (!(mt.theta_c_rad > 0 && mt.theta_c_rad < kPi)) e->bad("angle", "must be in (0, pi)");
    const bool has_impulse = e->has("impulse"), has_amplitude = e->has("steady_amplitude");
    if (has_impulse && has_amplitude)
      e->bad("steady_amplitude", "give impulse or steady_amplitude, not both");
    if (!has_impulse && !has_amplitude)
      e->missing("impulse", "N m s per tick, or steady_amplitude in rad");
    if (has_impulse) {
      mt.impulse_Nms = nonNegative(*e, "impulse", *e->optNumber("impulse"));
    } else {
      // eq. A_star: A_star is the stable amplitude only if A_star >= sqrt(2) theta_c
      const double A = *e->optNumber("steady_amplitude");
      const double lowest = std::sqrt(2.0) * mt.theta_c_rad;
      if (!(A >= lowest && A < kPi))
        e->bad("steady_amplitude",
               "must be in [sqrt(2) * angle, pi) = [" + numberText(lowest) +
                   ", 3.14159) (below sqrt(2) * angle no impulse makes it the stable amplitude)");
      if (!(mt.damping_kg_s > 0))
        e->bad("steady_amplitude",
               "needs damping > 0 (an undamped pendulum has no steady amplitude)");
      amplitude = *e;
    }
  }
}

// steady_amplitude -> J by eq. J_estimate with the metronome's own scaled nu_i, theta_c,i,
// then J-bar_i = eps J_i I_i sqrt(eps) omega0. With air drag the loss at the steady amplitude A
// is the linear damping's and the drag's: over a swing of the pendulum (thetadot^2 = 2 w^2 (cos
// theta - cos A), w its own small-swing frequency) the drag takes d oint |thetadot|^3 dt =
// 8 d w^2 (sin A - A cos A), what a linear damper b' takes of a harmonic swing (pi b' w A^2) when
// b' = 8 d w (sin A - A cos A) / (pi A^2): a decay rate beta_d = b' / (2 I), so nu_i gets
// 2 beta_d / (eps omega0) added (nu = 2 beta / (eps omega0); for small A, beta_d = 4 d w A /
// (3 pi I), the free decay's rate at A).
double dragNu(const MetronomeSpec& mt, double A_rad, double gravity, const ScaledParams& sp) {
  if (!(mt.air_drag_Nms2 > 0)) return 0.0;
  const double I = mt.inertia_kgm2;
  const double w = std::sqrt(mt.pendulum_mass_kg * gravity * mt.length_m / I);
  const double swing = std::sin(A_rad) - A_rad * std::cos(A_rad);
  const double beta_d = 4.0 * mt.air_drag_Nms2 * w * swing / (kPi * I * A_rad * A_rad);
  return 2.0 * beta_d * sp.time_scale_s / sp.epsilon;
}

void impulsesFromSteadyAmplitudes(Rig& rig,
                                  const std::vector<std::optional<Reader>>& amplitude_of) {
  const ScaledParams sp = computeScaled(rig);
  for (std::size_t i = 0; i < rig.metronomes.size(); ++i) {
    if (!amplitude_of[i]) continue;
    const Reader& e = *amplitude_of[i];
    const double A = *e.optNumber("steady_amplitude") / sp.angle_scale;
    double J = 0.0;
    try {
      const double nu = sp.nu[i] + dragNu(rig.metronomes[i], *e.optNumber("steady_amplitude"),
                                          rig.gravity_m_s2, sp);
      J = impulseForAmplitude(nu, A, sp.theta_c[i]);
    } catch (const std::invalid_argument& err) {
      e.bad("steady_amplitude", err.what());
    }
    MetronomeSpec& mt = rig.metronomes[i];
    mt.impulse_Nms = sp.epsilon * sp.angle_scale * J * mt.inertia_kgm2 / sp.time_scale_s;
  }
}

}  // namespace

Rig buildPhysical(const Node& root, const Source& src, const std::string& fallback_name,
                  const std::string& platform_path, const std::string& metronomes_path) {
  const Reader top(root, "", src);
  Rig rig;
  rig.units = Units::Physical;
  rig.name = readName(top, fallback_name);
  if (auto g = top.optNumber("gravity")) {
    if (!(*g > 0)) top.bad("gravity", "must be > 0");
    rig.gravity_m_s2 = *g;
  }

  // platform
  if (!top.has("platform")) top.missing("platform", "the board's mass and its friction law");
  const Reader platform(*top.find("platform"), platform_path, src);
  rig.platform.mass_kg = positive(platform, "mass", "the board's mass in kg");
  rig.platform.friction = readFriction(platform, Units::Physical);
  if (auto spring = platform.optMap("spring"))
    rig.platform.spring_N_m = nonNegative(*spring, "k", spring->number("k", "N/m"));
  readPlatformStart(top, rig.platform.start_x_m, rig.platform.start_v_m_s);

  // metronomes; a steady_amplitude becomes an impulse once the scaled parameters are known
  const Node& list =
      readMetronomeList(top, metronomes_path, "a list of metronomes, each with box_mass, pendulum");
  std::vector<std::optional<Reader>> amplitude_of(list.seq.size());
  for (std::size_t i = 0; i < list.seq.size(); ++i) {
    const Reader m(list.seq[i], metronomes_path + "." + std::to_string(i), src);
    MetronomeSpec mt;
    mt.name = optName(m).value_or(std::to_string(i + 1));
    // a mass, > 0 (SPEC 1c): a massless box would leave its pendulum's pivot without inertia
    mt.box_mass_kg = positive(m, "box_mass", "kg, the metronome without its pendulum");

    readPhysicalPendulum(m, mt);
    readPhysicalEscapement(m, mt, amplitude_of[i]);

    if (auto s = m.optMap("start")) {
      mt.start_angle_rad = s->optNumber("angle").value_or(0.0);
      mt.start_rate_rad_s = s->optNumber("rate").value_or(0.0);
    }
    mt.locked = m.optBool("locked").value_or(false);
    rig.metronomes.push_back(mt);
  }

  readSimulation(top, "duration", "s", rig.sim.t_end_s, rig.sim.accuracy, rig.sim.integrator,
                 rig.sim.sample_s);

  impulsesFromSteadyAmplitudes(rig, amplitude_of);
  return rig;
}

Rig buildScaled(const Node& root, const Source& src, const std::string& fallback_name) {
  const Reader top(root, "", src);
  ScaledRigInput in;
  in.name = readName(top, fallback_name);
  in.epsilon = top.number("epsilon", "the small parameter m1^2 L1^2 / (I1 M), in (0, 1)");
  if (!(in.epsilon > 0 && in.epsilon < 1)) top.bad("epsilon", "must be in (0, 1)");
  const double eps = in.epsilon;

  const Reader platform = top.map("platform", "its friction law");
  in.friction = readFriction(platform, Units::Scaled);
  readPlatformStart(top, in.x0, in.xdot0);

  const Node& list =
      readMetronomeList(top, "metronomes", "a list of metronomes, each with nu, J, theta_c");
  // the escapement angle theta-bar_c = sqrt(eps) theta_c must be a physical angle in (0, pi)
  const double theta_c_max = kPi / std::sqrt(eps);
  for (std::size_t i = 0; i < list.seq.size(); ++i) {
    const Reader m(list.seq[i], "metronomes." + std::to_string(i), src);
    ScaledMetronomeInput mt;
    mt.name = optName(m).value_or(std::to_string(i + 1));
    mt.nu = nonNegative(m, "nu", m.number("nu", "scaled pendulum damping, >= 0"));
    mt.J = nonNegative(m, "J", m.number("J", "scaled escapement impulse, >= 0"));
    mt.theta_c = m.number("theta_c", "scaled critical angle of the escapement");
    if (!(mt.theta_c > 0 && mt.theta_c < theta_c_max))
      m.bad("theta_c", "must be in (0, pi / sqrt(epsilon)) = (0, " + numberText(theta_c_max) +
                           ") (the angle sqrt(epsilon) theta_c must be in (0, pi))");
    for (const char* key : {"alpha", "zeta"}) {
      const std::optional<double> v = m.optNumber(key);
      if (!v) continue;
      if (i == 0 && *v != 0.0)
        m.bad(key, "must be 0: metronome 1 is the reference (alpha and zeta are 0 by definition)");
      // 1 + eps alpha = (its frequency / metronome 1's)^2 and 1 + eps zeta = m L / (m1 L1)
      if (!(1.0 + eps * *v > 0))
        m.bad(key, "must be > -1 / epsilon = " + numberText(-1.0 / eps) + " (1 + epsilon " + key +
                       " must be > 0)");
      (std::string(key) == "alpha" ? mt.alpha : mt.zeta) = *v;
    }
    if (auto s = m.optMap("start")) {
      const bool polar = s->has("A") || s->has("phi");
      if (polar) {
        for (const char* key : {"theta", "thetadot"})
          s->forbid(key, "give start as {A, phi} or as {theta, thetadot}, not both");
        const double A = s->number("A", "scaled amplitude, with phi");
        if (!(A >= 0)) s->bad("A", "must be >= 0");
        const double phi = s->number("phi", "phase in rad, with A");
        mt.theta0 = A * std::sin(phi);  // theta = A sin phi, thetadot = A cos phi
        mt.thetadot0 = A * std::cos(phi);
      } else {
        mt.theta0 = s->optNumber("theta").value_or(0.0);
        mt.thetadot0 = s->optNumber("thetadot").value_or(0.0);
      }
    }
    in.metronomes.push_back(mt);
  }

  readSimulation(top, "tau", "slow time; the fast time runs to t = tau / epsilon", in.tau_end,
                 in.accuracy, in.integrator, in.sample);

  try {
    return rigFromScaled(in);
  } catch (const std::invalid_argument& err) {
    top.bad("epsilon", err.what());
  }
}

}  // namespace metrosync::rigfile
