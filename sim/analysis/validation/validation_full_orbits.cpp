#include "sim/analysis/validation/validation_full_orbits.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "base/number_text.h"
#include "sim/analysis/periodic_orbit/full_continuation.h"
#include "sim/analysis/periodic_orbit/orbit_continuation.h"
#include "sim/analysis/validation/validation_bifurcations.h"
#include "sim/analysis/validation/validation_measures.h"
#include "sim/parallel/worker_pool.h"

namespace metrosync {

namespace {

using orbit::Family;
using orbit::OrbitBifurcation;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The default rig's state is followed in epsilon down to this (its near-antiphase remnant of the
// slow flow's neutral family is then within ~0.03 of the slow flow's state) and in mu up to this.
constexpr double kEpsLow = 0.005;
constexpr double kMuHigh = 0.5;
// the exact antiphase orbit's family is followed a little further down in epsilon
constexpr double kAntiphaseEpsLow = 0.004;

// The rig of the scenario's scaled parameters with the key at p, at epsilon.
std::function<Rig(double)> rigsOf(const ScaledParams& q, const std::string& name, double epsilon,
                                  const std::function<void(ScaledParams&, double)>& set) {
  return [=](double p) {
    ScaledParams r = q;
    set(r, p);
    return rigAtEpsilon(r, name, epsilon, r.tau_end);
  };
}

const orbit::FamilyPoint& pointAt(const Family& f, double p) {
  const orbit::FamilyPoint* best = &f.points.front();
  for (const orbit::FamilyPoint& q : f.points)
    if (std::abs(q.p - p) < std::abs(best->p - p)) best = &q;
  return *best;
}

// A metronome of the family's orbit at p swings below its escapement angle.
bool isSuppressed(const Family& f, double p, const ScaledParams& q) {
  const std::vector<double>& A = pointAt(f, p).measures.A;
  for (size_t i = 0; i < A.size() && i < q.theta_c.size(); ++i)
    if (A[i] < q.theta_c[i]) return true;
  return false;
}

struct FamilyRun {
  bool found = false;
  Family family;
  std::string note;
};

// The family of `spec` at epsilon, from the first start that settles onto an orbit.
FamilyRun familyAt(const FullFamilySpec& spec, const ScaledParams& q, double epsilon) {
  orbit::OrbitProblem prob;
  prob.rig_at = rigsOf(q, spec.scenario, epsilon, spec.set);
  FamilyRun out;
  for (double start : spec.starts) {
    try {
      const orbit::SettledOrbit st = orbit::settleOrbit(prob.rig_at(start), prob.ret, prob.newton);
      prob.pendulum = st.pendulum;
      orbit::FamilySettings s;
      s.p_min = std::min(spec.lo, start), s.p_max = spec.hi;
      out.family = orbit::continueFamily(prob, st.orbit, start, s);
      if (spec.suppressed && !isSuppressed(out.family, start, q)) {
        out.note += (out.note.empty() ? "" : "; ") + spec.key + " = " + numberText(start) +
                    ": the rig's start settles onto a state with every metronome ticking";
        continue;
      }
      out.found = true;
      const std::vector<double>& A = pointAt(out.family, start).measures.A;
      out.note =
          "from the rig's start settled at " + spec.key + " = " + numberText(start) + " (A =";
      for (double a : A) out.note += " " + numberText(a);
      out.note += ")";
      return out;
    } catch (const std::exception& e) {
      out.note +=
          (out.note.empty() ? "" : "; ") + spec.key + " = " + numberText(start) + ": " + e.what();
    }
  }
  return out;
}

// The slow flow's located points of the family (part 6's machinery, without full-model brackets).
std::vector<LocatedPoint> slowPoints(const FullFamilySpec& spec,
                                     const std::vector<Scenario>& scenarios,
                                     const ValidationEngines& engines) {
  BifurcationFamilySpec b;
  b.name = spec.name, b.scenario = spec.scenario, b.key = spec.key, b.set = spec.set;
  b.start = spec.slow_start, b.lo = spec.slow_lo, b.hi = spec.slow_hi;
  return runBifurcationFamilies({b}, scenarios, engines, 1).at(0).points;
}

// The special point of `type` on the family nearest to `near`.
const OrbitBifurcation* nearest(const Family& f, const std::string& type, double near) {
  const OrbitBifurcation* best = nullptr;
  for (const OrbitBifurcation& b : f.special)
    if (b.type == type && (!best || std::abs(b.point.p - near) < std::abs(best->point.p - near)))
      best = &b;
  return best;
}

void fit(FullPointSeries& s) {
  std::vector<double> x, y;
  for (const FullPointValue& v : s.values)
    if (std::isfinite(v.value) && v.value != s.slow) {
      x.push_back(v.epsilon);
      y.push_back(std::abs(v.value - s.slow));
    }
  if (x.size() >= 2) s.order = fitOrder(x, y);
  double smallest = kNaN;
  for (const FullPointValue& v : s.values)
    if (std::isfinite(v.value) && !(v.epsilon >= smallest)) {
      smallest = v.epsilon;
      s.constant = (v.value - s.slow) / v.epsilon;
    }
  s.checked = x.size() >= 2;
  s.pass = !s.checked || (s.order >= kOrderLo && s.order <= kOrderHi);
}

std::vector<FullPointSeries> seriesOf(const FullFamilySpec& spec,
                                      const std::vector<LocatedPoint>& slow,
                                      const std::vector<double>& eps,
                                      const std::vector<FamilyRun>& runs) {
  std::vector<FullPointSeries> out;
  for (const auto& [full_type, slow_type] : spec.points) {
    FullPointSeries s;
    s.family = spec.name, s.key = spec.key, s.full_type = full_type, s.slow_type = slow_type;
    // the slow flow's point of that type that loses or gains a stable state, else the first
    for (const LocatedPoint& p : slow)
      if (p.type == slow_type && (!std::isfinite(s.slow) || p.checked)) s.slow = p.value;
    for (size_t e = 0; e < eps.size(); ++e) {
      FullPointValue v;
      v.epsilon = eps[e];
      v.note = runs[e].note;
      if (const OrbitBifurcation* b =
              runs[e].found ? nearest(runs[e].family, full_type, s.slow) : nullptr) {
        v.value = b->point.p, v.A = b->point.measures.A, v.psi = b->point.measures.psi;
      } else if (runs[e].found) {
        v.note += "; no " + full_type + " on " + numberText(spec.lo) + " .. " +
                  numberText(spec.hi) + " (" + runs[e].family.end_backward + "; " +
                  runs[e].family.end_forward + ")";
      }
      s.values.push_back(v);
    }
    fit(s);
    out.push_back(s);
  }
  return out;
}

}  // namespace

std::vector<FullFamilySpec> paperFullFamilies() {
  auto mu = [](ScaledParams& p, double v) { p.friction = p.friction.with("mu", v); };
  auto alpha = [](ScaledParams& p, double v) { p.alpha.at(1) = v; };
  std::vector<FullFamilySpec> f(3);
  f[0] = {"f4.3 in mu",
          "f4.3-mu0.2",
          "platform.friction.mu",
          mu,
          {0.2},
          0.2,
          0.32,
          0.2,
          0.2,
          0.4,
          {{"torus", "hopf"}, {"fold", "fold"}}};
  f[1] = {"f4.4 in alpha, near antiphase",
          "f4.4-alpha0.2",
          "metronomes.1.alpha",
          alpha,
          {0.2},
          0.2,
          2.5,
          0.2,
          0.2,
          2.5,
          {{"torus", "hopf"}}};
  // the suppressed state's fold moves down by ~40 epsilon (3.52 at 0.01): started lower at larger
  // epsilon, where the rig's start settles onto it
  f[2] = {"f4.4 in alpha, suppressed",
          "f4.4-alpha4",
          "metronomes.1.alpha",
          alpha,
          {3.0, 1.5, 0.5},
          0.0,
          4.5,
          3.0,
          2.5,
          4.5,
          {{"fold", "fold"}}};
  f[2].suppressed = true;
  return f;
}

namespace {

// The family through the orbit the rig's start settles to at p0 (over [lo, hi]).
Family settledFamily(const std::function<Rig(double)>& rig_at, double p0, double lo, double hi,
                     std::string& how) {
  orbit::OrbitProblem prob;
  prob.rig_at = rig_at;
  const orbit::SettledOrbit st = orbit::settleOrbit(rig_at(p0), prob.ret, prob.newton);
  prob.pendulum = st.pendulum;
  how = st.how;
  orbit::FamilySettings s;
  s.p_min = lo, s.p_max = hi;
  return orbit::continueFamily(prob, st.orbit, p0, s);
}

// The default rig's state in epsilon (and mu), and the exact antiphase orbit's branch point.
void asymmetricState(const std::vector<Scenario>& scenarios, bool quick, AsymmetricState& a) {
  const Scenario& sc = findScenario(scenarios, "experiment-low-friction-antiphase");
  const ScaledParams q = sc.scaled;
  const std::string name = sc.spec.name;
  a.scenario = name, a.epsilon = q.epsilon, a.mu = q.friction.valueOr("mu", 0.0),
  a.eps_lo = kEpsLow;
  const ModelRun slow = runSlowModel(q, q.epsilon, q.tau_end);
  a.A_slow = slow.final().A, a.psi_slow = slow.final().psi;
  auto atEps = [&](const ScaledParams& base) {
    return [base, name](double eps) { return rigAtEpsilon(base, name, eps, base.tau_end); };
  };
  try {
    const Family f = settledFamily(atEps(q), q.epsilon, kEpsLow, q.epsilon, a.start);
    const orbit::FamilyPoint& at = pointAt(f, q.epsilon);
    a.A = at.measures.A, a.psi = at.measures.psi, a.max_multiplier = at.orbit.maxModulus();
    for (const OrbitBifurcation& b : f.special)
      if (b.type == "fold")
        a.eps_folds.push_back(
            {b.point.p, b.point.measures.A, b.point.measures.psi, b.stability_changes});
    const orbit::FamilyPoint& lo = pointAt(f, kEpsLow);
    a.A_lo = lo.measures.A, a.psi_lo = lo.measures.psi;
    a.eps_ends = f.end_backward + "; " + f.end_forward;
    if (!quick) {
      std::string how;
      const Family m = settledFamily(
          rigsOf(q, name, q.epsilon,
                 [](ScaledParams& p, double v) { p.friction = p.friction.with("mu", v); }),
          a.mu, 0.0, kMuHigh, how);
      a.mu_from = m.points.front().p, a.mu_to = m.points.back().p;
      a.mu_ends = m.end_backward + "; " + m.end_forward;
      for (const OrbitBifurcation& b : m.special)
        a.mu_specials.push_back(b.type + " at mu = " + numberText(b.point.p));
    }
  } catch (const std::exception& e) {
    a.start = e.what();
  }
  // exactly in antiphase: theta = 0, thetadot = +-A for both (the platform never moves)
  ScaledParams anti = q;
  anti.theta0 = {0.0, 0.0};
  anti.thetadot0 = {q.thetadot0.empty() ? 2.9 : std::hypot(q.theta0[0], q.thetadot0[0]), 0.0};
  anti.thetadot0[1] = -anti.thetadot0[0];
  anti.x0 = anti.xdot0 = 0.0;
  try {
    std::string how;
    const Family f = settledFamily(atEps(anti), q.epsilon, kAntiphaseEpsLow, q.epsilon, how);
    a.antiphase_multiplier = pointAt(f, q.epsilon).orbit.maxModulus();
    for (const OrbitBifurcation& b : f.special)
      if (b.type == "branch") a.antiphase_branch = b.point.p;
  } catch (const std::exception&) {
  }
}

}  // namespace

FullOrbitsResult runFullOrbitBifurcations(bool quick, const std::vector<Scenario>& scenarios,
                                          const ValidationEngines& engines, int jobs) {
  const auto t0 = std::chrono::steady_clock::now();
  FullOrbitsResult res;
  res.epsilons =
      quick ? std::vector<double>{0.073, 0.02} : std::vector<double>{0.073, 0.04, 0.02, 0.01};
  const std::vector<FullFamilySpec> specs = paperFullFamilies();
  std::vector<std::vector<LocatedPoint>> slow;
  for (const FullFamilySpec& f : specs) slow.push_back(slowPoints(f, scenarios, engines));
  // every (family, epsilon) and the default rig's state, on one pool
  const size_t ne = res.epsilons.size();
  std::vector<std::vector<FamilyRun>> runs(specs.size(), std::vector<FamilyRun>(ne));
  parallelFor(static_cast<long>(specs.size() * ne + 1), jobs, [&](long kl) {
    const size_t k = static_cast<size_t>(kl);
    if (k == specs.size() * ne) return asymmetricState(scenarios, quick, res.asymmetric);
    const FullFamilySpec& f = specs[k / ne];
    runs[k / ne][k % ne] =
        familyAt(f, findScenario(scenarios, f.scenario).scaled, res.epsilons[k % ne]);
  });
  for (size_t f = 0; f < specs.size(); ++f)
    for (FullPointSeries& s : seriesOf(specs[f], slow[f], res.epsilons, runs[f]))
      res.series.push_back(std::move(s));
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

int FullOrbitsResult::failed() const {
  int n = 0;
  for (const FullPointSeries& s : series) n += s.checked && !s.pass;
  return n;
}

}  // namespace metrosync
