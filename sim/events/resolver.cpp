#include "sim/events/resolver.h"

#include <cmath>

namespace metrosync {

EventResolver::EventResolver(std::vector<Escapement> escapements, const PlatformFriction& friction,
                             double period, const std::vector<double>& theta0)
    : esc_(std::move(escapements)),
      set_valued_(friction.setValued()),
      friction_(friction),
      period_(period) {
  armed_.assign(2 * esc_.size(), 0);
  // a witness that starts below zero can cross; one already past it waits for the next swing
  for (size_t j = 0; j < esc_.size(); ++j)
    for (int side : {-1, 1}) armed_[2 * j + (side > 0)] = esc_[j].witness(theta0[j], side) < 0;
}

WindowOutcome EventResolver::resolve(EventSystem& sys, bool platform_reported) {
  WindowOutcome out;
  const std::vector<int>& due = dueTicks(sys);
  if (!due.empty()) {
    const PlatformMode before = set_valued_ ? sys.mode() : PlatformMode::Stuck;
    applyTicks(sys, due, out);
    if (set_valued_) modeAfterImpulse(sys, before, out);
    sys.eventRow("tick");
  }
  if (set_valued_ && (platform_reported || !due.empty())) coulombRule(sys, out);
  return out;
}

WindowOutcome EventResolver::settleAfterSupportImpulse(EventSystem& sys) {
  WindowOutcome out;
  modeAfterImpulse(sys, sys.mode(), out);
  coulombRule(sys, out);
  return out;
}

void EventResolver::rearm(const EventSystem& sys) {
  for (int j = 0; j < static_cast<int>(esc_.size()); ++j) rearm(j, sys.theta(j));
}

PlatformMode EventResolver::settleAtStart(EventSystem& sys) const {
  const double v = sys.xdot();
  if (v != 0) {
    const PlatformMode m = v > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative;
    sys.setMode(m);
    return m;
  }
  sys.snapshotBefore();
  sys.setMode(PlatformMode::Stuck);
  const PlatformMode m = law().modeAtRest(sys.holdingForce());
  if (m != PlatformMode::Stuck) {
    sys.setMode(m);
    sys.eventRow("slip");
    sys.recordEvent("slip", -1);
  }
  return m;
}

// --- 1. ticks ---------------------------------------------------------------------------------

const std::vector<int>& EventResolver::dueTicks(const EventSystem& sys) {
  due_.clear();
  for (int j = 0; j < static_cast<int>(esc_.size()); ++j) {
    const double th = sys.theta(j);
    if (armed(j, Escapement::side(th)) && esc_[j].due(th, sys.thetadot(j))) due_.push_back(j);
  }
  return due_;
}

void EventResolver::applyTicks(EventSystem& sys, const std::vector<int>& due, WindowOutcome& out) {
  sys.snapshotBefore();
  impulse_.assign(esc_.size(), 0.0);
  for (int j : due) {
    const double th = sys.theta(j);
    impulse_[j] = esc_[j].tickImpulse(th);
    armed_[2 * j + (th > 0)] = 0;  // consumed until the pendulum is back inside
  }
  out.escapement_in += sys.applyImpulse(impulse_, 0.0);
  out.ticked = due;
  // one record per pendulum: the combined impulse is each one's tick (the same states)
  for (int j : due) sys.recordEvent("tick", j);
}

// --- 2. the platform after the impulse --------------------------------------------------------

void EventResolver::modeAfterImpulse(EventSystem& sys, PlatformMode before, WindowOutcome& out) {
  sys.snapshotBefore();  // after the ticks: a switch they cause starts from their result
  const double v = sys.xdot();
  if (v == 0) {
    // exactly cancelling impulses leave a stuck platform stuck; a slip at exactly 0 stops in
    // the Coulomb rule below
    if (before == PlatformMode::Stuck) sys.setMode(PlatformMode::Stuck);
    return;
  }
  const PlatformMode m = v > 0 ? PlatformMode::SlipPositive : PlatformMode::SlipNegative;
  sys.setMode(m);
  if (microSlip(sys, v, m)) {
    // a slip friction ends at once: counted by where it ends, against the mode before the
    // window (a stuck platform that stays stuck has not switched; nearly cancelling ticks)
    stopAndSettle(sys, before, out);
    ++out.plastic_stops;
    return;
  }
  countSwitch(sys, before, m, out);
}

// --- 3. the law's stick/slip rule
// ----------------------------------------------------------------------

void EventResolver::coulombRule(EventSystem& sys, WindowOutcome& out) {
  sys.snapshotBefore();
  const PlatformMode m = sys.mode();
  if (m == PlatformMode::Stuck) {
    const double h = sys.holdingForce();
    if (!law().breaksFree(h)) return;
    const PlatformMode to = SetValuedLaw::slipDirection(h);
    sys.setMode(to);
    countSwitch(sys, m, to, out);
    return;
  }
  if (static_cast<int>(m) * sys.xdot() > 0) return;  // still slipping its way
  stopAndSettle(sys, m, out);
}

bool EventResolver::microSlip(EventSystem& sys, double v, PlatformMode m) const {
  // friction alone decelerates the platform at |F(v)| * (M^-1)_xx (Coulomb: the kinetic bound)
  const double decel = std::abs(friction_.force(v, m)) * sys.platformMobility();
  return std::abs(v) < kPlasticStopPeriods * period_ * decel;
}

void EventResolver::stopAndSettle(EventSystem& sys, PlatformMode before, WindowOutcome& out) {
  const double v = sys.xdot();
  if (v != 0) {
    // friction's impulse on x alone, -v / (M^-1)_xx: xdot becomes 0 (to rounding), the pendulums
    // take the reaction; the kinetic energy it removes is friction's
    impulse_.assign(esc_.size(), 0.0);  // none on the pins
    out.friction_out -= sys.applyImpulse(impulse_, -v / sys.platformMobility());
  }
  sys.setMode(PlatformMode::Stuck);
  const PlatformMode after = law().modeAtRest(sys.holdingForce());
  if (after != PlatformMode::Stuck) sys.setMode(after);
  countSwitch(sys, before, after, out);
}

// --- 4. counts and rows -----------------------------------------------------------------------

void EventResolver::countSwitch(EventSystem& sys, PlatformMode before, PlatformMode after,
                                WindowOutcome& out) {
  if (after == before) return;
  if (before == PlatformMode::Stuck || after == PlatformMode::Stuck)
    ++out.stick_slip;
  else
    ++out.slip_reversals;
  sys.eventRow(after == PlatformMode::Stuck ? "stick" : "slip");
  sys.recordEvent(after == PlatformMode::Stuck ? "stick" : "slip", -1);
}

}  // namespace metrosync
