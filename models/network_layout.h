// The full model's state vector, one layout for every rig (issue 38: a board is a network of one):
//   x_p, xdot_p for every platform (file order),
//   theta_j then thetadot_j for every swinging pendulum (file order over the network),
//   then the energy ledger's quadratures: the work of the pivot dampers, of friction and, only when
//   the network has a damper (a ground damper under a platform or a damped coupling), of the
//   dampers (J).
// A single rig is a network of one platform on the table without a damper: x, xdot, the angles,
// the rates and two quadratures, the layout the single rig always had.
#pragma once

namespace metrosync::network {

struct Layout {
  int platforms = 0, n = 0;  // platforms, swinging pendulums
  bool dampers = false;      // a damper somewhere: the ledger has its slot
  int x(int p) const { return 2 * p; }
  int v(int p) const { return 2 * p + 1; }
  int theta(int j) const { return 2 * platforms + j; }
  int omega(int j) const { return 2 * platforms + n + j; }
  int dampingWork() const { return 2 * platforms + 2 * n; }
  int frictionWork() const { return dampingWork() + 1; }
  int damperWork() const { return dampingWork() + 2; }  // only with dampers
  int dim() const { return dampingWork() + (dampers ? 3 : 2); }
  // the dampers' work in y (0 without a damper)
  double damperWorkIn(const double* y) const { return dampers ? y[damperWork()] : 0.0; }
};

}  // namespace metrosync::network
