// The pictures of a sweep (PNG through gnuplot, as tools/report/plot.h): what a reader of the
// paper's figure exp1 wants to see, computed.
//   regimes.png     the regime of every grid point, one colour per regime, with a legend: a map
//                   over the two varied keys (first --vary across, second up), or for one key a
//                   strip of coloured cells along it
//   amplitudes.png  final A_i (the first four metronomes): maps, or lines against the key
//   phases.png      final psi_j in [0, 2 pi) (the first four): maps with a cyclic palette, or
//                   points against the key
//   order.png       final order parameter r (N >= 3 only)
//   drive.png       log10 of the final drive strength s = |Z| / mu of a Coulomb platform: below 0
//                   the platform sticks and the metronomes are uncoupled (the paper's exp1)
// A grid of more than two axes: the maps draw two (--map KEY1,KEY2; default the first two), and
// each combination of the other axes' values gets its own files, named after it:
// regimes--KEY3=V.png, regimes--KEY3=V--KEY4=W.png, ... ('*' of a wildcard key written "all").
// Grid points not run (an incomplete sweep or merge) are left white; failed points are drawn in
// the regime map only. A missing or failing gnuplot is a warning, never an error.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "sim/analysis/continuation/fold_curve.h"
#include "sim/analysis/sweep.h"
#include "tools/report/outputs.h"
#include "tools/report/sweep_files.h"

namespace metrosync {

// The file names the maps may have, in every plot format (for removing stale ones).
const std::vector<std::string>& sweepMapNames();
// Is `name` the map of one slice of an N-D sweep (STEM--....png, STEM a map's name)?
bool isSweepSliceMapName(const std::string& name);

// An N-D sweep draws at most this many slices (combinations of the axes not drawn); more: the
// slices of the first values only, with a warning.
constexpr long kMaxMapSlices = 64;

// A grid of more points than this gets no maps: the pictures are ~1000 pixels across, so a finer
// grid cannot be seen, and its gnuplot data (~60 bytes a cell) would cost more memory than the
// sweep itself.
constexpr long kMaxMapCells = 1000000;

// The points of a sweep, visited one at a time (each index once; any order): read again for each
// slice, so that memory is bounded by a slice's cells (a fixed size each), not by the points. The
// second argument, when set, says from a regimes.csv line whether its point is wanted (a cheap
// test of its key columns): the others may be skipped unparsed.
using SweepPointSource = std::function<void(const std::function<void(const SweepPoint&)>&,
                                            const std::function<bool(const std::string&)>&)>;

// Draws the maps into `dir` (none for a grid over kMaxMapCells); returns the names of the files
// written.
// `boundaries` (sweep --boundaries): fold and Hopf curves in the plane of the first two axes,
// drawn over the regime map (folds solid, Hopf curves dashed). `map_axes`: the axes drawn
// (mapAxes, sim/analysis/sweep.h); empty: the default.
std::vector<std::string> plotSweepMaps(const OutputDir& dir, const SweepGrid& grid, int n,
                                       const SweepPointSource& points, const std::string& title,
                                       const std::string& format = "png",  // --plot-format
                                       const std::vector<continuation::FoldCurve>& boundaries = {},
                                       const std::vector<size_t>& map_axes = {});

// The colours of the boundary curves on the maps (sweep --boundaries): fold and Hopf curves,
// each over a white halo; no regime is drawn in either.
extern const char* const kFoldCurveColour;
extern const char* const kHopfCurveColour;
// The colours of the regimes with fixed colours and the palette of the others.
std::vector<std::string> regimeColours();

// boundaries.csv: `curve,type,KEY1,KEY2`, one row per point of each curve in order along it.
std::string boundariesCsv(const std::vector<continuation::FoldCurve>& curves,
                          const std::string& key1, const std::string& key2);
// sweep.json's `boundaries`: [{curve, type, points, end_backward, end_forward}], with
// `failure` and `seed` (KEY1, KEY2) for a curve that could not be followed.
nlohmann::json boundariesJson(const std::vector<continuation::FoldCurve>& curves);

// The colour of a regime name (#rrggbb): fixed for the SPEC names and `failed`, from a palette in
// the order given for the others. `names` are the regimes present, in legend order.
std::vector<std::string> regimeLegendOrder(const std::map<long, SweepPoint>& points);
// ... from each regime's count of points
std::vector<std::string> regimeLegendOrder(const std::map<std::string, long>& count);
std::string regimeColour(const std::string& name, const std::vector<std::string>& legend);

// The gnuplot script of the regime map (exposed for tests).
std::string regimeMapScript(const std::string& data_path, const std::string& png_path,
                            const SweepGrid& grid, const std::vector<std::string>& legend,
                            const std::string& title, const std::string& format = "png",
                            const std::vector<continuation::FoldCurve>& boundaries = {},
                            const std::vector<size_t>& map_axes = {});

}  // namespace metrosync
