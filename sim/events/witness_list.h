// The witness list of a run of the direct engine, one for a single rig and for a network of
// platforms (issue 24): both sides of every pendulum with an escapement, and the contact under
// every platform under a set-valued law, each made rising through zero at its event
// (sim/events/witness.h). Detection and values on the kept step's dense output are here, once
// (sim/events/crossing.h); the run supplies what depends on its model:
//
//   bool armed(const RunWitness& w);                          a tick's side armed (resolver)
//   std::optional<LinearForm> linearForm(const RunWitness&);  a tick, a slip: sign (y_a - y_b) - c
//   std::optional<WindowCrossing> detectStuck(int index, const RunWitness& w);  a stuck margin
//   double stuckValueAt(const RunWitness& w, double th);      the margin on the dense output
//
// A tick's witness is side * theta_j - theta_c,j, a slipping contact's -mode * (xdot_p -
// xdot_below) (PlatformWitness made rising): both linear in the state. A stuck contact's is its
// margin |H| - bound, a function of the whole state (the run knows H and whether its rate is
// known).
#pragma once

#include <optional>
#include <vector>

#include "sim/events/crossing.h"
#include "sim/events/window.h"

namespace metrosync {

struct RunWitness {
  enum class Kind { Tick, Contact };
  Kind kind = Kind::Tick;
  int index = 0;  // Tick: the pendulum (its index in the state); Contact: the platform
  int side = 0;   // Tick: +1 at +theta_c, -1 at -theta_c
  bool tick() const { return kind == Kind::Tick; }
};

// sign * (y_a - y_b) - offset, b < 0: sign * y_a - offset (as LinearWitness).
struct LinearForm {
  int a = 0, b = -1;
  double sign = 1.0, offset = 0.0;
};

class WitnessList {
 public:
  // pendulum j's two sides, +1 first
  void addTicks(int j) {
    list_.push_back({RunWitness::Kind::Tick, j, +1});
    list_.push_back({RunWitness::Kind::Tick, j, -1});
  }
  void addContact(int p) { list_.push_back({RunWitness::Kind::Contact, p, 0}); }
  int size() const { return static_cast<int>(list_.size()); }
  const RunWitness& operator[](int i) const { return list_[i]; }
  std::vector<WindowCrossing>& found() { return found_; }

  // The crossings of the kept step into found(); mayReport(w): false when the run knows that the
  // witness cannot report in this step (a pre-filter: it must never hide a crossing). True: some.
  template <class Stepper, class Run, class MayReport>
  bool findCrossings(Stepper& s, Run& run, MayReport&& mayReport) {
    found_.clear();
    for (int i = 0; i < size(); ++i) {
      if (!mayReport(list_[i])) continue;
      if (auto c = detect(s, run, i)) found_.push_back(*c);
    }
    return !found_.empty();
  }

  // Witness i's crossing in the kept step: a linear one on its components (a slip may start from
  // rest), a stuck contact's margin by the run.
  template <class Stepper, class Run>
  std::optional<WindowCrossing> detect(Stepper& s, Run& run, int i) {
    const RunWitness& w = list_[i];
    if (w.tick() && !run.armed(w)) return std::nullopt;
    if (const std::optional<LinearForm> f = run.linearForm(w))
      return detectLinear(LinearWitness(s, f->a, f->sign, f->offset, f->b), i, !w.tick());
    return run.detectStuck(i, w);
  }

  // Witness i on the kept step's dense output at th.
  template <class Stepper, class Run>
  double valueAt(Stepper& s, Run& run, int i, double th) {
    const RunWitness& w = list_[i];
    if (const std::optional<LinearForm> f = run.linearForm(w))
      return LinearWitness(s, f->a, f->sign, f->offset, f->b).value(th);
    return run.stuckValueAt(w, th);
  }

 private:
  std::vector<RunWitness> list_;
  std::vector<WindowCrossing> found_;  // the crossings of the current step
};

}  // namespace metrosync
