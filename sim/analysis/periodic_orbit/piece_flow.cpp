#include "sim/analysis/periodic_orbit/piece_flow.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "base/constants.h"
#include "sim/ode/root_find.h"

namespace metrosync::orbit {

namespace {
// A step below this fraction of the fast period (2 pi) is an underflow: the pieces are smooth
// and O(1) long, so a step this small means a state the model cannot continue (non-finite).
constexpr double kMinStep = 1e-13;
// The largest step: a tenth of the fast period, as the direct engine (at most one extreme of
// theta_r per step, so that an upward crossing of the section is never hidden inside a step).
constexpr double kMaxStep = 0.2 * kPi;
// Newton refinements of the section time on the re-taken step: each one takes |theta_r| from
// the dense output's error (~1e-13) to the rounding of the step (~1e-16).
constexpr int kSectionRefinements = 2;
}  // namespace

struct PieceFlow::Rhs : ode::OdeRhs {
  Rhs(const ScaledModel& m, bool phi) : model(m), with_phi(phi), d(m.dim()) {}
  void eval(const double* y, double* dy) override {
    const Eigen::Map<const Vec> z(y, d);
    const Vec f = model.rhs(z, mode);
    std::copy(f.data(), f.data() + d, dy);
    if (!with_phi) return;
    const Eigen::Map<const Mat> phi(y + d, d, d);
    Eigen::Map<Mat> dphi(dy + d, d, d);
    dphi.noalias() = model.jacobian(z, mode) * phi;
  }
  const ScaledModel& model;
  bool with_phi;
  int d;
  PlatformMode mode = PlatformMode::Stuck;
};

PieceFlow::PieceFlow(const ScaledModel& model, double accuracy)
    : model_(model), accuracy_(accuracy) {
  const int d = model.dim();
  const ode::RkTableau& tab = ode::rkTableau("verner76");
  rhs_z_ = std::make_unique<Rhs>(model, false);
  rhs_ext_ = std::make_unique<Rhs>(model, true);
  z_only_ = std::make_unique<ode::RkStepper>(tab, d, *rhs_z_);
  extended_ = std::make_unique<ode::RkStepper>(tab, d + d * d, *rhs_ext_);
  z_only_->setTolerances(accuracy, std::vector<double>(d, accuracy));
  std::vector<double> atol(d + d * d, -1.0);  // Phi: not controlled
  std::fill(atol.begin(), atol.begin() + d, accuracy);
  extended_->setTolerances(accuracy, atol);
}

PieceFlow::~PieceFlow() = default;

void PieceFlow::restart(const FlowPoint& at, PlatformMode mode) {
  const int d = model_.dim();
  with_phi_ = at.phi.size() > 0;
  cur_ = with_phi_ ? extended_.get() : z_only_.get();
  (with_phi_ ? rhs_ext_ : rhs_z_)->mode = mode;
  std::vector<double> y(cur_->dim());
  std::copy(at.z.data(), at.z.data() + d, y.begin());
  if (with_phi_) std::copy(at.phi.data(), at.phi.data() + d * d, y.begin() + d);
  cur_->restart(at.t, y.data());
}

void PieceFlow::take(FlowPoint& at) const {
  const int d = model_.dim();
  at.t = cur_->t();
  at.z = Eigen::Map<const Vec>(cur_->y(), d);
  if (with_phi_) at.phi = Eigen::Map<const Mat>(cur_->y() + d, d, d);
}

void PieceFlow::advance(FlowPoint& at, double t1, PlatformMode mode) {
  run(at, t1, mode, nullptr);
}

bool PieceFlow::advanceToSection(FlowPoint& at, double t1, PlatformMode mode,
                                 const SectionSpec& section) {
  return run(at, t1, mode, &section);
}

// The fraction th of the attempted step where theta_r crosses 0 upwards (on the dense output),
// then the step re-taken to there and refined by Newton: the end state is a full step's.
double PieceFlow::locateSection(int k, double step) {
  auto g = [&](double th) { return cur_->component(k, th); };
  const ode::Bracket b = ode::illinois(g, 0.0, cur_->y()[k], 1.0, cur_->y1()[k]);
  double h = 0.5 * (b.lo + b.hi) * step;
  for (int it = 0; it < kSectionRefinements; ++it) {
    cur_->attempt(h);
    const double rate = cur_->f1()[k];
    if (!(rate > 0)) break;
    h -= cur_->y1()[k] / rate;
  }
  cur_->attempt(h);
  return h;
}

bool PieceFlow::run(FlowPoint& at, double t1, PlatformMode mode, const SectionSpec* section) {
  if (!(t1 > at.t)) return false;
  restart(at, mode);
  const int k = section ? model_.theta(section->pendulum) : -1;
  double h = cur_->initialStepSize(std::min(kMaxStep, t1 - at.t));
  while (cur_->t() < t1) {
    const double t0 = cur_->t();
    const bool last = t0 + h >= t1 * (1 - 4 * std::numeric_limits<double>::epsilon());
    const double step = last ? t1 - t0 : h;
    if (!(step > kMinStep) && !last) throw std::runtime_error("step size underflow");
    const double err = cur_->attempt(step);
    if (!(err <= 1.0)) {
      if (!std::isfinite(err) && step < kMinStep * 1e3)
        throw std::runtime_error("non-finite state");
      h = std::isfinite(err) ? cur_->nextStepSize(step, err, false) : 0.25 * step;
      continue;
    }
    ++steps_;
    if (section && cur_->y()[k] < 0 && cur_->y1()[k] >= 0 && cur_->t1() > section->t_min) {
      locateSection(k, step);
      cur_->advance();
      take(at);
      return true;
    }
    h = std::min(kMaxStep, cur_->nextStepSize(step, err, true));
    cur_->advance();
    if (last) break;
  }
  take(at);
  at.t = t1;
  return false;
}

}  // namespace metrosync::orbit
