// branches.png of `metrosync continue`: the bifurcation diagram as AUTO and MatCont draw it.
// Two panels against KEY: the amplitudes A_i (top) and the phase differences psi_j (bottom).
//   - one colour per branch (kBranchColours, in branch order); stable solid, unstable dashed;
//   - one marker and line width per metronome, so that curves that coincide (A_1 = A_2 for
//     identical metronomes in phase) both stay visible: the wider line under the narrower one,
//     their markers side by side;
//   - special points marked and labelled: LP (fold), H sub / H sup (Hopf, by the sign of the
//     first Lyapunov coefficient), BP (branch point), B (a border of the vector field);
//   - a neutral family's extent in psi as a band in its branch's colour;
//   - the limit cycles: the maximum and minimum of each A_i over the orbit, thin, in the colour
//     of the branch of their Hopf point (stable solid, unstable dashed), LPC at a confirmed fold.
#pragma once

#include <string>

#include "sim/analysis/continuation/result.h"

namespace metrosync {

// The gnuplot data as datablocks (the script loads them): $b<branch>c<column> for each branch
// and column of A_1..A_N, psi_2..psi_N (2..2N: KEY, the value, the value where stable and where
// unstable, else nan), $special (KEY,
// A_1..A_N, psi_2..psi_N, stable, the label, the largest A), $family<f> (KEY, psi_min_j,
// psi_max_j), $cycle<c> (KEY, A_min_i, A_max_i, stable) and $lpc, the confirmed folds of cycles
// (KEY, A_max).
std::string continuationDiagramData(const continuation::ContinuationResult& r);
std::string continuationDiagramScript(const continuation::ContinuationResult& r,
                                      const std::string& data, const std::string& png);

// The branch colours, in order (repeating past the last).
extern const char* const kBranchColours[10];

}  // namespace metrosync
