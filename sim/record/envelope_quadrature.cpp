#include "sim/record/envelope_quadrature.h"

#include <algorithm>
#include <cmath>

namespace metrosync {

void EnvelopeQuadrature::Sums::reset(int n) {
  for (auto* v : {&A, &er, &ei}) {
    v->resize(n);
    std::fill(v->begin(), v->end(), 0.0);
  }
  span = 0.0;
}

void EnvelopeQuadrature::Sums::add(const Sums& o) {
  for (size_t i = 0; i < A.size(); ++i) {
    A[i] += o.A[i];
    er[i] += o.er[i];
    ei[i] += o.ei[i];
  }
  span += o.span;
}

EnvelopeQuadrature::EnvelopeQuadrature(double epsilon, std::vector<bool> active, double t_end,
                                       RunSink& sink)
    : epsilon_(epsilon),
      active_(std::move(active)),
      sink_(sink),
      n_(static_cast<int>(active_.size())),
      t_end_(t_end),
      t_from_(std::max(0.0, t_end - kTwoPi)),
      trailing_(1 + 3 * n_),
      unwrap_(n_ > 1 ? n_ - 1 : 0),
      th_(kNodes * n_, 0.0),
      w_(kNodes * n_, 0.0) {
  period_sums_.reset(n_);
  piece_sums_.reset(n_);
}

void EnvelopeQuadrature::start(const double* theta, const double* thetadot) {
  EnvelopeRow row;
  row.tau = 0.0;
  row.A.resize(n_);
  std::vector<double> er(n_, 1.0), ei(n_, 0.0);
  for (int i = 0; i < n_; ++i) {
    if (!active_[i]) continue;
    const double a = std::sqrt(theta[i] * theta[i] + thetadot[i] * thetadot[i]);
    row.A[i] = a;
    if (a > 0) {  // exp(i atan2(theta, thetadot)) at t = 0
      er[i] = thetadot[i] / a;
      ei[i] = theta[i] / a;
    }
  }
  emit(std::move(row), er, ei);
}

double EnvelopeQuadrature::nextCut(double t) const {
  const double boundary = kTwoPi * static_cast<double>(period_ + 1);
  return t < t_from_ ? std::min(boundary, t_from_) : boundary;
}

namespace {

// 1 / ((k + 1) k) for k = 1 .. 21: the Taylor recurrences of sin and cos
constexpr double kInvPairs[] = {0.0,       1.0 / 2,   1.0 / 6,   1.0 / 12,  1.0 / 20,  1.0 / 30,
                                1.0 / 42,  1.0 / 56,  1.0 / 72,  1.0 / 90,  1.0 / 110, 1.0 / 132,
                                1.0 / 156, 1.0 / 182, 1.0 / 210, 1.0 / 240, 1.0 / 272, 1.0 / 306,
                                1.0 / 342, 1.0 / 380, 1.0 / 420, 1.0 / 462};

// cos x and sin x for |x| <= 1 (a Gauss node's distance from its piece's middle, in scaled time:
// pieces are at most a fifth of a period) by their Taylor polynomials to x^20 and x^21
// (truncation below 2e-20), else the library's.
void smallSinCos(double x, double& c, double& s) {
  if (!(std::abs(x) <= 1.0)) {
    c = std::cos(x);
    s = std::sin(x);
    return;
  }
  const double x2 = x * x;
  double cs = 1.0, sn = 1.0;
  for (int k = 20; k >= 2; k -= 2) {
    cs = 1.0 - x2 * kInvPairs[k - 1] * cs;  // 1 / (k (k - 1))
    sn = 1.0 - x2 * kInvPairs[k] * sn;      // 1 / ((k + 1) k)
  }
  c = cs;
  s = x * sn;
}

}  // namespace

// The piece's nodes: A_i and exp(i phi_i) = (thetadot + i theta) / A exp(-i t), each weighted by
// its Gauss weight times half the piece's length. exp(-i t) at the nodes: exp(-i mid) (one
// sincos) turned by exp(-i half x_q), the nodes symmetric about the middle (x_0 = -x_3).
void EnvelopeQuadrature::addPiece(double a, double b) {
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  const double cm = std::cos(mid), sm = -std::sin(mid);  // exp(-i mid)
  double rot_c[kNodes], rot_s[kNodes];                   // exp(-i half x_q)
  for (int q = kNodes / 2; q < kNodes; ++q) {
    double c, sn;
    smallSinCos(half * kNode[q], c, sn);
    rot_c[q] = rot_c[kNodes - 1 - q] = c;
    rot_s[q] = -sn;
    rot_s[kNodes - 1 - q] = sn;
  }
  double* __restrict A = piece_sums_.A.data();
  double* __restrict er = piece_sums_.er.data();
  double* __restrict ei = piece_sums_.ei.data();
  for (int q = 0; q < kNodes; ++q) {
    const double cr = cm * rot_c[q] - sm * rot_s[q], ci = cm * rot_s[q] + sm * rot_c[q];
    const double dt_weight = half * kWeight[q];
    const double* theta = th_.data() + q * n_;
    const double* thetadot = w_.data() + q * n_;
    for (int i = 0; i < n_; ++i) {
      const double th = theta[i], w = thetadot[i];
      const double amp = std::sqrt(th * th + w * w);
      // a locked metronome or one at rest: A = 0, its phase 0 (exp(i phi) = 1)
      const bool swings = active_[i] && amp > 0;
      const double d = swings ? amp : 1.0;
      const double ur = swings ? w / d : 1.0, ui = swings ? th / d : 0.0;
      const double u_r = swings ? ur * cr - ui * ci : 1.0, u_i = swings ? ur * ci + ui * cr : 0.0;
      A[i] += dt_weight * (active_[i] ? amp : 0.0);
      er[i] += dt_weight * u_r;
      ei[i] += dt_weight * u_i;
    }
  }
}

// A piece [a, b] summed: into its period (closed at a boundary) and the trailing memory.
void EnvelopeQuadrature::endPiece(double a, double b) {
  piece_sums_.span = b - a;
  period_sums_.add(piece_sums_);
  {
    // [a, b, sums] kept while it can still be part of the final period
    const double* parts[] = {&b, piece_sums_.A.data(), piece_sums_.er.data(),
                             piece_sums_.ei.data()};
    trailing_.push(a, parts, {1, n_, n_, n_});
    const double keep_from = std::min(t_from_, b - kTwoPi);
    while (trailing_.size() > 1 && trailing_.values(0)[0] <= keep_from) trailing_.popFront();
  }
  piece_sums_.reset(n_);
  if (b >= kTwoPi * static_cast<double>(period_ + 1)) closePeriod();
}

void EnvelopeQuadrature::closePeriod() {
  EnvelopeRow row;
  row.tau = envelopeTau(epsilon_, period_);
  row.A.resize(n_);
  const double len = period_sums_.span > 0 ? period_sums_.span : 1.0;
  for (int i = 0; i < n_; ++i) row.A[i] = period_sums_.A[i] / len;
  emit(std::move(row), period_sums_.er, period_sums_.ei);
  period_sums_.reset(n_);
  ++period_;
}

// Completes a row with A set: psi_j = phi_1 - phi_j from the phases' sums (only their directions
// count), unwrapped against the rows before, and r.
void EnvelopeQuadrature::emit(EnvelopeRow row, const std::vector<double>& phase_re,
                              const std::vector<double>& phase_im) {
  std::vector<double> phi(n_);
  for (int i = 0; i < n_; ++i) phi[i] = active_[i] ? std::atan2(phase_im[i], phase_re[i]) : 0.0;
  row.psi.clear();
  for (int j = 1; j < n_; ++j) row.psi.push_back(unwrap_[j - 1](phi[0] - phi[j]));
  row.r = orderParameter(row.A, row.psi);
  sink_.envelopeRow(row);
  last_row_ = std::move(row);
}

// The final row: the pieces of the final period [t_from, t_end] (a run stopped early: of the
// pieces that start within 2 pi of where it stopped).
EnvelopeRow EnvelopeQuadrature::finish() {
  const double from = t_last_ >= t_end_ ? t_from_ : std::max(0.0, t_last_ - kTwoPi);
  Sums sums;
  sums.reset(n_);
  for (size_t k = 0; k < trailing_.size(); ++k) {
    if (trailing_.time(k) < from) continue;
    const double* v = trailing_.values(k);
    sums.span += v[0] - trailing_.time(k);
    for (int i = 0; i < n_; ++i) {
      sums.A[i] += v[1 + i];
      sums.er[i] += v[1 + n_ + i];
      sums.ei[i] += v[1 + 2 * n_ + i];
    }
  }
  final_span_ = sums.span;
  EnvelopeRow row;
  row.tau = epsilon_ * t_last_;
  row.A.resize(n_);
  if (!(sums.span > 0)) {  // a run of length 0: the start's envelope
    row.A = last_row_.A;
    row.psi = last_row_.psi;
    row.r = last_row_.r;
    sink_.envelopeRow(row);
    last_row_ = row;
    return row;
  }
  for (int i = 0; i < n_; ++i) row.A[i] = sums.A[i] / sums.span;
  emit(std::move(row), sums.er, sums.ei);
  return last_row_;
}

}  // namespace metrosync
