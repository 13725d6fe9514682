#include "sim/record/envelope.h"

#include <cmath>
#include <complex>
#include <stdexcept>

#include "base/constants.h"
#include "base/csv.h"
#include "base/number_text.h"

namespace metrosync {

double orderParameter(const std::vector<double>& A, const std::vector<double>& psi) {
  if (A.empty()) return 0.0;
  std::complex<double> sum = A[0];  // phi_1 = 0 without loss
  double total = A[0];
  for (size_t j = 1; j < A.size(); ++j) {
    const double p = j - 1 < psi.size() ? psi[j - 1] : 0.0;
    sum += std::polar(A[j], -p);  // A_j e^{i (phi_1 - psi_j)}
    total += A[j];
  }
  return total > 0.0 ? std::abs(sum) / total : 0.0;
}

std::string envelopeHeader(int n) {
  std::string h = "tau";
  for (int i = 1; i <= n; ++i) h += ",A_" + std::to_string(i);
  for (int j = 2; j <= n; ++j) h += ",psi_" + std::to_string(j);
  return h + ",r";
}

std::string formatEnvelopeRow(const EnvelopeRow& row) {
  std::string s = numberText(row.tau, 10);
  for (double a : row.A) s += "," + numberText(a, 12);
  for (double p : row.psi) s += "," + numberText(p, 12);
  const double r = std::isnan(row.r) ? orderParameter(row.A, row.psi) : row.r;
  return s + "," + numberText(r, 12);
}

EnvelopeLayout parseEnvelopeHeader(const std::string& header, const std::string& path) {
  const std::vector<std::string> names = csvCells(header);
  EnvelopeLayout layout;
  layout.has_t_s = names.size() > 1 && names.back() == "t_s";
  const size_t tail = names.size() - (layout.has_t_s ? 1 : 0);
  layout.has_r = tail > 1 && names[tail - 1] == "r";
  const size_t core = tail - (layout.has_r ? 1 : 0);  // tau + N + (N-1) = 2N columns
  layout.n = static_cast<int>(core / 2);
  bool ok = core >= 2 && core % 2 == 0 && names[0] == "tau";
  for (int i = 1; ok && i <= layout.n; ++i) ok = names[i] == "A_" + std::to_string(i);
  for (int j = 2; ok && j <= layout.n; ++j)
    ok = names[layout.n + j - 1] == "psi_" + std::to_string(j);
  if (!ok)
    throw std::runtime_error(path + ": not an envelope file (header '" + header +
                             "', expected tau,A_1..A_N,psi_2..psi_N[,r][,t_s])");
  return layout;
}

EnvelopeRow envelopeRowFromValues(const std::vector<double>& v, const EnvelopeLayout& layout) {
  const int n = layout.n;
  EnvelopeRow r;
  r.tau = v[0];
  r.A.assign(v.begin() + 1, v.begin() + 1 + n);
  r.psi.assign(v.begin() + 1 + n, v.begin() + 2 * n);
  r.r = layout.has_r ? v[2 * n] : orderParameter(r.A, r.psi);
  return r;
}

double PhaseUnwrapper::operator()(double raw) {
  if (!started_) {
    started_ = true;
    last_ = raw - kTwoPi * std::floor(raw / kTwoPi);
    return last_;
  }
  last_ = raw + kTwoPi * std::round((last_ - raw) / kTwoPi);
  return last_;
}

}  // namespace metrosync
