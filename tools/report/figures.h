// The files of `metrosync figures` (sim/analysis/figures/paper_figures.h), written into the output
// directory through gnuplot, PNG and SVG of each:
//   f4.1 .. f4.4   the paper's layout: A_1 (top), A_2 (middle), psi (bottom) against tau, one
//                  curve per run in the paper's colours (black, red, blue) with the varied value in
//                  the legend; the full model solid, the slow flow dashed (--model both);
//                  theta_c dashed in the amplitude panels, pi and 2 pi in the phase panel
//   exp1[-slow|-full]  the computed regime diagram: regime of each (mu, psi0) cell, exp1's two
//                  panels (psi0 = 0 and pi) dashed, the experiment's two frictions dotted
//   figures.md     the index: each figure with its caption and the command that makes it alone
//   figures.json   every run's final state and regime (the numbers of validate's summary.json)
// A missing gnuplot drops the pictures with a warning, never figures.md and figures.json.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "sim/analysis/figures/paper_figures.h"
#include "sim/analysis/sweep.h"
#include "tools/report/outputs.h"

namespace metrosync {

// A computed regime map: the sweep's grid and points, with its model.
struct RegimeMapResult {
  RegimeMapSpec spec;
  std::string model;      // "slow" or "full"
  std::string name;       // "exp1-slow"
  std::string sweep_dir;  // the sweep's own folder (regimes.csv, sweep.json), relative to --out
  SweepGrid grid;
  std::map<long, SweepPoint> points;
  bool complete = false;
};

struct FiguresContext {
  std::string models;   // "slow", "full" or "both"
  std::string options;  // the command's other options (" --quick"), for the commands shown
  std::vector<double> mu_experiment;  // the experiment's platforms, scaled (dotted in exp1)
};

// The gnuplot script of one f4.x figure (exposed for tests); `svg` chooses the terminal.
std::string paperFigureScript(const FigureResult& f, const std::string& data_path,
                              const std::string& out_path, bool svg);

// The gnuplot script of one regime map (exp1; exposed for tests): its cells from `data_path`,
// `legend` the regimes in the key's order. Every text in the key is printed as written
// (noenhanced), so ψ₀ is written with its subscript character.
std::string mapScript(const RegimeMapResult& m, const FiguresContext& ctx,
                      const std::vector<std::string>& legend, const std::string& data_path,
                      const std::string& out_path, bool svg);

// {figures: [{id, title, caption, erratum, command, files, runs: [{scenario, label, slow, full}]}],
// maps: [{id, model, ...}]}
nlohmann::json figuresJson(const std::vector<FigureResult>& figures,
                           const std::vector<RegimeMapResult>& maps, const FiguresContext& ctx);

// Draws every figure (PNG, SVG), writes figures.md and figures.json; returns the files written.
std::vector<std::string> writeFigures(const OutputDir& dir,
                                      const std::vector<FigureResult>& figures,
                                      const std::vector<RegimeMapResult>& maps,
                                      const FiguresContext& ctx);

}  // namespace metrosync
