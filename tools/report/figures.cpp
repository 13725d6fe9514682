#include "tools/report/figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "base/constants.h"
#include "sim/record/atomic_file.h"
#include "tools/report/plot.h"
#include "tools/report/sweep_maps.h"
#include "tools/report/validation_report.h"

namespace metrosync {

namespace {

// the terminal: the same picture as PNG (cairo) or SVG
std::string terminal(bool svg, int width, int height) {
  const std::string size = std::to_string(width) + "," + std::to_string(height);
  return svg ? "set terminal svg size " + size + " dynamic enhanced font 'sans,11'\n"
             : "set terminal pngcairo size " + size + " enhanced font 'sans,11' linewidth 1.2\n";
}

// tics at multiples of pi/2 over [lo, hi] (fewer when the range is wide)
std::string piTics(const char* axis, double lo, double hi) {
  long step = 1;
  while ((hi - lo) / (step * kPi / 2) > 8) step *= 2;
  std::string tics;
  for (long k = static_cast<long>(std::ceil(lo / (kPi / 2) / step)) * step;
       k * kPi / 2 <= hi + 1e-12; k += step)
    tics += (tics.empty() ? "" : ", ") + std::string("\"") + halfPiLabel(k) + "\" " +
            gnuplotNumber(k * kPi / 2);
  return std::string("set ") + axis + "tics (" + tics + ")\n";
}

// the blocks of a figure's data, in plotting order: each run's full model, then its slow flow
struct Block {
  const FigureRun* run;
  const ModelRun* model;
  bool full;
};

std::vector<Block> blocksOf(const FigureResult& f) {
  std::vector<Block> b;
  for (const auto& r : f.runs) {
    if (r.has_full) b.push_back({&r, &r.full, true});
    if (r.has_slow) b.push_back({&r, &r.slow, false});
  }
  return b;
}

// Whether psi runs away (the metronomes fall out of sync): then the panel shows it wrapped to
// [0, 2 pi), as a phase, instead of a line leaving the picture.
bool drifts(const std::vector<EnvelopeRow>& rows) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& r : rows)
    if (!r.psi.empty() && std::isfinite(r.psi[0]))
      lo = std::min(lo, r.psi[0]), hi = std::max(hi, r.psi[0]);
  return hi - lo > 3 * kPi;
}

// "tau A_1 A_2 psi" per row, blocks separated by two blank lines (gnuplot's `index`)
std::string figureData(const FigureResult& f) {
  std::ostringstream out;
  bool first = true;
  for (const Block& b : blocksOf(f)) {
    if (!first) out << "\n\n";
    first = false;
    if (b.model->envelope.empty()) out << "nan nan nan nan\n";
    const bool wrap = drifts(b.model->envelope);
    double last = NAN;
    for (const auto& r : b.model->envelope) {
      double psi = r.psi.empty() ? NAN : r.psi[0];
      if (wrap) {
        psi = wrapToTwoPi(psi);
        if (std::fabs(psi - last) > kPi) out << '\n';  // no line across the wrap
        last = psi;
      }
      out << gnuplotNumber(r.tau) << ' ' << gnuplotNumber(r.A[0]) << ' '
          << gnuplotNumber(r.A.size() > 1 ? r.A[1] : NAN) << ' ' << gnuplotNumber(psi) << '\n';
    }
  }
  return out.str();
}

// the psi panel's range: every curve's, with pi and 2 pi in it
void psiRange(const FigureResult& f, double& lo, double& hi, double& tau_max) {
  lo = 0.0, hi = 2 * kPi, tau_max = 0.0;
  for (const Block& b : blocksOf(f)) {
    const bool wrapped = drifts(b.model->envelope);  // drawn in [0, 2 pi)
    for (const auto& r : b.model->envelope) {
      tau_max = std::max(tau_max, r.tau);
      if (!r.psi.empty() && std::isfinite(r.psi[0]) && !wrapped)
        lo = std::min(lo, r.psi[0]), hi = std::max(hi, r.psi[0]);
    }
  }
}

std::string legendOf(const Block& b, bool both) {
  if (!both) return b.run->curve.label;
  return b.run->curve.label + (b.full ? ", full model" : ", slow flow");
}

}  // namespace

std::string paperFigureScript(const FigureResult& f, const std::string& data_path,
                              const std::string& out_path, bool svg) {
  const std::vector<Block> blocks = blocksOf(f);
  const bool both = std::any_of(f.runs.begin(), f.runs.end(),
                                [](const FigureRun& r) { return r.has_full && r.has_slow; });
  double lo = 0, hi = 0, tau_max = 0;
  psiRange(f, lo, hi, tau_max);
  const double theta_c = f.runs.empty() ? 0.0 : f.runs[0].scaled.theta_c[0];
  std::ostringstream s;
  s << terminal(svg, 900, 1000) << "set output " << gnuplotQuote(out_path) << "\n"
    << "set datafile missing 'nan'\nset grid back lt 1 lw 0.8 lc rgb '#e4e4e4'\n"
    << "set key outside right top samplen 3 noenhanced\n"
    << "set lmargin at screen 0.10\nset rmargin at screen 0.74\n"
    << "set xrange [0:" << gnuplotNumber(tau_max > 0 ? tau_max : 1) << "]\n"
    << "set multiplot layout 3,1 title " << gnuplotQuote(f.spec.title)
    << " noenhanced font 'sans,13'\n";
  auto curves = [&](int column) {
    std::string plot;
    for (size_t k = 0; k < blocks.size(); ++k)
      plot += (plot.empty() ? "plot " : ", \\\n     ") + gnuplotQuote(data_path) + " index " +
              std::to_string(k) + " using 1:" + std::to_string(column) + " with lines lw " +
              (blocks[k].full ? "2" : "1.6") + " dt " + (blocks[k].full || !both ? "1" : "2") +
              " lc rgb '" + blocks[k].run->curve.colour + "' title " +
              gnuplotQuote(legendOf(blocks[k], both));
    return plot;
  };
  for (int i = 1; i <= 2; ++i) {
    s << "unset xlabel\nset ylabel 'A_" << i << "'\nset yrange [0:*]\n"
      << curves(1 + i) << ", \\\n     " << gnuplotNumber(theta_c)
      << " with lines dt 2 lw 1.5 lc rgb '#555555' title 'θ_c' enhanced\n";  // θ, subscript c
  }
  const double pad = 0.04 * (hi - lo);
  s << "set xlabel 'τ'\nset ylabel 'ψ'\nset yrange [" << gnuplotNumber(lo - pad) << ":"
    << gnuplotNumber(hi + pad) << "]\n"
    << piTics("y", lo - pad, hi + pad) << curves(4)
    << ", \\\n     pi with lines dt 2 lw 1.2 lc rgb '#555555' title 'π, 2π', \\\n"
    << "     2*pi with lines dt 2 lw 1.2 lc rgb '#555555' notitle\n"
    << "unset multiplot\nset output\n";
  return s.str();
}

namespace {

// "mu psi0 R G B" cells of the regime map (white where not run), rows separated by blank lines
std::string mapData(const RegimeMapResult& m, const std::vector<std::string>& legend) {
  std::ostringstream d;
  const auto& axes = m.grid.axes();
  for (long i = 0; i < axes[0].count; ++i) {
    for (long j = 0; j < axes[1].count; ++j) {
      const long g = i * axes[1].count + j;
      const auto it = m.points.find(g);
      const long rgb =
          it == m.points.end()
              ? 0xffffff
              : std::stol(regimeColour(it->second.regime, legend).substr(1), nullptr, 16);
      d << gnuplotNumber(axes[0].values[i]) << ' ' << gnuplotNumber(axes[1].values[j]) << ' '
        << ((rgb >> 16) & 255) << ' ' << ((rgb >> 8) & 255) << ' ' << (rgb & 255) << '\n';
    }
    d << '\n';
  }
  return d.str();
}

double cellOf(const SweepAxis& a) {
  return a.count > 1 ? (a.values.back() - a.values.front()) / (a.count - 1) : 1.0;
}

}  // namespace

std::string mapScript(const RegimeMapResult& m, const FiguresContext& ctx,
                      const std::vector<std::string>& legend, const std::string& data_path,
                      const std::string& out_path, bool svg) {
  const SweepAxis &x = m.grid.axes()[0], &y = m.grid.axes()[1];
  const double cx = cellOf(x), cy = cellOf(y);
  std::string arrows;  // the experiment's two frictions, dotted verticals
  for (double mu : ctx.mu_experiment)
    arrows += "set arrow from " + gnuplotNumber(mu) + ", graph 0 to " + gnuplotNumber(mu) +
              ", graph 1 nohead front dt 3 lw 2 lc rgb '#000000'\n";
  std::ostringstream s;
  s << terminal(svg, 1000, 720) << "set output " << gnuplotQuote(out_path) << "\n"
    << "set title "
    << gnuplotQuote(m.spec.title + " (" + (m.model == "full" ? "full model" : "slow flow") + ")")
    << " noenhanced font 'sans,13'\n"
    << "set xlabel 'platform friction μ (scaled)'\nset ylabel 'initial phase difference ψ₀'\n"
    << "set xrange [" << gnuplotNumber(x.values.front() - cx / 2) << ":"
    << gnuplotNumber(x.values.back() + cx / 2) << "]\nset yrange ["
    << gnuplotNumber(y.values.front() - cy / 2) << ":" << gnuplotNumber(y.values.back() + cy / 2)
    << "]\n"
    << piTics("y", 0.0, 2 * kPi) << "set rmargin at screen 0.74\n"
    << "set key at screen 0.76, graph 1 left top Left reverse noenhanced title 'regime' samplen "
       "1.5\n"
    << arrows << "plot " << gnuplotQuote(data_path) << " using 1:2:3:4:5 with rgbimage notitle";
  // exp1's two panels: psi0 = 0 (in-phase start) and psi0 = pi (antiphase start)
  s << ", \\\n     0 with lines dt 2 lw 2 lc rgb '#000000' title 'exp1 panels: ψ₀ = 0, π'"
    << ", \\\n     pi with lines dt 2 lw 2 lc rgb '#000000' notitle";
  if (!ctx.mu_experiment.empty())
    s << ", \\\n     keyentry with lines dt 3 lw 2 lc rgb '#000000' title 'the experiment''s "
         "platforms'";
  for (const auto& name : legend)
    s << ", \\\n     keyentry with boxes fill solid 1.0 border lc rgb '#606060' fc rgb '"
      << regimeColour(name, legend) << "' title " << gnuplotQuote(name);
  s << "\nset output\n";
  return s.str();
}

namespace {

std::string commandFor(const std::string& id, const FiguresContext& ctx) {
  return "metrosync figures --only " + id + " --model " + ctx.models + ctx.options;
}

// one picture in both formats; the names written
std::vector<std::string> drawBoth(
    const OutputDir& dir, const std::string& name, const std::string& data,
    const std::function<std::string(const std::string&, const std::string&, bool)>& script) {
  std::vector<std::string> files;
  for (bool svg : {false, true}) {
    const std::string file = name + (svg ? ".svg" : ".png");
    if (drawPng(dir, file, data,
                [&](const std::string& d, const std::string& out) { return script(d, out, svg); }))
      files.push_back(file);
  }
  return files;
}

}  // namespace

nlohmann::json figuresJson(const std::vector<FigureResult>& figures,
                           const std::vector<RegimeMapResult>& maps, const FiguresContext& ctx) {
  nlohmann::json j;
  j["version"] = metrosyncVersion();
  j["model"] = ctx.models;
  j["figures"] = nlohmann::json::array();
  for (const auto& f : figures) {
    nlohmann::json runs = nlohmann::json::array();
    for (const auto& r : f.runs) {
      nlohmann::json jr = {{"scenario", r.curve.scenario}, {"label", r.curve.label}};
      if (r.has_slow) jr["slow"] = modelRunJson(r.slow);
      if (r.has_full) jr["full"] = modelRunJson(r.full);
      runs.push_back(jr);
    }
    j["figures"].push_back({{"id", f.spec.id},
                            {"title", f.spec.title},
                            {"caption", f.spec.caption},
                            {"erratum", f.spec.erratum},
                            {"command", commandFor(f.spec.id, ctx)},
                            {"files", {f.spec.id + ".png", f.spec.id + ".svg"}},
                            {"runs", runs}});
  }
  j["maps"] = nlohmann::json::array();
  for (const auto& m : maps) {
    nlohmann::json counts = nlohmann::json::object();
    for (const auto& [g, p] : m.points) counts[p.regime] = counts.value(p.regime, 0) + 1;
    j["maps"].push_back({{"id", m.spec.id},
                         {"model", m.model},
                         {"files", {m.name + ".png", m.name + ".svg"}},
                         {"sweep", m.sweep_dir},
                         {"grid", m.grid.toJson()},
                         {"complete", m.complete},
                         {"regimes", counts},
                         {"command", commandFor(m.spec.id, ctx)}});
  }
  return j;
}

namespace {

std::string figuresMarkdown(const std::vector<FigureResult>& figures,
                            const std::vector<RegimeMapResult>& maps, const FiguresContext& ctx) {
  std::ostringstream md;
  md << "# The paper's section-4 figures, computed\n\n"
     << "Made by `metrosync figures --model " << ctx.models << ctx.options << "` (metrosync "
     << metrosyncVersion() << "). Each figure is a PNG and an SVG; the "
     << "command under it makes that figure alone. The numbers (every run's final state and "
     << "regime) are in figures.json.\n\n";
  for (const auto& f : figures) {
    md << "## " << f.spec.id << "\n\n![" << f.spec.id << "](" << f.spec.id << ".png)\n\n"
       << f.spec.caption << " Curves: ";
    for (size_t k = 0; k < f.runs.size(); ++k)
      md << (k ? ", " : "") << f.runs[k].curve.label << " (`yaml/rigs/paper/"
         << f.runs[k].curve.scenario << ".yaml`)";
    md << ". " << (ctx.models == "both" ? "Full model solid, slow flow dashed, " : "")
       << "epsilon = " << gnuplotNumber(f.runs.empty() ? 0 : f.runs[0].scaled.epsilon) << ".\n\n";
    if (!f.spec.erratum.empty()) md << "*Erratum:* " << f.spec.erratum << ".\n\n";
    md << "Files: [" << f.spec.id << ".png](" << f.spec.id << ".png), [" << f.spec.id << ".svg]("
       << f.spec.id << ".svg)\n\n```sh\n"
       << commandFor(f.spec.id, ctx) << "\n```\n\n";
  }
  for (const auto& m : maps) {
    md << "## " << m.name << "\n\n![" << m.name << "](" << m.name << ".png)\n\n"
       << m.spec.caption << " " << (m.model == "full" ? "Full model" : "Slow flow") << ", "
       << m.grid.axes()[0].count << " x " << m.grid.axes()[1].count
       << " grid; the sweep's files (regimes.csv, sweep.json) in " << m.sweep_dir << "/.\n\n"
       << "Files: [" << m.name << ".png](" << m.name << ".png), [" << m.name << ".svg](" << m.name
       << ".svg)\n\n```sh\n"
       << commandFor(m.spec.id, ctx) << "\n```\n\n";
  }
  return md.str();
}

}  // namespace

std::vector<std::string> writeFigures(const OutputDir& dir,
                                      const std::vector<FigureResult>& figures,
                                      const std::vector<RegimeMapResult>& maps,
                                      const FiguresContext& ctx) {
  std::vector<std::string> files;
  for (const auto& f : figures)
    for (const auto& name : drawBoth(dir, f.spec.id, figureData(f),
                                     [&](const std::string&d, const std::string&out, bool svg) {
                                       return paperFigureScript(f, d, out, svg);
                                     }))
      files.push_back(name);
  for (const auto& m : maps) {
    std::vector<std::string> legend = regimeLegendOrder(m.points);
    for (const auto& name : drawBoth(dir, m.name, mapData(m, legend),
                                     [&](const std::string&d, const std::string&out, bool svg) {
                                       return mapScript(m, ctx, legend, d, out, svg);
                                     }))
      files.push_back(name);
  }
  writeFileAtomically(dir.file("figures.md"), figuresMarkdown(figures, maps, ctx));
  writeFileAtomically(dir.file("figures.json"), figuresJson(figures, maps, ctx).dump(2) + "\n");
  files.push_back("figures.md");
  files.push_back("figures.json");
  return files;
}

}  // namespace metrosync
