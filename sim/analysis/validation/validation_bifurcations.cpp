#include "sim/analysis/validation/validation_bifurcations.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <stdexcept>

#include "base/number_text.h"
#include "sim/analysis/continuation/arclength.h"
#include "sim/analysis/continuation/start_states.h"
#include "sim/analysis/validation/validation_measures.h"
#include "sim/parallel/worker_pool.h"

namespace metrosync {

namespace {

using namespace continuation;
using Cd = std::complex<double>;

// The side checks: runs this long in tau (the slow passage past a fold takes ~100), from the locked
// state perturbed by this (relative, and in phase), at the point +- kSideOffset of the range.
constexpr double kCheckTau = 1000.0;
constexpr double kCheckPerturbation = 1e-3;
constexpr double kSideOffset = 0.01;

EnvelopeRow rowOf(const SlowFlowProblem& prob, const Vec& x) {
  EnvelopeRow r;
  r.A = prob.amplitudes(x);
  r.psi = prob.phaseDifferences(x);
  return r;
}

// A slow-flow run from the locked state x (perturbed) at parameter v, against x.
SideCheck sideCheck(const SlowFlowProblem& prob, const ParamsAt& at, const Vec& x, double v) {
  SideCheck c;
  c.value = v;
  std::vector<Cd> z = prob.unpack(x);
  for (size_t i = 0; i < z.size(); ++i)
    z[i] *= std::polar(1.0 + kCheckPerturbation, i == 0 ? 0.0 : kCheckPerturbation);
  ScaledParams q = at(v);
  for (size_t i = 0; i < z.size(); ++i) q.thetadot0[i] = z[i].real(), q.theta0[i] = z[i].imag();
  const ModelRun run = runSlowModel(q, q.epsilon, kCheckTau);
  c.distance = run.report.complete ? envelopeDistance(run.final(), rowOf(prob, x)) : INFINITY;
  c.persists = c.distance <= kPersistDistance;
  return c;
}

// Whether the branch is stable next to `at` on either side (its nearest points along the branch).
bool stableNextTo(const Branch& b, const BranchPoint& at) {
  size_t k = 0;
  for (size_t i = 1; i < b.points.size(); ++i)
    if ((b.points[i].y - at.y).norm() < (b.points[k].y - at.y).norm()) k = i;
  for (size_t i = k > 0 ? k - 1 : 0; i <= k + 1 && i < b.points.size(); ++i)
    if (b.points[i].stable) return true;
  return false;
}

// The located folds and Hopf points of the family's branch, each with its side checks.
void locate(const BifurcationFamilySpec& spec, const ParamsAt& at, BifurcationFamilyResult& out) {
  const ScaledParams p0 = at(spec.start);
  const SettledState st = settleFromStart(p0, p0.tau_end > 0 ? p0.tau_end : 300.0);
  if (!st.settled) {
    out.start = "the rig's start does not settle at " + spec.key + " = " + numberText(spec.start) +
                ": " + st.why;
    return;
  }
  int ref = 0;
  for (size_t i = 1; i < st.z.size(); ++i)
    if (std::abs(st.z[i]) > std::abs(st.z[ref])) ref = static_cast<int>(i);
  const SlowFlowProblem prob(at, spec.start, ref);
  const auto x = solveLocked(prob, prob.pack(st.z, prob.omegaGuess(spec.start, st.z)), spec.start);
  if (!x) {
    out.start = "Newton does not converge on the settled state";
    return;
  }
  out.start = "the rig's start settled by the slow flow at tau = " + numberText(st.tau);
  ContinuationSettings s;
  s.p_min = spec.lo, s.p_max = spec.hi, s.max_branches = 1;
  s.step = (spec.hi - spec.lo) / 100, s.step_max = (spec.hi - spec.lo) / 25;
  const double offset = kSideOffset * (spec.hi - spec.lo);
  const std::vector<Branch> branches = continueFrom(prob.system(), *x, spec.start, s);
  for (const Bifurcation& e : branches.at(0).special) {
    if (e.type != BifurcationType::Fold && e.type != BifurcationType::Hopf) continue;
    LocatedPoint pt;
    pt.type = toString(e.type);
    pt.value = e.point.p();
    const Vec xe = e.point.y.head(prob.system().n);
    pt.A = prob.amplitudes(xe), pt.psi = prob.phaseDifferences(xe), pt.detail = e.detail;
    pt.checked = stableNextTo(branches[0], e.point);
    pt.below = sideCheck(prob, at, xe, pt.value - offset);
    pt.above = sideCheck(prob, at, xe, pt.value + offset);
    pt.pass = !pt.checked || pt.below.persists != pt.above.persists;
    out.points.push_back(pt);
  }
}

// The bracket's grids, one full-model run per value (the rig's start), then the first change.
void bracket(const BifurcationFamilySpec& spec, const ParamsAt& at,
             const ValidationEngines& engines, int jobs, BifurcationFamilyResult& out) {
  struct Job {
    size_t point, eps, k;
  };
  std::vector<Job> jobs_list;
  out.full.assign(out.points.size(), {});
  for (size_t i = 0; i < out.points.size(); ++i)
    for (size_t e = 0; e < spec.full_epsilons.size(); ++e) {
      FullBracket b;
      b.epsilon = spec.full_epsilons[e];
      for (int k = 0; k < spec.full_points; ++k) {
        const double w = spec.full_points > 1 ? double(k) / (spec.full_points - 1) : 0.5;
        b.values.push_back(out.points[i].value + spec.full_halfwidth * (2 * w - 1));
        jobs_list.push_back({i, e, static_cast<size_t>(k)});
      }
      b.regimes.assign(b.values.size(), "");
      out.full[i].push_back(b);
    }
  parallelFor(static_cast<long>(jobs_list.size()), jobs, [&](long j) {
    const Job& job = jobs_list[j];
    FullBracket& b = out.full[job.point][job.eps];
    const ScaledParams q = at(b.values[job.k]);
    const ModelRun run = runFullModelAt(engines, q, spec.scenario, b.epsilon, q.tau_end);
    b.regimes[job.k] = run.report.complete ? toString(run.verdict.regime) : "failed";
  });
  for (auto& per_point : out.full)
    for (FullBracket& b : per_point)
      for (size_t k = 1; k < b.values.size(); ++k)
        if (b.regimes[k] != b.regimes[k - 1]) {
          b.lo = b.values[k - 1], b.hi = b.values[k];
          break;
        }
}

}  // namespace

std::vector<BifurcationFamilySpec> paperBifurcationFamilies(bool quick) {
  const std::vector<double> eps =
      quick ? std::vector<double>{0.073} : std::vector<double>{0.073, 0.02};
  const int points = quick ? 5 : 9;
  BifurcationFamilySpec mu;
  mu.name = "f4.3 in mu";
  mu.scenario = "f4.3-mu0.2";
  mu.key = "platform.friction.mu";
  mu.set = [](ScaledParams& p, double v) { p.friction = p.friction.with("mu", v); };
  mu.start = 0.2, mu.lo = 0.1, mu.hi = 0.5;
  mu.full_epsilons = eps, mu.full_points = points, mu.full_halfwidth = 0.08;
  mu.meaning =
      "The in-phase state of f4.3 (mu = 0.2) loses its stability at a subcritical Hopf point "
      "between the paper's mu = 0.2 (in-phase) and mu = 0.3 (suppression near antiphase): past it "
      "the pair leaves in-phase for the states the paper shows at mu = 0.3 and 0.4.";
  BifurcationFamilySpec alpha;
  alpha.name = "f4.4 in alpha";
  alpha.scenario = "f4.4-alpha4";
  alpha.key = "metronomes.1.alpha";
  alpha.set = [](ScaledParams& p, double v) { p.alpha.at(1) = v; };
  alpha.start = 3.0, alpha.lo = 2.5, alpha.hi = 4.5;
  alpha.full_epsilons = eps, alpha.full_points = points, alpha.full_halfwidth = 0.3;
  alpha.meaning =
      "Metronome 2's suppressed state (A_2 below theta_c, psi near pi) dies in a saddle-node "
      "(fold) just below the paper's alpha = 4: at alpha = 4 no locked state is left, but the flow "
      "is slow where the pair of states vanished, which is the paper's long suppression before "
      "death (the slow passage takes ~ pi / sqrt(a (alpha - alpha_fold)) in tau).";
  return {mu, alpha};
}

std::vector<BifurcationFamilyResult> runBifurcationFamilies(
    const std::vector<BifurcationFamilySpec>& families, const std::vector<Scenario>& scenarios,
    const ValidationEngines& engines, int jobs) {
  std::vector<BifurcationFamilyResult> out;
  for (const BifurcationFamilySpec& spec : families) {
    BifurcationFamilyResult r;
    r.spec = spec;
    const ScaledParams base = findScenario(scenarios, spec.scenario).scaled;
    const ParamsAt at = [base, set = spec.set](double v) {
      ScaledParams q = base;
      set(q, v);
      return q;
    };
    locate(spec, at, r);
    if (engines.full_model) bracket(spec, at, engines, jobs, r);
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace metrosync
