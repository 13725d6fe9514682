#include "tools/report/validation_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/constants.h"
#include "base/number_text.h"
#include "contact/averaged_response.h"
#include "sim/engines/slow_flow/slow_flow_engine.h"
#include "tools/report/json_file.h"
#include "tools/report/plot.h"
#include "tools/report/validation_bifurcations_report.h"
#include "tools/report/validation_experiments_report.h"
#include "tools/report/validation_full_orbits_report.h"

namespace metrosync {

namespace {

// a number for a table: fixed for O(1) values, scientific for tiny or huge ones
std::string tableNumber(double v, int digits = 3) {
  if (!std::isfinite(v)) return "–";
  const double a = std::abs(v);
  if (a != 0 && (a < 1e-3 || a >= 1e5))
    return numberText(v, std::max(digits - 1, 0), Notation::Scientific);
  return numberText(v, digits, Notation::Fixed);
}

std::string sci(double v, int digits = 1) {
  if (!std::isfinite(v)) return "–";
  return numberText(v, digits, Notation::Scientific);
}

std::string duration(double seconds) {
  if (seconds < 120) return numberText(seconds, 0, Notation::Fixed) + " s";
  return numberText(seconds / 60, 1, Notation::Fixed) + " min";
}

// a markdown table cell: a '|' would end the cell
std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

// 1e-07 -> 1e-7
std::string shortSci(double v) {
  std::string s = numberText(v, 0, Notation::Scientific);
  const size_t e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mant = s.substr(0, e), ex = s.substr(e + 1);
  const bool neg = !ex.empty() && ex[0] == '-';
  size_t k = (!ex.empty() && (ex[0] == '-' || ex[0] == '+')) ? 1 : 0;
  while (k + 1 < ex.size() && ex[k] == '0') ++k;
  return mant + "e" + (neg ? "-" : "") + ex.substr(k);
}

std::string passText(bool pass) {
  return pass ? "pass" : "**FAIL**";
}

std::string epsLabel(double eps) {
  return numberText(eps, 4);
}

// "A = 1.43, 0.67; ψ = 3.32" for a final envelope row
std::string stateText(const EnvelopeRow& f) {
  if (f.A.empty()) return "no state";
  std::string s = "A = ";
  for (size_t i = 0; i < f.A.size(); ++i) s += (i ? ", " : "") + tableNumber(f.A[i], 2);
  if (!f.psi.empty()) {
    s += "; ψ = ";
    for (size_t j = 0; j < f.psi.size(); ++j) s += (j ? ", " : "") + tableNumber(f.psi[j], 2);
  }
  return s;
}

std::string regimeText(const ModelRun& r) {
  if (!r.report.complete) return "failed: " + r.report.failure;
  return toString(r.verdict.regime);
}

double regimeEps(const RegimeComparison& rc, size_t k) {
  return k < rc.full.size() ? rc.full[k].epsilon : 0.0;
}

// ---- gnuplot --------------------------------------------------------------------------------

const char* const kColours[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00", "#56b4e9",
                                "#000000", "#f0e442", "#7f7f7f", "#8c564b", "#1f77b4", "#bcbd22"};

std::string header(const std::string& png, const char* size = "720,430") {
  return std::string("set terminal pngcairo size ") + size +
         " enhanced font 'sans,10' linewidth 1.1\nset output " + gnuplotQuote(png) +
         "\nset grid back lt 1 lw 0.8 lc rgb '#e4e4e4'\nset datafile missing 'nan'\n";
}

bool plotBetas(const OutputDir& dir, const ValidationResults& r) {
  if (r.betas.empty()) return false;
  std::ostringstream d;
  // block 0: the closed forms on a fine grid; block 1: the element's measurements
  const int n = 600;
  for (int k = 0; k <= n; ++k) {
    const double s = 0.5 * std::pow(20.0, static_cast<double>(k) / n);
    d << numberText(s, 10) << ' ' << numberText(coulombBeta1(s), 12) << ' '
      << numberText(coulombBeta2(s), 12) << '\n';
  }
  d << "\n\n";
  for (const auto& b : r.betas)
    d << numberText(b.s, 12) << ' ' << numberText(b.measured.beta1, 12) << ' '
      << numberText(b.measured.beta2, 12) << '\n';
  return drawPng(dir, "betas.png", d.str(), [](const std::string& data, const std::string& png) {
    std::ostringstream s;
    s << header(png) << "set logscale x\nset xrange [0.5:10]\nset xtics (0.5,1,2,3,5,10)\n"
      << "set xlabel 's = A/μ (drive over friction bound)'\nset ylabel 'β'\n"
      << "set key left top\nset title 'β_1, β_2: closed forms (eq. d2, lines) and the full "
         "model''s Coulomb element (points)'\n"
      << "set arrow from 1, graph 0 to 1, graph 1 nohead dt 3 lc rgb '#555555'\n"
      << "set arrow from " << numberText(kCoulombSlipThreshold, 10) << ", graph 0 to "
      << numberText(kCoulombSlipThreshold, 10) << ", graph 1 nohead dt 3 lc rgb '#555555'\n"
      << "plot " << gnuplotQuote(data) << " index 0 using 1:2 with lines lw 2 lc rgb '"
      << kColours[0] << "' title 'β_1 (d2)', '' index 0 using 1:3 with lines lw 2 lc rgb '"
      << kColours[1]
      << "' title 'β_2 (d2)', '' index 1 using 1:2 with points pt 6 ps 1.1 lc rgb '#000000'"
      << " title 'β_1 element', '' index 1 using 1:3 with points pt 4 ps 1.1 lc rgb '#000000'"
      << " title 'β_2 element'\nset output\n";
    return s.str();
  });
}

bool plotConvergence(const OutputDir& dir, const ValidationResults& r) {
  if (r.convergence.empty()) return false;
  std::ostringstream d;
  for (size_t c = 0; c < r.convergence.size(); ++c) {
    if (c) d << "\n\n";
    const auto& cv = r.convergence[c];
    for (size_t k = 0; k < cv.eps.size(); ++k)
      d << numberText(cv.eps[k], 10) << ' ' << numberText(cv.error[k].max_distance, 10) << '\n';
  }
  // a slope-1 guide through the geometric mean of the errors at the middle epsilon
  double log_mid = 0;
  int count = 0;
  for (const auto& cv : r.convergence)
    if (cv.error.size() >= 2 && cv.error[1].max_distance > 0) {
      log_mid += std::log(cv.error[1].max_distance / cv.eps[1]);
      ++count;
    }
  const double c1 = count ? std::exp(log_mid / count) : 1.0;
  std::vector<std::string> names;
  double eps_lo = INFINITY, eps_hi = 0;
  for (const auto& cv : r.convergence) {
    names.push_back(cv.name);
    for (double e : cv.eps) eps_lo = std::min(eps_lo, e), eps_hi = std::max(eps_hi, e);
  }
  return drawPng(
      dir, "convergence.png", d.str(), [&](const std::string& data, const std::string& png) {
        std::ostringstream s;
        s << header(png, "760,460") << "set logscale xy\nset xlabel 'ε'\n"
          << "set xrange [" << numberText(eps_lo / 1.3) << ":" << numberText(eps_hi * 1.3) << "]\n"
          << "set ylabel 'max envelope error over τ ∈ [0, " << numberText(r.plan.convergence_tau)
          << "]'\nset rmargin at screen 0.64\nset key at screen 0.66, 0.9 left Left reverse font "
             "',8' spacing 0.9 samplen 2\n"
          << "set format y '10^{%T}'\nset xtics (";
        for (size_t k = 0; k < r.plan.convergence_eps.size(); ++k)
          s << (k ? ", " : "") << numberText(r.plan.convergence_eps[k]);
        s << ")\nset title 'full model against the slow flow'\nplot ";
        // eight colours, then the same colours dashed with open symbols
        for (size_t c = 0; c < names.size(); ++c)
          s << (c ? ", " : "") << gnuplotQuote(data) << " index " << c
            << " using 1:2 with linespoints lw 1.5" << (c < 8 ? " dt 1 pt 7" : " dt 2 pt 6")
            << " ps 0.8 lc rgb '" << kColours[c % 8] << "' title " << gnuplotQuote(names[c])
            << " noenhanced";
        s << ", " << numberText(c1, 10)
          << "*x with lines dt 2 lw 2 lc rgb '#555555' title 'slope 1'\n"
          << "set output\n";
        return s.str();
      });
}

bool plotSweep(const OutputDir& dir, const ValidationResults& r) {
  if (r.sweep.empty()) return false;
  std::ostringstream d;
  for (int b = 0; b < 2; ++b) {
    if (b) d << "\n\n";
    for (const auto& p : r.sweep) {
      const ModelRun& m = b == 0 ? p.slow : p.full;
      const EnvelopeRow& f = m.final();
      if (f.A.size() < 2) continue;
      d << numberText(p.mu, 10) << ' ' << numberText(f.A[0], 10) << ' ' << numberText(f.A[1], 10)
        << '\n';
    }
  }
  const double theta_c =
      r.sweep.front().slow.theta_c.empty() ? std::nan("") : r.sweep.front().slow.theta_c[0];
  return drawPng(dir, "sweep.png", d.str(), [&](const std::string& data, const std::string& png) {
    std::ostringstream s;
    s << header(png) << "set logscale x\nset xlabel 'μ (scaled platform friction)'\n"
      << "set xrange [" << numberText(r.sweep.front().mu / 1.3) << ":"
      << numberText(r.sweep.back().mu * 1.3) << "]\n"
      << "set ylabel 'final amplitude'\nset yrange [0:*]\nset key outside right top\n"
      << "set title 'experiment rig, near in-phase start, ε = " << numberText(r.sweep_epsilon, 4)
      << "'\nplot " << gnuplotQuote(data)
      << " index 0 using 1:2 with linespoints dt 2 pt 6 ps 1.2 lc rgb '" << kColours[0]
      << "' title 'A_1 slow', '' index 0 using 1:3 with linespoints dt 2 pt 4 ps 1.2 lc rgb '"
      << kColours[1] << "' title 'A_2 slow', '' index 1 using 1:2 with linespoints pt 7 lc rgb '"
      << kColours[0] << "' title 'A_1 full', '' index 1 using 1:3 with linespoints pt 5 lc rgb '"
      << kColours[1] << "' title 'A_2 full'";
    if (std::isfinite(theta_c))
      s << ", " << numberText(theta_c, 10)
        << " with lines dt 3 lw 1.5 lc rgb '#555555' title 'θ_c'";
    s << "\nset output\n";
    return s.str();
  });
}

// The scenarios whose final states disagree most at the rig's own epsilon: the first whose
// regimes differ, and the farthest apart of those that share a regime but not a state.
std::vector<const RegimeComparison*> disagreementsToPlot(const ValidationResults& r) {
  std::vector<const RegimeComparison*> picks;
  const RegimeComparison* differing = nullptr;
  const RegimeComparison* farthest = nullptr;
  for (const auto& rc : r.regimes) {
    if (rc.full.empty() || !rc.full[0].report.complete || !rc.slow.report.complete) continue;
    if (rc.agree[0] || rc.mirror_agree[0]) continue;
    if (rc.full[0].verdict.regime != rc.slow.verdict.regime) {
      if (!differing) differing = &rc;
    } else if (!farthest || rc.distance[0] > farthest->distance[0]) {
      farthest = &rc;
    }
  }
  if (differing) picks.push_back(differing);
  if (farthest) picks.push_back(farthest);
  return picks;
}

std::string pngNameFor(const RegimeComparison& rc) {
  return "disagreement-" + rc.name + ".png";
}

}  // namespace

// ---- the regime sequence ------------------------------------------------------------------------

std::vector<RegimeStretch> regimeSequence(const std::vector<FrictionSweepPoint>& sweep, bool full) {
  std::vector<RegimeStretch> seq;
  for (const auto& p : sweep) {
    const std::string label = sweepLabel(full ? p.full : p.slow);
    if (!seq.empty() && seq.back().label == label)
      seq.back().mu_to = p.mu;
    else
      seq.push_back({label, p.mu, p.mu});
  }
  return seq;
}

namespace {

// A friction value of part 5: four digits (the refined values are geometric means, good to the
// refinement's 2%; the grid's values print as written)
std::string muText(double mu) {
  return numberText(mu, 4);
}

std::string sequenceText(const std::vector<RegimeStretch>& seq) {
  std::string s;
  for (const auto& st : seq) {
    s += (s.empty() ? "" : " → ") + st.label + " (μ = " + muText(st.mu_from);
    if (st.mu_to != st.mu_from) s += "–" + muText(st.mu_to);
    s += ")";
  }
  return s;
}

// in-phase, then suppression, then death, in this order (other stretches may sit between)
bool followsPaperOrder(const std::vector<RegimeStretch>& seq) {
  const char* const wanted[] = {"in-phase", "suppression", "death"};
  size_t k = 0;
  for (const auto& st : seq)
    if (k < 3 && st.label == wanted[k]) ++k;
  return k == 3;
}

double firstMuWith(const std::vector<FrictionSweepPoint>& sweep, bool full, Regime g) {
  for (const auto& p : sweep)
    if ((full ? p.full : p.slow).verdict.regime == g) return p.mu;
  return std::nan("");
}

const RegimeComparison* findRegimes(const ValidationResults& r, const std::string& name) {
  for (const auto& rc : r.regimes)
    if (rc.name == name) return &rc;
  return nullptr;
}

}  // namespace

// ---- report.md ----------------------------------------------------------------------------------

namespace {

// ---- report.md, one function per section ---------------------------------------------------

bool hasPlot(const std::vector<std::string>& plots, const std::string& png) {
  return std::find(plots.begin(), plots.end(), png) != plots.end();
}

// the title, the command that regenerates the report, the rigs and the engine
void mdHeader(std::ostream& md, const ValidationResults& r, const ReportContext& ctx) {
  const ValidationPlan& plan = r.plan;

  md << "# Validation: the full model against the asymptotics\n\n"
     << "Generated by `" << ctx.command << "` (metrosync " << metrosyncVersion() << ", "
     << (plan.quick ? "the quick plan" : "the full plan") << "), finished " << ctx.date << " after "
     << duration(r.wall_seconds) << " of wall time. Every number below comes "
     << "from that one run. To regenerate the report, build and run the same command from the "
     << "repository root:\n\n```sh\ncmake -S . -B build -DCMAKE_BUILD_TYPE=Release && cmake "
        "--build build\n./build/"
     << ctx.command << "\n```\n\n"
     << "Rigs: the shipped ones (`" << ctx.rigs_dir << "`): the paper's eight simulations in "
     << "`paper/` (scaled units, section 4 captions) and the experiment's four "
     << "(`experiment-{low,high}-friction-{inphase,antiphase}.yaml`, physical units, section 3). "
     << "The full model is the " << ctx.engine << " engine at its default accuracy ("
     << shortSci(ScaledRigInput{}.accuracy) << "); the slow flow is integrated at rtol "
     << shortSci(SlowFlowOptions{}.rtol) << ".\n\n";
}

// one row per part
void mdSummary(std::ostream& md, const ValidationResults& r) {
  const ValidationPlan& plan = r.plan;
  double beta_max = 0, s_lo = INFINITY, s_hi = 0;
  bool betas_pass = !r.betas.empty();
  for (const auto& b : r.betas) {
    beta_max = std::max({beta_max, b.err1, b.err2});
    s_lo = std::min(s_lo, b.s);
    s_hi = std::max(s_hi, b.s);
    betas_pass = betas_pass && b.pass;
  }
  int paper_pass = 0;
  for (const auto& s : r.scenarios) paper_pass += s.pass;
  double order_lo = INFINITY, order_hi = -INFINITY;
  bool conv_pass = !r.convergence.empty();
  for (const auto& c : r.convergence) {
    order_lo = std::min(order_lo, c.order);
    order_hi = std::max(order_hi, c.order);
    conv_pass = conv_pass && c.pass;
  }
  md << "## Summary\n\n| part | result |\n| --- | --- |\n";
  md << "| 1. β₁, β₂ against the full model's Coulomb element | max \\|measured − closed form\\| = "
     << sci(beta_max) << " over " << r.betas.size() << " drive strengths s ∈ [" << numberText(s_lo)
     << ", " << numberText(s_hi) << "] (bound " << shortSci(plan.beta_tol)
     << "): " << passText(betas_pass) << " |\n";
  md << "| 2. the paper's eight simulations, slow flow | " << paper_pass << " of "
     << r.scenarios.size() << " as the paper describes: "
     << passText(paper_pass == static_cast<int>(r.scenarios.size()) && !r.scenarios.empty())
     << " |\n";
  md << "| 3. convergence in ε (theory: order 1) | orders "
     << numberText(order_lo, 2, Notation::Fixed) << " to "
     << numberText(order_hi, 2, Notation::Fixed) << " over " << r.convergence.size()
     << " scenarios (bound " << numberText(plan.order_lo, 1, Notation::Fixed) << " to "
     << numberText(plan.order_hi, 1, Notation::Fixed) << "): " << passText(conv_pass) << " |\n";
  if (!r.regimes.empty()) {
    md << "| 4. final regime and state, full model against slow flow | ";
    for (size_t k = 0; k < plan.regime_eps.size(); ++k) {
      int differ = 0, mirror = 0, total = 0;
      double eps = 0;
      for (const auto& rc : r.regimes) {
        if (k >= rc.full.size()) continue;
        ++total;
        differ += !rc.agree[k];
        mirror += rc.mirror_agree[k];
        eps = rc.full[k].epsilon;
      }
      md << (k ? "; " : "") << "ε = " << (plan.regime_eps[k] > 0 ? epsLabel(eps) : "rig's own")
         << ": " << differ << " of " << total << " differ";
      if (mirror) md << " (" << mirror << " only by which of two identical metronomes is which)";
    }
    md << " (findings, not failures) |\n";
  }
  if (!r.sweep.empty())
    md << "| 5. the experiment's regime sequence over μ | slow flow: "
       << sequenceText(regimeSequence(r.sweep, false))
       << "<br>full model: " << sequenceText(regimeSequence(r.sweep, true)) << " |\n";
  if (!r.bifurcations.empty()) {
    int located = 0, checked = 0, pass = 0;
    for (const auto& f : r.bifurcations)
      for (const auto& p : f.points)
        located += 1, checked += p.checked, pass += p.checked && p.pass;
    md << "| 6. bifurcations of the slow flow (continuation) | " << located
       << " folds and Hopf points located on " << r.bifurcations.size() << " families; " << checked
       << " of them change a stable state, " << pass
       << " confirmed by slow-flow runs on both sides: " << passText(pass == checked && located > 0)
       << " |\n";
  }
  if (r.full_orbits) mdFullOrbitsSummaryRow(md, *r.full_orbits);
  if (r.experiments) mdExperimentsSummaryRow(md, *r.experiments);
  md << "\nChecks failed: " << r.failedChecks()
     << "; runs that stopped early: " << r.incompleteRuns() << ".\n\n";
}

// part 1: beta1, beta2 against the Coulomb element
void mdBetas(std::ostream& md, const ValidationResults& r, const std::vector<std::string>& plots) {
  md << "## 1. β₁, β₂ against the full model's Coulomb element\n\n"
     << "The Simbody Coulomb contact of the full model (`contact/simbody/coulomb_contact.h`: its "
        "witness; `resolveSwitch` and `settleAtRest` in `driven_coulomb_harness.h`), on a unit "
        "mass with unit friction bound, "
        "driven by B sin t (eq. c1, B = s), started at rest and run until its switch instants "
        "repeat from one drive period to the next (to "
     << shortSci(DrivenCoulombOptions{}.periodic_tol)
     << "). Over that period, β₁ = (1/(2πB)) ∫ y″ sin t dt and β₂ = (1/(2πB)) ∫ y″ cos t dt, "
        "y″ read from the element's own accelerations at "
     << DrivenCoulombOptions{}.gauss_nodes
     << " Gauss-Legendre nodes in each smooth "
        "piece between switches (exact there). Closed forms: eq. d2 "
        "(`contact/averaged_response.h`). s_b = √(1 + π²/4) = "
     << numberText(kCoulombSlipThreshold, 7, Notation::Fixed) << ".\n\n"
     << "| s | periods to steady state | switches per period | β₁ closed form | β₁ element | "
        "\\|Δβ₁\\| | β₂ closed form | β₂ element | \\|Δβ₂\\| |\n"
     << "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
  for (const auto& b : r.betas) {
    md << "| " << numberText(b.s, 9) << " | "
       << (b.measured.periodic ? std::to_string(b.measured.periods) : "not reached") << " | "
       << b.measured.switches.size() << " | " << numberText(b.beta1_closed, 12, Notation::Fixed)
       << " | " << numberText(b.measured.beta1, 12, Notation::Fixed) << " | " << sci(b.err1)
       << " | " << numberText(b.beta2_closed, 12, Notation::Fixed) << " | "
       << numberText(b.measured.beta2, 12, Notation::Fixed) << " | " << sci(b.err2)
       << (b.pass ? "" : " **FAIL**") << " |\n";
  }
  md << "\n0 switches: the platform stays stuck (s ≤ 1); 4: stick-slip (slip, stick, slip back, "
        "stick); 2: pure slip, reversing twice per period (s > s_b).\n\n";
  if (hasPlot(plots, "betas.png")) md << "![β₁, β₂: closed forms and the element](betas.png)\n\n";
}

// part 2: the paper's eight simulations
void mdScenarios(std::ostream& md, const ValidationResults& r) {
  md << "## 2. The paper's eight simulations, from the slow flow\n\n"
     << "Each shipped `paper/` rig run with the slow flow to its own τ ("
     << (r.scenarios.empty() ? std::string("–") : numberText(r.scenarios.front().slow.tau_end))
     << "), regime by the contract's rules (docs/contract.md section 4) "
        "on the last 10%, then the paper's statements about it checked (ψ = φ₁ − φ₂; "
        "α > 0 makes metronome 2 the faster one).\n\n"
     << "| scenario | the paper | slow flow | final state | checks |\n"
     << "| --- | --- | --- | --- | --- |\n";
  for (const auto& s : r.scenarios) {
    std::string paper;
    for (const auto& spec : shippedScenarios())
      if (spec.name == s.name) paper = spec.paper;
    std::string checks;
    for (const auto& c : s.checks)
      checks += (checks.empty() ? "" : "<br>") + std::string(c.pass ? "✓ " : "✗ **") +
                cell(c.what) + (c.pass ? "" : "**") + " (" + cell(c.detail) + ")";
    md << "| " << s.name << " | " << paper << " | " << regimeText(s.slow) << " | "
       << stateText(s.slow.final()) << " | " << checks << " |\n";
  }
  md << "\n";
}

// part 3: convergence in epsilon
void mdConvergence(std::ostream& md, const ValidationResults& r,
                   const std::vector<std::string>& plots) {
  const ValidationPlan& plan = r.plan;
  md << "## 3. Convergence in ε\n\n"
     << "Every scenario's scaled parameters and start, the full model at ε = ";
  for (size_t k = 0; k < plan.convergence_eps.size(); ++k)
    md << (k ? ", " : "") << numberText(plan.convergence_eps[k]);
  md << " against the slow flow, envelopes row by row (one row per fast period) over τ ∈ [0, "
     << numberText(plan.convergence_tau)
     << "]. Error: the largest distance between the complex amplitudes in metronome 1's frame, "
        "max over τ and j of \\|A_j e^{−iψ_j} (full) − A_j e^{−iψ_j} (slow)\\| (j = 1: \\|ΔA₁\\|); "
        "it weighs a phase error by its amplitude, so a suppressed or dying metronome (whose "
        "phase means little) does not dominate. Order: least-squares slope of log error against "
        "log ε; the two-timescale theory says 1. The last two columns, for information: the "
        "largest \\|ΔA_i\\| and \\|Δψ_j\\| (mod 2π) at the smallest ε.\n\n"
     << "| scenario |";
  for (double e : plan.convergence_eps) md << " error, ε = " << numberText(e) << " |";
  md << " order | max \\|ΔA\\| | max \\|Δψ\\| | |\n| --- |";
  for (size_t k = 0; k < plan.convergence_eps.size(); ++k) md << " --- |";
  md << " --- | --- | --- | --- |\n";
  for (const auto& c : r.convergence) {
    md << "| " << c.name << " |";
    for (const auto& e : c.error) md << " " << tableNumber(e.max_distance, 4) << " |";
    const EnvelopeError& last = c.error.back();
    md << " " << numberText(c.order, 3, Notation::Fixed) << " | " << tableNumber(last.max_dA, 4)
       << " | " << tableNumber(last.max_dpsi, 4) << " | " << passText(c.pass) << " |\n";
  }
  md << "\n";
  if (hasPlot(plots, "convergence.png"))
    md << "![envelope error against ε, log-log](convergence.png)\n\n";
}

// part 4: the final regimes, full model against slow flow, as a table
void mdRegimeTable(std::ostream& md, const ValidationResults& r) {
  const ValidationPlan& plan = r.plan;
  md << "## 4. Where the asymptotics fail\n\n"
     << "The final regime (the contract's rules on the last 10% of the run) of each scenario "
        "from the "
        "full model at the rig's own ε (";
  {
    std::vector<std::string> own;
    for (const auto& rc : r.regimes)
      if (!rc.full.empty()) {
        const std::string e = epsLabel(rc.full[0].epsilon);
        if (std::find(own.begin(), own.end(), e) == own.end()) own.push_back(e);
      }
    for (size_t k = 0; k < own.size(); ++k) md << (k ? ", " : "") << own[k];
  }
  md << ")";
  for (size_t k = 1; k < plan.regime_eps.size(); ++k) md << ", " << numberText(plan.regime_eps[k]);
  md << ", next to the slow flow's, over the τ window shown (long enough for the slow flow's "
        "final regime). d: the distance between the final states (as in part 3). ✓: same "
        "regime and, for a settled state with a metronome alive, d ≤ "
     << numberText(kAgreeDistance)
     << "; ↔: the same, once the full model's two metronomes (identical but for their start) "
        "are exchanged; ✗: neither.\n\n| scenario | τ | slow flow |";
  for (size_t k = 0; k < plan.regime_eps.size(); ++k)
    md << " full, ε = " << (plan.regime_eps[k] > 0 ? numberText(plan.regime_eps[k]) : "rig's")
       << " |";
  md << "\n| --- | --- | --- |";
  for (size_t k = 0; k < plan.regime_eps.size(); ++k) md << " --- |";
  md << "\n";
  for (const auto& rc : r.regimes) {
    md << "| " << rc.name << " | " << numberText(rc.tau_end) << " | **" << regimeText(rc.slow)
       << "**<br>" << stateText(rc.slow.final()) << " |";
    for (size_t k = 0; k < rc.full.size(); ++k) {
      const ModelRun& f = rc.full[k];
      md << " "
         << (rc.agree[k]          ? "✓ "
             : rc.mirror_agree[k] ? "↔ "
                                  : "✗ ")
         << "**" << regimeText(f) << "**<br>" << stateText(f.final())
         << "<br>d = " << tableNumber(rc.distance[k], 3) << " |";
    }
    md << "\n";
  }
  md << "\n";
}

// part 4: the disagreements, in words, and their plots
void mdDisagreements(std::ostream& md, const ValidationResults& r,
                     const std::vector<std::string>& plots) {
  std::vector<std::string> lines;
  for (const auto& rc : r.regimes)
    for (size_t k = 0; k < rc.full.size(); ++k) {
      if (rc.agree[k]) continue;
      const ModelRun& f = rc.full[k];
      std::string line = "- **" + rc.name + "** at ε = " + epsLabel(regimeEps(rc, k)) + ": ";
      if (f.verdict.regime != rc.slow.verdict.regime)
        line += "the full model ends in " + regimeText(f) + " (" + stateText(f.final()) +
                "), the slow flow in " + regimeText(rc.slow) + " (" + stateText(rc.slow.final()) +
                ").";
      else
        line += "both " + regimeText(f) + ", but in different states: full " +
                stateText(f.final()) + ", slow " + stateText(rc.slow.final()) +
                " (d = " + tableNumber(rc.distance[k], 2) + ").";
      if (rc.mirror_agree[k])
        line +=
            " With the full model's metronomes exchanged (they are identical but for their "
            "start) the states agree, d = " +
            tableNumber(rc.mirror_distance[k], 3) +
            ": the small asymmetry of the start grew the other way.";
      lines.push_back(line);
    }
  if (lines.empty()) {
    md << "The full model agrees with the slow flow on every scenario at every ε.\n\n";
  } else {
    md << "Disagreements:\n\n";
    for (const auto& l : lines) md << l << "\n";
    md << "\n";
  }
  for (const RegimeComparison* rc : disagreementsToPlot(r)) {
    const std::string png = pngNameFor(*rc);
    if (hasPlot(plots, png))
      md << "![" << rc->name
         << ": full model (solid) and slow flow (dashed) at ε = " << epsLabel(regimeEps(*rc, 0))
         << "](" << png << ")\n\n";
  }
}

// part 5: the experiment's regime sequence over mu, as a table
void mdSweepTable(std::ostream& md, const ValidationResults& r) {
  md << "## 5. The experiment's regime sequence over μ\n\n"
     << "The paper's figure exp1, right panel (experiments started in phase): in-phase "
        "synchronization at low μ, then metronome suppression, then oscillator death, then "
        "antiphase synchronization and, at the highest μ, uncoupling (the platform barely "
        "moves). Here both models run the rig `"
     << r.sweep_scenario
     << "` (its scaled parameters: ψ₀ = " << numberText(r.sweep_psi0, 4, Notation::Fixed)
     << ", ε = " << numberText(r.sweep_epsilon, 4)
     << ", τ = " << numberText(r.sweep_tau, 1, Notation::Fixed)
     << ") with its friction μ replaced; μ̄ = μ ε^{3/2} is the physical coefficient";
  std::string exp_mu;
  for (const auto& rc : r.regimes)
    if (rc.name.rfind("experiment-", 0) == 0 && rc.name.find("inphase") != std::string::npos)
      exp_mu += (exp_mu.empty() ? "" : ", ") + rc.name +
                ": μ = " + numberText(rc.slow.mu, 3, Notation::Fixed);
  if (!exp_mu.empty()) md << " (the experiment's rigs: " << exp_mu << ")";
  md << ".";
  if (r.plan.sweep_resolution > 0)
    md << " The grid is refined where the regimes change: wherever two neighbouring values of μ "
          "end in different regimes (in either model), the run at their geometric mean is added, "
          "round after round, until such neighbours are within a ratio of "
       << numberText(1 + r.plan.sweep_resolution) << " (" << r.sweep.size()
       << " values of μ in all, " << r.plan.sweep_mu.size()
       << " on the grid); a window of a regime between two values that end alike is not "
          "looked for.";
  md << " Platform: where it spends the last 10% (full model: the share of time stuck; slow "
        "flow: the Coulomb regime of the final drive s = \\|Z\\|/μ); \"uncoupled\": alive over "
        "a platform at rest.\n\n"
     << "| μ | μ̄ | slow flow | full model, ε = " << numberText(r.sweep_epsilon, 4) << " |\n"
     << "| --- | --- | --- | --- |\n";
  for (const auto& p : r.sweep) {
    auto cell = [](const ModelRun& m) {
      std::string s = "**" + regimeText(m) + "**<br>" + stateText(m.final());
      if (!m.platform.empty()) {
        s += "<br>platform " + m.platform;
        if (std::isfinite(m.platform_stuck_fraction) && m.platform == "stick-slip")
          s += " (stuck " + numberText(100 * m.platform_stuck_fraction, 1, Notation::Fixed) + "%)";
      }
      return s;
    };
    md << "| " << muText(p.mu) << " | " << sci(p.mu_bar, 2) << " | " << cell(p.slow) << " | "
       << cell(p.full) << " |\n";
  }
}

// part 5: the sequences and what they say
void mdSweepWords(std::ostream& md, const ValidationResults& r,
                  const std::vector<std::string>& plots) {
  const auto slow_seq = regimeSequence(r.sweep, false), full_seq = regimeSequence(r.sweep, true);
  md << "\nThe sequences, collapsed:\n\n"
     << "- paper (fig. exp1, right): in-phase → suppression → death → antiphase → uncoupled\n"
     << "- slow flow: " << sequenceText(slow_seq) << "\n"
     << "- full model: " << sequenceText(full_seq) << "\n\n";
  md << "In words: the slow flow " << (followsPaperOrder(slow_seq) ? "does" : "does not")
     << " go through in-phase, suppression and death in the paper's order; the full model "
     << (followsPaperOrder(full_seq) ? "does" : "does not") << ". ";
  const double s_sup = firstMuWith(r.sweep, false, Regime::Suppression),
               f_sup = firstMuWith(r.sweep, true, Regime::Suppression);
  const double s_death = firstMuWith(r.sweep, false, Regime::Death),
               f_death = firstMuWith(r.sweep, true, Regime::Death);
  auto at = [](double mu) { return std::isfinite(mu) ? "μ = " + muText(mu) : "never"; };
  md << "Suppression first appears at " << at(s_sup) << " in the slow flow and " << at(f_sup)
     << " in the full model; death at " << at(s_death) << " and " << at(f_death)
     << ". At the highest μ tried (" << muText(r.sweep.back().mu) << ") the slow flow gives "
     << sweepLabel(r.sweep.back().slow) << " and the full model " << sweepLabel(r.sweep.back().full)
     << " (the paper: antiphase, then uncoupling). ";
  if (const RegimeComparison* hi = findRegimes(r, "experiment-high-friction-inphase")) {
    md << "The experiment's own high friction (μ = " << numberText(hi->slow.mu, 3, Notation::Fixed)
       << "; fig. exp3: death about 20 s after an in-phase start) gives " << regimeText(hi->slow)
       << " in the slow flow";
    if (!hi->full.empty()) md << " and " << regimeText(hi->full[0]) << " in the full model";
    md << " at the rig's ε (part 4)";
    std::vector<std::string> later;
    if (hi->slow.verdict.regime != Regime::Death) later.push_back("the slow flow");
    if (!hi->full.empty() && hi->full[0].verdict.regime != Regime::Death)
      later.push_back("the full model");
    if (!later.empty())
      md << ": in " << (later.size() == 2 ? later[0] + " and " + later[1] : later[0])
         << " death needs more friction than in the experiment";
    md << ".";
  }
  // the highest friction: a still platform in the slow flow, not quite in the full model
  const FrictionSweepPoint& top = r.sweep.back();
  if (top.slow.platform == "stuck" && top.full.report.complete && top.full.platform != "stuck" &&
      std::isfinite(top.full.platform_stuck_fraction) && !top.full.final().psi.empty())
    md << " At μ = " << muText(top.mu)
       << " the slow flow's platform never moves (\\|Z\\| < μ: the metronomes are uncoupled), "
          "while the full model's is at rest "
       << numberText(100 * top.full.platform_stuck_fraction, 1, Notation::Fixed)
       << "% of the time: every escapement tick jumps a pendulum's velocity, and e1.1c turns "
          "that into an impulse on the platform, which no finite friction force can hold; the "
          "platform slides briefly at each tick, so the full model's metronomes never decouple "
          "completely (ψ: "
       << numberText(r.sweep_psi0, 4, Notation::Fixed) << " at the start, "
       << numberText(wrapToPi(top.full.final().psi[0]), 4, Notation::Fixed)
       << " at the end; the slow flow's "
       << numberText(wrapToPi(top.slow.final().psi[0]), 4, Notation::Fixed) << ").";
  md << "\n\n";
  if (hasPlot(plots, "sweep.png")) md << "![final amplitudes against μ](sweep.png)\n\n";
}

}  // namespace

std::string validationReportMarkdown(const ValidationResults& r, const ReportContext& ctx,
                                     const std::vector<std::string>& plots) {
  std::ostringstream md;
  mdHeader(md, r, ctx);
  mdSummary(md, r);
  mdBetas(md, r, plots);
  mdScenarios(md, r);
  mdConvergence(md, r, plots);
  if (!r.regimes.empty()) {
    mdRegimeTable(md, r);
    mdDisagreements(md, r, plots);
  }
  if (!r.sweep.empty()) {
    mdSweepTable(md, r);
    mdSweepWords(md, r, plots);
  }
  mdBifurcations(md, r.bifurcations);
  if (r.full_orbits) mdFullOrbits(md, *r.full_orbits);
  if (r.experiments) mdExperiments(md, *r.experiments);
  return md.str();
}

// ---- summary.json -------------------------------------------------------------------------------

nlohmann::json modelRunJson(const ModelRun& m) {
  nlohmann::json j;
  j["model"] = m.model;
  j["epsilon"] = m.epsilon;
  j["tau_end"] = m.tau_end;
  j["complete"] = m.report.complete;
  if (!m.report.complete) j["failure"] = m.report.failure;
  j["regime"] = toString(m.verdict.regime);
  j["final"] = {{"tau", m.final().tau}, {"A", m.final().A}, {"psi", m.final().psi}};
  if (!m.platform.empty()) j["platform"] = m.platform;
  if (std::isfinite(m.platform_stuck_fraction))
    j["platform_stuck_fraction"] = m.platform_stuck_fraction;
  j["wall_seconds"] = m.report.wall_seconds;
  return j;
}

nlohmann::json validationJson(const ValidationResults& r, const ReportContext& ctx) {
  nlohmann::json j;
  j["command"] = ctx.command;
  j["version"] = metrosyncVersion();
  j["date"] = ctx.date;
  j["engine"] = ctx.engine;
  j["plan"] = r.plan.quick ? "quick" : "full";
  j["failed_checks"] = r.failedChecks();
  j["incomplete_runs"] = r.incompleteRuns();
  j["wall_seconds"] = r.wall_seconds;
  for (const auto& b : r.betas)
    j["betas"].push_back({{"s", b.s},
                          {"beta1_closed", b.beta1_closed},
                          {"beta2_closed", b.beta2_closed},
                          {"beta1_element", b.measured.beta1},
                          {"beta2_element", b.measured.beta2},
                          {"periodic", b.measured.periodic},
                          {"periods", b.measured.periods},
                          {"switches_per_period", b.measured.switches.size()},
                          {"pass", b.pass}});
  for (const auto& s : r.scenarios) {
    nlohmann::json checks = nlohmann::json::array();
    for (const auto& c : s.checks)
      checks.push_back({{"what", c.what}, {"pass", c.pass}, {"detail", c.detail}});
    j["scenarios"].push_back(
        {{"name", s.name}, {"slow", modelRunJson(s.slow)}, {"checks", checks}, {"pass", s.pass}});
  }
  for (const auto& c : r.convergence) {
    nlohmann::json e = nlohmann::json::array();
    for (size_t k = 0; k < c.eps.size(); ++k)
      e.push_back({{"epsilon", c.eps[k]},
                   {"max_distance", c.error[k].max_distance},
                   {"tau_at_max", c.error[k].tau_at_max},
                   {"max_dA", c.error[k].max_dA},
                   {"max_dpsi", c.error[k].max_dpsi},
                   {"rows", c.error[k].rows}});
    j["convergence"].push_back(
        {{"name", c.name}, {"errors", e}, {"order", c.order}, {"pass", c.pass}});
  }
  for (const auto& rc : r.regimes) {
    nlohmann::json full = nlohmann::json::array();
    for (size_t k = 0; k < rc.full.size(); ++k) {
      nlohmann::json f = modelRunJson(rc.full[k]);
      f["distance"] = rc.distance[k];
      f["agree"] = static_cast<bool>(rc.agree[k]);
      f["mirror_agree"] = static_cast<bool>(rc.mirror_agree[k]);
      if (std::isfinite(rc.mirror_distance[k])) f["mirror_distance"] = rc.mirror_distance[k];
      full.push_back(f);
    }
    j["regimes"].push_back({{"name", rc.name},
                            {"tau_end", rc.tau_end},
                            {"slow", modelRunJson(rc.slow)},
                            {"full", full}});
  }
  for (const auto& p : r.sweep)
    j["sweep"].push_back({{"mu", p.mu},
                          {"mu_bar", p.mu_bar},
                          {"slow", modelRunJson(p.slow)},
                          {"full", modelRunJson(p.full)}});
  if (!r.bifurcations.empty()) j["bifurcations"] = validationBifurcationsJson(r.bifurcations);
  if (r.full_orbits) j["full_orbits"] = validationFullOrbitsJson(*r.full_orbits);
  if (r.experiments) j["experiments"] = validationExperimentsJson(*r.experiments);
  return j;
}

std::vector<std::string> writeValidationReport(const OutputDir& dir, const ValidationResults& r,
                                               const ReportContext& ctx) {
  std::vector<std::string> plots;
  if (plotBetas(dir, r)) plots.push_back("betas.png");
  if (plotConvergence(dir, r)) plots.push_back("convergence.png");
  for (const RegimeComparison* rc : disagreementsToPlot(r)) {
    const ModelRun& f = rc->full[0];
    const std::string png = pngNameFor(*rc);
    if (plotComparison(dir, png, f.envelope, rc->slow.envelope, f.theta_c,
                       rc->name + ": full model (solid, " + toString(f.verdict.regime) +
                           ") and slow flow "
                           "(dashed, " +
                           toString(rc->slow.verdict.regime) + "), ε = " + epsLabel(f.epsilon)))
      plots.push_back(png);
  }
  if (plotSweep(dir, r)) plots.push_back("sweep.png");

  std::vector<std::string> files = plots;
  writeFileAtomically(dir.file("report.md"), validationReportMarkdown(r, ctx, plots));
  files.push_back("report.md");
  writeJsonFile(dir.file("summary.json"), validationJson(r, ctx));
  files.push_back("summary.json");
  return files;
}

}  // namespace metrosync
