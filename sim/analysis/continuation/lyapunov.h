// The first Lyapunov coefficient l1 of a Hopf point of x' = f(x) (Kuznetsov, Elements of Applied
// Bifurcation Theory, eq. 3.20 / 8.23):
//   l1 = Re[ <p, C(q,q,qbar)> - 2 <p, B(q, A^-1 B(q,qbar))> + <p, B(qbar, (2 i w - A)^-1 B(q,q))> ]
//        / (2 w)
// with A q = i w q, A^T p = -i w p, <p, q> = pbar . q = 1, |q| = 1; B, C the second and third
// derivatives of f, here by central differences. l1 < 0: supercritical (a stable cycle is born),
// l1 > 0: subcritical. For x' = b x - y + s x r^2, y' = x + b y + s y r^2: l1 = 2 s (|q| = 1).
#pragma once

#include <functional>

#include "sim/analysis/continuation/system.h"

namespace metrosync::continuation {

// NaN when A = f'(y0) has no eigenvalue pair +-i w (w > 0) near the imaginary axis.
double firstLyapunovCoefficient(const std::function<Vec(const Vec&)>& f, const Vec& y0);

}  // namespace metrosync::continuation
