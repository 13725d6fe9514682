// The full model's envelope (docs/outputs.md): for each fast period [2 pi k, 2 pi (k+1)] of scaled
// time, the time average of A_i = sqrt(theta_i^2 + thetadot_i^2) and of exp(i phi_i),
// phi_i = atan2(theta_i, thetadot_i) - t (phases averaged as unit complex numbers: psi comes from
// their directions), a row with tau at the middle of the period; before them the start's row (the
// instantaneous A and phases at t = 0) and after them the final row: the same averages over the
// last fast period ending at t_end, [t_end - 2 pi, t_end] (over [0, t_end] for a shorter run).
//
// The averages are integrals of the engine's interpolant. An engine hands over each smooth stretch
// of its trajectory (no impulse inside: every event window ends one), with a way to evaluate the
// state anywhere in it; each piece of a stretch between period boundaries (and the final period's
// start) is integrated by 4-point Gauss-Legendre, exact for polynomials of degree 7, so the rows
// carry the interpolant's error (the integrator's order), not a quadrature's. (The trapezoid over
// 64 interpolated samples per period that this replaces erred by up to 2e-5 in A where an impulse
// bends A(t); docs/outputs.md has the measured comparison.)
// Engine-independent: both full-model engines and the benchmark's peers feed it, in scaled units.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

#include "base/constants.h"
#include "sim/record/envelope.h"
#include "sim/record/run_report.h"
#include "sim/record/sample_ring.h"

namespace metrosync {

class EnvelopeQuadrature {
 public:
  // active[i] == false for a locked metronome (reported as A = 0, phi = 0); t_end: the run's
  // planned end (scaled time), where the final period starts 2 pi before.
  EnvelopeQuadrature(double epsilon, std::vector<bool> active, double t_end, RunSink& sink);

  // The start's row from the state at t = 0: theta, thetadot (N x 1) scaled.
  void start(const double* theta, const double* thetadot);
  // A smooth stretch [ta, tb] of scaled time (ta where the last one ended, tb >= ta), cut into
  // pieces at the period boundaries: nodes(a, b, theta, thetadot) writes the scaled angles and
  // rates at the kNodes Gauss nodes of the piece [a, b] (nodeTime(a, b, q)): theta[q * N + i].
  template <class Nodes>
  void stretch(double ta, double tb, Nodes&& nodes);
  // The same from the state at any time: state(t, theta, thetadot), N values each.
  template <class State>
  void stretchAt(double ta, double tb, State&& state) {
    stretch(ta, tb, [&](double a, double b, double* th, double* w) {
      for (int q = 0; q < kNodes; ++q) state(nodeTime(a, b, q), th + q * n_, w + q * n_);
    });
  }
  // Emits and returns the final row; call once, after the last stretch. A run stopped before its
  // planned end is averaged over the pieces of its last 2 pi (finalSpan() says how long).
  EnvelopeRow finish();

  double finalSpan() const { return final_span_; }
  long rowsWritten() const { return period_; }
  const EnvelopeRow& lastRow() const { return last_row_; }

  // the q-th Gauss node of [a, b]
  static double nodeTime(double a, double b, int q) {
    return 0.5 * (a + b) + 0.5 * (b - a) * kNode[q];
  }
  // 4-point Gauss-Legendre on [-1, 1]
  static constexpr int kNodes = 4;
  // nodes +-sqrt(3/7 -+ 2/7 sqrt(6/5)), weights (18 +- sqrt(30)) / 36
  static constexpr double kNode[kNodes] = {-0.86113631159405258, -0.33998104358485626,
                                           0.33998104358485626, 0.86113631159405258};
  static constexpr double kWeight[kNodes] = {0.34785484513745386, 0.65214515486254614,
                                             0.65214515486254614, 0.34785484513745386};

 private:
  // sums of A_i and of exp(i phi_i) = er_i + i ei_i over a span of time
  struct Sums {
    std::vector<double> A, er, ei;
    double span = 0.0;
    void reset(int n);
    void add(const Sums& o);
  };
  double nextCut(double t) const;     // the next period boundary or final start after t
  void addPiece(double a, double b);  // the nodes in th_, w_ summed over [a, b]
  void endPiece(double a, double b);
  void closePeriod();
  void emit(EnvelopeRow row, const std::vector<double>& phase_re,
            const std::vector<double>& phase_im);

  double epsilon_;
  std::vector<bool> active_;
  RunSink& sink_;
  int n_;
  double t_end_;     // the planned end
  double t_from_;    // the final period's start: t_end - 2 pi (0 for a shorter run)
  long period_ = 0;  // index of the period being summed
  Sums period_sums_, piece_sums_;
  // the pieces of the last 2 pi, oldest first: time a, then b and the piece's 3N sums
  SampleRing trailing_;
  std::vector<PhaseUnwrapper> unwrap_;
  std::vector<double> th_, w_;  // the nodes' states (kNodes x N each)
  double t_last_ = 0.0;
  EnvelopeRow last_row_;
  double final_span_ = 0.0;
};

template <class Nodes>
void EnvelopeQuadrature::stretch(double ta, double tb, Nodes&& nodes) {
  double a = ta;
  while (a < tb) {
    const double b = std::min(tb, nextCut(a));
    nodes(a, b, th_.data(), w_.data());
    addPiece(a, b);
    endPiece(a, b);
    a = b;
  }
  t_last_ = std::max(t_last_, tb);
}

}  // namespace metrosync
