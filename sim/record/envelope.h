// The envelope format both models write (SPEC section 3, envelope.csv):
//   tau, A_1..A_N, psi_2..psi_N, r   (scaled units; psi_j = phi_1 - phi_j, unwrapped; r the order
//                                     parameter, an extension of the SPEC at the end of the row)
// The full model produces one row per fast period (average over 2 pi of scaled time, phases
// averaged as unit complex numbers, tau at the middle of the period); the slow flow produces rows
// on the same grid, tau_k = eps * 2 pi (k + 1/2), so that the two can be compared row by row.
#pragma once

#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "base/constants.h"

namespace metrosync {

struct EnvelopeRow {
  double tau = 0.0;
  std::vector<double> A;    // (N x 1) scaled amplitudes
  std::vector<double> psi;  // (N-1 x 1) phase differences phi_1 - phi_j, j = 2..N, unwrapped
  // order parameter r = |sum_j A_j e^{i phi_j}| / sum_j A_j: 1 all in phase, 0 balanced (antiphase
  // pair, splay state). Engines set it with orderParameter(A, psi); left NaN, formatEnvelopeRow
  // computes it.
  double r = std::numeric_limits<double>::quiet_NaN();
};

// r of the row above from its A and psi (e^{i phi_j} = e^{i phi_1} e^{-i psi_j}, so phi_1 drops
// out); 0 when sum_j A_j = 0 (nothing swings).
double orderParameter(const std::vector<double>& A, const std::vector<double>& psi);

// Header line (no newline) for N metronomes: tau,A_1..A_N,psi_2..psi_N,r
std::string envelopeHeader(int n);
// One CSV line (no newline), full precision.
std::string formatEnvelopeRow(const EnvelopeRow& row);

// The columns of an envelope file, from its header: tau, N amplitudes, N-1 phase differences and
// (files written since r was added) r. Throws std::runtime_error for any other header.
struct EnvelopeLayout {
  int n = 0;             // metronomes
  bool has_r = false;    // the column after psi_N is r
  bool has_t_s = false;  // the last column is t_s (seconds; physical rigs, docs/outputs.md)
  int columns() const { return 2 * n + (has_r ? 1 : 0) + (has_t_s ? 1 : 0); }
};
EnvelopeLayout parseEnvelopeHeader(const std::string& header, const std::string& path);
// A row from the numbers of one line (values.size() == layout.columns()); r computed when absent.
EnvelopeRow envelopeRowFromValues(const std::vector<double>& values, const EnvelopeLayout& layout);

// (envelope.csv read back: sim/record/envelope_csv.h)

// Keeps a phase difference continuous: each new raw value (any branch) is moved by a multiple of
// 2 pi to the branch nearest the previous one; the first value is put in [0, 2 pi).
class PhaseUnwrapper {
 public:
  double operator()(double raw);
  void reset() { started_ = false; }

 private:
  bool started_ = false;
  double last_ = 0.0;
};

// The fast-period grid shared by both models: tau of row k.
inline double envelopeTau(double epsilon, long k) {
  return epsilon * kTwoPi * (static_cast<double>(k) + 0.5);
}

}  // namespace metrosync
