#include "tools/report/plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ext/stdio_filebuf.h>
#include <fstream>
#include <iostream>
#include <sstream>

#include "base/constants.h"
#include "base/number_text.h"
#include "sim/record/private_dir.h"

extern char** environ;

namespace metrosync {

namespace {

// one colour per metronome (colour-blind friendly order), cycled beyond eight
const char* const kColours[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                "#e69f00", "#56b4e9", "#000000", "#f0e442"};

const char* colour(int i) {
  return kColours[i % 8];
}

// ytics at multiples of pi (or pi/2) so that phase plots read in units of pi
std::string piTics(double lo, double hi) {
  const double span_halves = (hi - lo) / (kPi / 2);
  long step = 1;  // in halves of pi
  for (long s : {1L, 2L, 4L, 10L, 20L, 40L, 100L, 200L, 400L, 1000L}) {
    step = s;
    if (span_halves / s <= 10) break;
  }
  std::string tics;
  const long k0 = static_cast<long>(std::ceil(lo / (kPi / 2) / step)) * step;
  for (long k = k0; k * (kPi / 2) <= hi + 1e-12 && tics.size() < 4000; k += step)
    tics += (tics.empty() ? "" : ", ") + std::string("\"") + halfPiLabel(k) + "\" " +
            gnuplotNumber(k * kPi / 2);
  return "set ytics (" + tics + ")\n";
}

void warn(const std::string& what) {
  std::cerr << "metrosync: warning: " << what << "\n";
}

// The heatmap's cells: row k spans half-way to its neighbours in tau, at most kCells rows.
void heatmapData(std::ostringstream& out, const std::vector<EnvelopeRow>& rows) {
  constexpr size_t kCells = 600;
  const size_t stride = rows.size() / kCells + 1;
  std::vector<const EnvelopeRow*> kept;
  for (size_t k = 0; k < rows.size(); k += stride) kept.push_back(&rows[k]);
  if (!rows.empty() && kept.back() != &rows.back()) kept.push_back(&rows.back());
  for (size_t k = 0; k < kept.size(); ++k) {
    const double tau = kept[k]->tau;
    const double lo = k ? (kept[k - 1]->tau + tau) / 2 : tau;
    const double hi = k + 1 < kept.size() ? (tau + kept[k + 1]->tau) / 2 : tau;
    for (size_t i = 0; i < kept[k]->A.size(); ++i)
      out << gnuplotNumber(lo) << ' ' << gnuplotNumber(hi) << ' ' << i + 1 << ' '
          << gnuplotNumber(kept[k]->A[i]) << '\n';
  }
  if (kept.empty()) out << "nan\n";
}

std::string envelopeData(const std::vector<const std::vector<EnvelopeRow>*>& blocks, int n) {
  std::ostringstream out;
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (b) out << "\n\n";  // gnuplot: two blank lines separate data blocks (`index`)
    if (blocks[b]->empty()) {
      // an empty block keeps its `index`: one undefined point (a model that wrote no row)
      out << "nan\n";
      continue;
    }
    for (const auto& r : *blocks[b]) {
      out << gnuplotNumber(r.tau);
      for (double a : r.A) out << ' ' << gnuplotNumber(a);
      for (double p : r.psi) out << ' ' << gnuplotNumber(p);
      out << '\n';
    }
  }
  if (n > kHeatmapAbove) {
    out << "\n\n";
    heatmapData(out, *blocks[0]);
  }
  return out.str();
}

// The first `count` lines of `text` that say something, joined with " | ".
std::string firstLines(const std::string& text, int count) {
  std::istringstream in(text);
  std::string line, joined;
  for (int k = 0; k < count && std::getline(in, line);) {
    if (line.find_first_not_of(" \t^") == std::string::npos) continue;
    joined += (joined.empty() ? "" : " | ") + line;
    ++k;
  }
  return joined;
}

bool drawPlot(const OutputDir& dir, const std::string& png_name,
              const std::vector<const std::vector<EnvelopeRow>*>& blocks,
              const std::vector<double>& theta_c, const std::string& title,
              const PlotStyle& style) {
  int n = 0;
  double psi_lo = 0.0, psi_hi = 2 * kPi, tau_max = 0.0;
  bool any = false;
  for (const auto* b : blocks)
    for (const auto& r : *b) {
      n = static_cast<int>(r.A.size());
      any = true;
      if (std::isfinite(r.tau)) tau_max = std::max(tau_max, r.tau);
      for (double p : r.psi)
        if (std::isfinite(p)) psi_lo = std::min(psi_lo, p), psi_hi = std::max(psi_hi, p);
    }
  if (!any) {
    if (!findExecutable("gnuplot").empty())
      warn(png_name + " not written: no envelope row to plot");
    return false;
  }
  return drawPng(dir, png_name, envelopeData(blocks, n),
                 [&](const std::string& data_path, const std::string& png_path) {
                   return gnuplotScript(data_path, png_path, n, static_cast<int>(blocks.size()),
                                        theta_c, tau_max, psi_lo, psi_hi, title, style);
                 });
}

}  // namespace

bool drawPng(const OutputDir& dir, const std::string& png_name, const std::string& data,
             const std::function<std::string(const std::string&, const std::string&)>& script) {
  return drawPngFrom(
      dir, png_name, [&](std::ostream& out) { out << data; }, script);
}

bool drawPngFrom(const OutputDir& dir, const std::string& png_name,
                 const std::function<void(std::ostream&)>& data,
                 const std::function<std::string(const std::string&, const std::string&)>& script) {
  const std::string gnuplot = findExecutable("gnuplot");
  if (gnuplot.empty()) {
    static bool warned = false;
    if (!warned) warn("gnuplot not found on PATH: plots are skipped");
    warned = true;
    return false;
  }
  // every file gnuplot opens lies in a private folder it reaches through a descriptor
  // (sim/record/private_dir.h): nothing is reopened by a name someone else could replace
  int rc = -1;
  try {
    PrivateDir tmp(dir.path());
    {
      __gnu_cxx::stdio_filebuf<char> buf(tmp.createOpen("data"), std::ios::out);  // closes it
      std::ostream out(&buf);
      data(out);
      if (!out.flush()) throw std::runtime_error("cannot write the data of " + png_name);
    }
    tmp.create("log");
    tmp.create("plot.gp", script(PrivateDir::childPath("data"), PrivateDir::childPath("out")));
    rc = runGnuplot(gnuplot, PrivateDir::childPath("plot.gp"), tmp);
    if (rc != 0 || tmp.size("out") <= 0) {
      const std::string why = firstLines(tmp.read("log"), 3);
      warn(png_name + " not written: gnuplot failed" + (why.empty() ? "" : ": " + why));
      return false;
    }
    if (!tmp.publish("out", dir.file(png_name))) {
      warn(png_name + " not written: cannot rename its temporary file");
      return false;
    }
  } catch (const std::runtime_error& e) {
    warn(png_name + " not written: " + e.what());
    return false;
  }
  return true;
}

int runGnuplot(const std::string& gnuplot, const std::string& script, const PrivateDir& tmp) {
  const int log = tmp.openForWriting("log");
  if (log < 0) return -1;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&fa, log, 2);
  posix_spawn_file_actions_adddup2(&fa, tmp.fd(), kChildDirFd);
  std::vector<char*> argv = {const_cast<char*>(gnuplot.c_str()), const_cast<char*>(script.c_str()),
                             nullptr};
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, gnuplot.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  ::close(log);
  if (rc != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string halfPiLabel(long k) {
  if (k == 0) return "0";
  const std::string sign = k < 0 ? "-" : "";
  const long a = std::labs(k);
  if (a % 2 == 1) return sign + (a == 1 ? "" : std::to_string(a)) + "π/2";
  return sign + (a == 2 ? "" : std::to_string(a / 2)) + "π";
}

std::string gnuplotQuote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

std::string gnuplotNumber(double v) {
  return std::isnan(v) ? std::string("NaN") : numberText(v, 10);
}

std::string findExecutable(const std::string& name) {
  if (name.find('/') != std::string::npos) return ::access(name.c_str(), X_OK) == 0 ? name : "";
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "");
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
        ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return "";
}

const std::vector<std::string>& plotFormats() {
  static const std::vector<std::string> formats = {"png", "svg", "pdf"};
  return formats;
}

std::string plotTerminal(const std::string& format, int width_px, int height_px) {
  std::ostringstream s;
  if (format == "svg")
    s << "set terminal svg size " << width_px << "," << height_px
      << " enhanced font 'sans,11' linewidth 1.2 background rgb 'white'\n";
  else if (format == "pdf")  // 100 pixels an inch: the PNG's proportions and type size
    s << "set terminal pdfcairo size " << gnuplotNumber(width_px / 100.0) << "in,"
      << gnuplotNumber(height_px / 100.0) << "in enhanced font 'sans,11' linewidth 1.2\n";
  else
    s << "set terminal pngcairo size " << width_px << "," << height_px
      << " enhanced font 'sans,11' linewidth 1.2\n";
  return s.str();
}

// The x axis: tau, or seconds with tau on the top axis (style.seconds_per_tau > 0).
std::string timeAxis(const PlotStyle& style, double tau_max) {
  const double k = style.seconds_per_tau;
  const double hi = tau_max > 0 ? tau_max : 1;
  std::ostringstream s;
  if (k > 0) {
    // both axes start at 0 and span the same run: tau on top at its own round tics
    s << "set xrange [0:" << gnuplotNumber(hi * k) << "]\nset x2range [0:" << gnuplotNumber(hi)
      << "]\n"
      << "set xtics nomirror\nset x2tics\n"
      << "set xlabel 'time (s); top axis: slow time τ'\n";
  } else {
    s << "set xrange [0:" << gnuplotNumber(hi) << "]\nset xlabel 'slow time τ'\n";
  }
  return s.str();
}

// gnuplot's x value of a data row whose tau is `expr`
std::string timeOf(const PlotStyle& style, const std::string& expr) {
  return style.seconds_per_tau > 0 ? "((" + expr + ")*" + gnuplotNumber(style.seconds_per_tau) + ")"
                                   : "(" + expr + ")";
}

namespace {

// What a panel needs: the data, its shape, the style; `plot` collects one `plot` command.
struct Panel {
  const std::string& data;
  int n, blocks;
  const PlotStyle& style;
  std::string plot;
  void add(const std::string& item) { plot += (plot.empty() ? "plot " : ", \\\n     ") + item; }
  bool compare() const { return blocks == 2; }
  std::string model(int b) const {
    static const char* const names[] = {"full", "slow"};
    return compare() ? std::string(" ") + names[b] : "";
  }
  std::string lines(int b, int column) const {
    return gnuplotQuote(data) + " index " + std::to_string(b) + " using " + timeOf(style, "$1") +
           ":" + std::to_string(column) + " with lines lw " + (b == 0 ? "2" : "1.5") + " dt " +
           (b == 0 ? "1" : "2");
  }
};

// One row of cells per metronome, coloured by A_i (the first model's, in a comparison).
std::string heatmapPanel(Panel& p) {
  std::ostringstream s;
  s << "set ylabel 'metronome i" << (p.compare() ? " (full model)" : "") << "'\n"
    << "set yrange [0.5:" << p.n + 0.5 << "]\nset cbrange [0:*]\n"
    << "set cblabel 'amplitude A_i (scaled)'\n"
    << "set palette defined (0 '#440154', 1 '#3b528b', 2 '#21918c', 3 '#5ec962', 4 '#fde725')\n";
  p.add(gnuplotQuote(p.data) + " index " + std::to_string(p.blocks) + " using " +
        timeOf(p.style, "($1+$2)/2") + ":3:" + timeOf(p.style, "$1") + ":" + timeOf(p.style, "$2") +
        ":($3-0.5):($3+0.5):4 with boxxyerror fs solid 1.0 noborder lc palette notitle");
  s << p.plot << "\nunset colorbox\nunset cblabel\n";
  return s.str();
}

// Amplitudes, with the escapement threshold: below theta_c a metronome is dead (SPEC 4).
std::string amplitudePanel(Panel& p, const std::vector<double>& theta_c) {
  std::ostringstream s;
  s << "set ylabel 'amplitude A_i (scaled)'\nset yrange [0:*]\n";
  for (int b = 0; b < p.blocks; ++b)
    for (int i = 0; i < p.n; ++i)
      p.add(p.lines(b, 2 + i) + " lc rgb '" + colour(i) + "' title 'A_" + std::to_string(i + 1) +
            p.model(b) + "'");
  std::vector<double> levels;
  for (double tc : theta_c)
    if (std::none_of(levels.begin(), levels.end(),
                     [&](double l) { return std::fabs(l - tc) < 1e-9; }))
      levels.push_back(tc);
  for (size_t k = 0; k < levels.size(); ++k)
    p.add(gnuplotNumber(levels[k]) + " with lines dt 3 lw 1.5 lc rgb '#555555' " +
          (k == 0 ? "title 'θ_c'" : "notitle"));
  s << p.plot << "\n";
  return s.str();
}

// Phase differences, in units of pi, with guides at pi (antiphase) and 2 pi (in-phase); above
// kHeatmapAbove metronomes one key entry for them all.
std::string phasePanel(Panel& p, double psi_lo, double psi_hi) {
  std::ostringstream s;
  const double pad = 0.04 * (psi_hi - psi_lo);
  s << "set ylabel 'phase difference ψ_j = φ_1 - φ_j (rad)'\n"
    << "set yrange [" << gnuplotNumber(psi_lo - pad) << ":" << gnuplotNumber(psi_hi + pad) << "]\n"
    << piTics(psi_lo - pad, psi_hi + pad);
  const bool many = p.n > kHeatmapAbove;
  for (int b = 0; b < p.blocks; ++b)
    for (int j = 2; j <= p.n; ++j) {
      const std::string key =
          many ? (j == 2 ? "title 'ψ_j, j = 2..." + std::to_string(p.n) + p.model(b) + "'"
                         : std::string("notitle"))
               : "title 'ψ_" + std::to_string(j) + p.model(b) + "'";
      p.add(p.lines(b, p.n + j) + " lc rgb '" + colour(j - 1) + "' " + key);
    }
  p.add("pi with lines dt 3 lw 1.5 lc rgb '#555555' title 'π, 2π'");
  p.add("2*pi with lines dt 3 lw 1.5 lc rgb '#555555' notitle");
  s << p.plot << "\n";
  return s.str();
}

}  // namespace

std::string gnuplotScript(const std::string& data_path, const std::string& png_path, int n,
                          int blocks, const std::vector<double>& theta_c, double tau_max,
                          double psi_lo, double psi_hi, const std::string& title,
                          const PlotStyle& style) {
  std::ostringstream s;
  const int panels = n > 1 ? 2 : 1;
  s << plotTerminal(style.format, 1100, panels == 2 ? 850 : 480) << "set output "
    << gnuplotQuote(png_path) << "\n"
    << "set datafile missing 'nan'\n"
    << "set grid back lt 1 lw 0.8 lc rgb '#e4e4e4'\n"
    << "set key outside right top samplen 3\n"
    // fixed margins, so that the panels' tau axes line up whatever their keys
    << "set lmargin at screen 0.09\nset rmargin at screen 0.84\n"
    << timeAxis(style, tau_max) << "set multiplot layout " << panels << ",1 title "
    << gnuplotQuote(title) << " noenhanced font 'sans,13'\n";
  Panel top{data_path, n, blocks, style, {}};
  s << (n > kHeatmapAbove ? heatmapPanel(top) : amplitudePanel(top, theta_c));
  if (style.seconds_per_tau > 0) s << "unset x2tics\nset xtics mirror\nset xlabel 'time (s)'\n";
  if (panels == 2) {
    Panel bottom{data_path, n, blocks, style, {}};
    s << phasePanel(bottom, psi_lo, psi_hi);
  }
  s << "unset multiplot\nset output\n";
  return s.str();
}

bool plotEnvelope(const OutputDir& dir, const std::string& png_name,
                  const std::vector<EnvelopeRow>& rows, const std::vector<double>& theta_c,
                  const std::string& title, const PlotStyle& style) {
  return drawPlot(dir, png_name, {&rows}, theta_c, title, style);
}

bool plotComparison(const OutputDir& dir, const std::string& png_name,
                    const std::vector<EnvelopeRow>& full, const std::vector<EnvelopeRow>& slow,
                    const std::vector<double>& theta_c, const std::string& title,
                    const PlotStyle& style) {
  return drawPlot(dir, png_name, {&full, &slow}, theta_c, title, style);
}

}  // namespace metrosync
