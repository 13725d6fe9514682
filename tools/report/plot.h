// PNG plots through gnuplot (pngcairo terminal): what a reader of the paper wants to see.
//   envelope plot:   amplitudes A_i against tau with the escapement threshold theta_c (top) and
//                    the phase differences psi_j against tau with guides at pi and 2 pi (bottom;
//                    absent for N = 1), as in the paper's simulation figures
//   comparison plot: the same panels, full model (solid) over the slow flow (dashed)
// The data, the script and gnuplot's log go to a private temporary folder in the output directory
// (sim/record/private_dir.h), gnuplot draws into a PNG there that is renamed into place when
// complete. A missing or failing gnuplot is a warning on stderr, never an
// error: the run's results do not depend on its plots.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "sim/record/envelope.h"
#include "tools/report/outputs.h"

namespace metrosync {

// Text in a gnuplot script: a string in single quotes (a quote doubled), a number as %.10g with
// NaN as gnuplot's NaN (a gap in a curve, an empty map cell).
std::string gnuplotQuote(const std::string& s);
std::string gnuplotNumber(double v);
// A tic label for k halves of pi: "0", "π/2", "π", "3π/2", "2π", "-π", ...
std::string halfPiLabel(long k);

// Full path of `name` found on $PATH (executable), or "" when absent.
std::string findExecutable(const std::string& name);

class PrivateDir;
// Runs `gnuplot script` (stdin and stdout to /dev/null, stderr to `tmp`'s file "log", `tmp` as
// the child's descriptor kChildDirFd); returns gnuplot's exit status, or -1 if it could not run.
int runGnuplot(const std::string& gnuplot, const std::string& script, const PrivateDir& tmp);

// Draws DIR/png_name: writes `data` to a private temporary folder in DIR, runs the gnuplot script
// that script(data_path, png_path) returns, renames the PNG into place. A missing gnuplot (said
// once per process) or a failing one is a warning; returns true when the PNG was written.
bool drawPng(const OutputDir& dir, const std::string& png_name, const std::string& data,
             const std::function<std::string(const std::string&, const std::string&)>& script);
// ... the data written by `data` as it goes (never held whole in memory).
bool drawPngFrom(const OutputDir& dir, const std::string& png_name,
                 const std::function<void(std::ostream&)>& data,
                 const std::function<std::string(const std::string&, const std::string&)>& script);

// How the envelope and comparison plots are drawn (docs/outputs.md).
struct PlotStyle {
  std::string format = "png";    // png (pngcairo), svg or pdf (pdfcairo): --plot-format
  double seconds_per_tau = 0.0;  // > 0 (a physical rig): x in seconds, tau on the top axis
};
// Above this many metronomes the amplitude panel is a heatmap of A_i(tau), not one line each.
constexpr int kHeatmapAbove = 8;
// The plot formats --plot-format takes.
const std::vector<std::string>& plotFormats();
// gnuplot's `set terminal` line for `format` at the size of a width x height pixel PNG.
std::string plotTerminal(const std::string& format, int width_px, int height_px);

// The x axis of a plot against time: from 0 to exactly tau_max (no axis past the data), in tau,
// or with style.seconds_per_tau > 0 in seconds with tau on the top axis; and gnuplot's x of a
// data column holding tau (`expr`, e.g. "$1").
std::string timeAxis(const PlotStyle& style, double tau_max);
std::string timeOf(const PlotStyle& style, const std::string& expr);

// Returns true when DIR/png_name was written. theta_c: (N x 1) scaled critical angles.
bool plotEnvelope(const OutputDir& dir, const std::string& png_name,
                  const std::vector<EnvelopeRow>& rows, const std::vector<double>& theta_c,
                  const std::string& title, const PlotStyle& style = {});

bool plotComparison(const OutputDir& dir, const std::string& png_name,
                    const std::vector<EnvelopeRow>& full, const std::vector<EnvelopeRow>& slow,
                    const std::vector<double>& theta_c, const std::string& title,
                    const PlotStyle& style = {});

// The gnuplot script of a plot (exposed for tests): reads `data_path` (blocks of rows
// "tau A_1..A_N psi_2..psi_N", one block per model; above kHeatmapAbove metronomes one more
// block of heatmap cells "tau_lo tau_hi i A_i" for the first model), writes `png_path`.
std::string gnuplotScript(const std::string& data_path, const std::string& png_path, int n,
                          int blocks, const std::vector<double>& theta_c, double tau_max,
                          double psi_lo, double psi_hi, const std::string& title,
                          const PlotStyle& style = {});

}  // namespace metrosync
