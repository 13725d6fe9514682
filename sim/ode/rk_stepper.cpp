#include "sim/ode/rk_stepper.h"

namespace metrosync::ode {

namespace detail {

Row nonzeroRow(const std::vector<double>& w, int count) {
  Row row;
  for (int l = 0; l < count; ++l) {
    if (w[l] == 0.0) continue;
    if (row.count == kMaxTerms) throw std::logic_error("RkStepper: too many terms in a row");
    row.stage[row.count] = l;
    row.weight[row.count] = w[l];
    ++row.count;
  }
  return row;
}

DenseTable::DenseTable(const RkTableau& tab) : degree(tab.dense_degree) {
  std::vector<double> p;  // the nonzero rows of p, (rows x degree)
  for (int j = 0; j < tab.dense_stages; ++j) {
    if (std::all_of(tab.p[j].begin(), tab.p[j].end(), [](double v) { return v == 0.0; })) continue;
    stage.push_back(j);
    p.insert(p.end(), tab.p[j].begin(), tab.p[j].end());
  }
  const int rows = static_cast<int>(stage.size());
  if (rows > kPadRows) throw std::invalid_argument("RkStepper: too many interpolant stages");
  padded_rows = rows <= kPadRowsSmall ? kPadRowsSmall : kPadRows;
  if (degree > kMaxDegree) throw std::invalid_argument("RkStepper: interpolant degree too high");
  // kMaxDegree rows of coefficients, the ones past the degree zero: whole-vector loops over them
  pt.assign(static_cast<size_t>(padded_rows) * kMaxDegree, 0.0);
  rate_pt = pt;
  for (int r = 0; r < rows; ++r)
    for (int q = 0; q < degree; ++q) {
      const double v = p[static_cast<size_t>(r) * degree + q];
      pt[static_cast<size_t>(q) * padded_rows + r] = v;
      rate_pt[static_cast<size_t>(q) * padded_rows + r] = (q + 1) * v;
    }
}

namespace {

// w_r = scale * sum_q p_rq th^(q+1) (value) or sum_q (q + 1) p_rq th^q (rate), by Horner's rule
// with the degree and the (padded) row count known at compile time. The rows are the inner loop
// (the coefficients stored degree-major, zero-padded to R rows, and for the rate pre-multiplied
// by q + 1), so that the compiler vectorizes across rows; each row's arithmetic is the same
// sequence of operations as a row-wise Horner, so the weights are the same to the last bit.
template <int D, int R>
void hornerRows(const double* __restrict pt, double th, double scale, bool rate,
                double* __restrict w) {
  double acc[R];
  for (int r = 0; r < R; ++r) acc[r] = pt[(D - 1) * R + r];
  for (int q = D - 2; q >= 0; --q)
    for (int r = 0; r < R; ++r) acc[r] = acc[r] * th + pt[q * R + r];
  if (!rate)
    for (int r = 0; r < R; ++r) acc[r] *= scale;
  for (int r = 0; r < R; ++r) w[r] = acc[r];  // all R: a fixed-size store, not a memcpy call
}

}  // namespace

void DenseTable::weights(double th, double h, bool rate, double* w) const {
  const double scale = h * th;
  const double* p = rate ? rate_pt.data() : pt.data();
  if (padded_rows == kPadRowsSmall && degree == 4)
    return hornerRows<4, kPadRowsSmall>(p, th, scale, rate, w);
  if (padded_rows == kPadRows) {
    switch (degree) {
      case 6:
        return hornerRows<6, kPadRows>(p, th, scale, rate, w);
      case 7:
        return hornerRows<7, kPadRows>(p, th, scale, rate, w);
    }
  }
  const int rows = static_cast<int>(stage.size());
  for (int r = 0; r < rows; ++r) {
    double acc = p[static_cast<size_t>(degree - 1) * padded_rows + r];
    for (int q = degree - 2; q >= 0; --q)
      acc = acc * th + p[static_cast<size_t>(q) * padded_rows + r];
    w[r] = rate ? acc : scale * acc;
  }
}

double nextStepSize(const RkTableau& tab, double& log2_err_old, double h, double err,
                    bool accepted) {
  // Hairer's DOPRI5 controller: safety 0.9, the step changes by a factor in [0.2, 10]. The
  // previous error is kept as its log2, so that the PI factor err^expo / err_old^beta is one exp2
  // of one log2 per step (the same value as two pow calls to a few ulps, which only nudge the next
  // step's size; a fifth of their cost)
  const double beta = tab.pi_beta;
  const double expo = 1.0 / (tab.error_order + 1) - 0.75 * beta;
  const double log2_err = std::log2(std::max(err, 1e-300));
  if (accepted) {
    double fac = std::exp2(expo * log2_err - beta * log2_err_old) / 0.9;
    fac = std::clamp(fac, 0.1, 5.0);
    log2_err_old = std::max(log2_err, kLog2ErrFloor);
    return h / fac;
  }
  return h / std::min(5.0, std::exp2(expo * log2_err) / 0.9);
}

}  // namespace detail

template class RkStepperT<OdeRhs, kDynamic, 0>;

}  // namespace metrosync::ode
