// Work-precision arithmetic: medians, the cheapest-time-for-an-error front of a set of runs, and
// time ratios at equal error between two fronts (log-log interpolation, never extrapolation).
#pragma once

#include <string>
#include <vector>

#include "base/number_text.h"

namespace metrosync::bench {

// numberText(v, precision, notation) (base/number_text.h); "" for a NaN or an infinity (an empty
// table cell).
std::string benchNumber(double v, int precision, Notation notation = Notation::General);
// A CSV field: quoted (quotes doubled) when it holds a comma or a quote.
std::string csvField(const std::string& s);

double median(std::vector<double> v);  // NaN for an empty vector

// A target's verdict over `measured` rows of which `met` meet it: "met in all N rows", "NOT met
// in K of N rows" (K the rows that miss it), "not measured" (no row).
std::string rowsVerdict(int met, int measured);

// One (error, time) point of a work-precision curve.
struct WorkPoint {
  double error = 0.0;
  double time_s = 0.0;
};

// The front of `points`: for each error level, the cheapest run that reaches it. Sorted by error
// ascending, time strictly descending; points with a non-finite or non-positive error or time are
// dropped.
std::vector<WorkPoint> paretoFront(std::vector<WorkPoint> points);

// Time to reach `error` on a front, interpolated linearly in log(error), log(time) between the
// front's points; NaN outside [front.front().error, front.back().error].
double timeAtError(const std::vector<WorkPoint>& front, double error);

// Time ratio a / b at equal error, where both fronts cover the error.
struct EqualErrorRatio {
  double error = 0.0;
  double time_a_s = 0.0, time_b_s = 0.0;
  double ratio() const { return time_a_s / time_b_s; }
};

// The ratio at every decade 10^k and at both ends of the overlap of the two fronts' error ranges
// (ascending error); empty when the ranges do not overlap.
std::vector<EqualErrorRatio> ratiosAtEqualError(const std::vector<WorkPoint>& a,
                                                const std::vector<WorkPoint>& b);

// Geometric mean of the ratios (NaN for none).
double geometricMeanRatio(const std::vector<EqualErrorRatio>& r);

}  // namespace metrosync::bench
