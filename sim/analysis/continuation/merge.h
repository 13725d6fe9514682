// Each branch and each bifurcation once: `continue --all` starts from every locked state Newton
// finds, so one branch is reached from several starts (both ends of an S-shaped branch at the
// start value, both members of a family), and branch switching reaches a branch again from each
// branch crossing it. Two branches followed both ways to the ends of the range are the same
// curve when most points of one lie on the other; a special point found on symmetric copies of a
// state (identical metronomes exchanged) is one bifurcation.
#pragma once

#include <vector>

#include "sim/analysis/continuation/result.h"

namespace metrosync::continuation {

// Whether the state (A, psi) at parameter p lies on a branch already in r (on one of its
// segments, the parameter in units of span) or in one of its families' extents.
bool alreadyFollowed(const ContinuationResult& r, double p, const std::vector<double>& A,
                     const std::vector<double>& psi, double span);

// Drops every branch most of whose points lie on an earlier one (and its points, special
// points, family), renumbers the rest in order; then keeps one of each set of special points
// of the same type at the same parameter and the same amplitudes up to order, saying in its
// detail how many copies it stands for.
void mergeDuplicates(ContinuationResult& r);

// Whether a curve of `kind` in `curves` passes within kSameCurve of (p1, p2) in the plane
// (units: the spans of the two keys).
bool onACurve(const std::vector<FoldCurve>& curves, CurveKind kind, double p1, double p2,
              double span1, double span2);

// Drops every curve most of whose points lie on an earlier curve of the same kind.
void mergeCurves(std::vector<FoldCurve>& curves, double span1, double span2);

}  // namespace metrosync::continuation
