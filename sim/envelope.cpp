#include "sim/envelope.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace metrosync {

std::string envelopeHeader(int n) {
  std::string h = "tau";
  for (int i = 1; i <= n; ++i) h += ",A_" + std::to_string(i);
  for (int j = 2; j <= n; ++j) h += ",psi_" + std::to_string(j);
  return h;
}

std::string formatEnvelopeRow(const EnvelopeRow& row) {
  char buf[40];
  std::string s;
  std::snprintf(buf, sizeof buf, "%.10g", row.tau);
  s += buf;
  for (double a : row.A) {
    std::snprintf(buf, sizeof buf, ",%.12g", a);
    s += buf;
  }
  for (double p : row.psi) {
    std::snprintf(buf, sizeof buf, ",%.12g", p);
    s += buf;
  }
  return s;
}

std::vector<EnvelopeRow> readEnvelopeCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open");
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(path + ": empty file");
  int ncols = 1;
  for (char c : line) ncols += (c == ',');
  const int n = (ncols + 1) / 2;  // 1 + N + (N-1) = 2N columns
  if (ncols != 2 * n) throw std::runtime_error(path + ": header has " + std::to_string(ncols) +
                                               " columns, not tau + 2N - 1");
  std::vector<EnvelopeRow> rows;
  long lineno = 1;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.empty()) continue;
    std::stringstream ss(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
    if (static_cast<int>(v.size()) != ncols)
      throw std::runtime_error(path + ":" + std::to_string(lineno) + ": wrong number of columns");
    EnvelopeRow r;
    r.tau = v[0];
    r.A.assign(v.begin() + 1, v.begin() + 1 + n);
    r.psi.assign(v.begin() + 1 + n, v.end());
    rows.push_back(std::move(r));
  }
  return rows;
}

double PhaseUnwrapper::operator()(double raw) {
  constexpr double kTwoPi = 6.283185307179586;
  if (!started_) {
    started_ = true;
    last_ = raw - kTwoPi * std::floor(raw / kTwoPi);
    return last_;
  }
  last_ = raw + kTwoPi * std::round((last_ - raw) / kTwoPi);
  return last_;
}

}  // namespace metrosync
