// The Siconos peer's envelope (tools/bench/siconos_peer.cpp; the Odeint peer integrates its own
// solution as the engines do): an integrator without an interpolant the project's quadrature
// (sim/record/envelope_quadrature.h) could integrate gives samples instead, and this turns them
// into the same rows by the trapezoid rule, as the engines' recorder did before issue 36 (its
// error, up to 2e-5 in A where an impulse bends A(t), is part of the peers' envelope error; their
// verdicts go by the final state).
//
// Turns a sampled full-model trajectory into envelope rows (SPEC section 3): for each fast period
// [2 pi k, 2 pi (k+1)] of scaled time, the time average of A_i = sqrt(theta_i^2 + thetadot_i^2)
// and of exp(i phi_i), phi_i = atan2(theta_i, thetadot_i) - t (phases averaged as unit complex
// numbers), by the trapezoid rule over the samples. Samples come in non-decreasing t; two samples
// at the same t (just before and just after an impulse) make the jump exact, and the caller puts
// a sample on every period boundary (nextBoundary()) so no trapezoid straddles two periods.
//
// Besides the period rows (tau at the middle of each period, the grid the slow flow shares):
//   - the first sample emits the start's row: tau of that sample (0), A_i = sqrt(theta_i^2 +
//     thetadot_i^2) and the phases of that instant;
//   - finish(), after the last sample (at t_end), emits the final row at tau_end: the average over
//     the last fast period ENDING at t_end, [t_end - 2 pi, t_end] (SPEC 3 "final"), from the
//     samples of the trailing period, which the recorder keeps (O(samples per period) memory). A
//     run shorter than one period is averaged over what there is (finalSpan() < 2 pi says so).
#pragma once

#include <vector>

#include "base/constants.h"
#include "sim/record/envelope.h"
#include "sim/record/run_report.h"
#include "sim/record/sample_ring.h"

namespace metrosync {

class EnvelopeRecorder {
 public:
  // active[i] == false for a locked metronome (reported as A = 0, phi = 0).
  EnvelopeRecorder(double epsilon, std::vector<bool> active, RunSink& sink);

  // theta, thetadot: (N x 1) scaled.
  void sample(double t, const double* theta, const double* thetadot);
  // Emits and returns the final row (see above); call once, after the sample at the end of the
  // run. Without any sample: an empty row.
  EnvelopeRow finish();
  // Scaled time the final row averages over: 2 pi, or less for a run shorter than one period.
  double finalSpan() const { return final_span_; }
  // Scaled time of the next period boundary.
  double nextBoundary() const { return kTwoPi * static_cast<double>(period_ + 1); }
  long rowsWritten() const { return period_; }
  const EnvelopeRow& lastRow() const { return last_row_; }

 private:
  // A_i and exp(i phi_i) = er_i + i ei_i at one sample, (N x 1) each: split into real arrays so
  // that the per-metronome loops vectorize (one sample per envelope point and two per event)
  struct Values {
    std::vector<double> A, er, ei;
    void resize(int n) {
      A.resize(n);
      er.resize(n);
      ei.resize(n);
    }
  };
  void eval(double t, const double* theta, const double* thetadot, Values& out) const;
  void closePeriod();
  void integrate(double h, const Values& a, const Values& b);
  // phase_re, phase_im: the sums of exp(i phi_i) (only their directions count)
  void emit(EnvelopeRow row, const std::vector<double>& phase_re,
            const std::vector<double>& phase_im);
  void keepTrailing(double t);

  double epsilon_;
  std::vector<bool> active_;
  RunSink& sink_;
  int n_;
  long period_ = 0;  // index of the period being accumulated
  bool have_prev_ = false;
  double t_prev_ = 0.0;
  Values prev_, cur_;
  std::vector<double> sum_A_;            // integral of A_i over the period so far
  std::vector<double> sum_er_, sum_ei_;  // integral of exp(i phi_i), real and imaginary parts
  double covered_ = 0.0;                 // length of the period integrated so far
  std::vector<PhaseUnwrapper> unwrap_;
  EnvelopeRow last_row_;
  // samples of the last period (and one before): t, then A, er, ei (3N values)
  SampleRing trailing_;
  void trailingValues(size_t k, Values& out) const;
  double final_span_ = 0.0;
};

}  // namespace metrosync
