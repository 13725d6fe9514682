// The full model's state vector, one layout for every rig (issue 38: a board is a network of one):
//   x_p, xdot_p for every platform (file order),
//   theta_j then thetadot_j for every swinging pendulum (file order over the network),
//   then the energy ledger's quadratures: the work of the pivot dampers, of friction and, only when
//   the network has a damper (a ground damper under a platform or a damped coupling), of the
//   dampers (J).
// A single board is a network of one platform on the table without a damper: x, xdot, the angles,
// the rates and two quadratures, the layout the single rig always had. Where it pays (the direct
// engine's run on a single board) the number of platforms is known to the compiler (BoardLayout):
// the same slots, every offset folded.
#pragma once

#include <type_traits>

namespace metrosync::network {

// P: the number of platforms known to the compiler, or 0 (known at run time).
template <int P>
struct BasicLayout {
  int platforms = P, n = 0;  // platforms, swinging pendulums
  bool dampers = false;      // a damper somewhere: the ledger has its slot
  int platformCount() const { return P > 0 ? P : platforms; }
  int x(int p) const { return 2 * p; }
  int v(int p) const { return 2 * p + 1; }
  int theta(int j) const { return 2 * platformCount() + j; }
  int omega(int j) const { return 2 * platformCount() + n + j; }
  int dampingWork() const { return 2 * platformCount() + 2 * n; }
  int frictionWork() const { return dampingWork() + 1; }
  int damperWork() const { return dampingWork() + 2; }  // only with dampers
  int dim() const { return dampingWork() + (dampers ? 3 : 2); }
  // the dampers' work in y (0 without a damper)
  double damperWorkIn(const double* y) const { return dampers ? y[damperWork()] : 0.0; }

  // the same layout with the count known (or not) to the compiler
  template <int Q>
  BasicLayout<Q> as() const {
    BasicLayout<Q> l;
    l.platforms = platforms;
    l.n = n;
    l.dampers = dampers;
    return l;
  }
  template <int Q = P, std::enable_if_t<(Q > 0), int> = 0>
  operator BasicLayout<0>() const {  // NOLINT: a known count is a count
    return as<0>();
  }
};

using Layout = BasicLayout<0>;
using BoardLayout = BasicLayout<1>;  // a single board's: one platform on the table

}  // namespace metrosync::network
