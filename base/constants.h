// The mathematical constants, defined once for every library (base/ sits below contact/ in the
// layout's order: anything may include it, it includes nothing of the project).
#pragma once

namespace metrosync {

// pi and 2 pi as the nearest doubles (M_PI is POSIX, not C++17)
constexpr double kPi = 3.141592653589793;
constexpr double kTwoPi = 6.283185307179586;
static_assert(kTwoPi == 2 * kPi, "2 pi is pi doubled exactly");

}  // namespace metrosync
