// The envelope format both models write (SPEC section 3, envelope.csv):
//   tau, A_1..A_N, psi_2..psi_N   (scaled units; psi_j = phi_1 - phi_j, unwrapped)
// The full model produces one row per fast period (average over 2 pi of scaled time, phases
// averaged as unit complex numbers, tau at the middle of the period); the slow flow produces rows
// on the same grid, tau_k = eps * 2 pi (k + 1/2), so that the two can be compared row by row.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace metrosync {

struct EnvelopeRow {
  double tau = 0.0;
  std::vector<double> A;    // (N x 1) scaled amplitudes
  std::vector<double> psi;  // (N-1 x 1) phase differences phi_1 - phi_j, j = 2..N, unwrapped
};

// Header line (no newline) for N metronomes.
std::string envelopeHeader(int n);
// One CSV line (no newline), full precision.
std::string formatEnvelopeRow(const EnvelopeRow& row);
// Reads an envelope.csv written by formatEnvelopeRow; throws std::runtime_error on bad input.
std::vector<EnvelopeRow> readEnvelopeCsv(const std::string& path);

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
  return epsilon * 6.283185307179586 * (static_cast<double>(k) + 0.5);
}

}  // namespace metrosync
