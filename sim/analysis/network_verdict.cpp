#include "sim/analysis/network_verdict.h"

#include <cmath>

#include "base/constants.h"
#include "models/network_equations.h"
#include "models/scaling.h"
#include "sim/analysis/network_regime.h"
#include "sim/analysis/order_parameter.h"
#include "sim/analysis/regime.h"

namespace metrosync {

struct NetworkVerdict::Impl {
  const Network& net;
  network::NetworkEquations eq;
  network::Layout lay;
  ScaledParams sp;
  double omega0 = 1.0;
  std::vector<double> omega;                    // (n) each swinging pendulum's frequency
  std::vector<int> swinging_index;              // (N) -> swinging pendulum or -1 (locked)
  std::vector<PhaseUnwrapper> unwrap;           // (N-1) psi_2..psi_N
  std::vector<PhaseUnwrapper> platform_unwrap;  // (n) psi within each platform
  std::vector<RegimeWindow> regimes;            // per platform
  NetworkWindow window;
  EnvelopeRow last;
  std::vector<double> phi;    // the last sample's phases
  std::vector<Order> groups;  // ... each platform's order parameter
  Order all;                  // ... the network's
  bool seen = false;

  explicit Impl(const Network& n)
      : net(n),
        eq(n),
        lay(eq.layout()),
        sp(computeScaled(n.scalesRig())),
        window(static_cast<int>(n.platforms.size()), n.sim.t_end_s, kTwoPi * sp.time_scale_s) {
    omega0 = 1.0 / sp.time_scale_s;
    swinging_index.assign(n.numMetronomes(), -1);
    for (int j = 0; j < lay.n; ++j) {
      const network::PendulumConstants& q = eq.pendulum(j);
      omega.push_back(std::sqrt(q.mgL / q.inertia));
      swinging_index[q.rig_index] = j;
    }
    unwrap.resize(std::max(0, n.numMetronomes() - 1));
    platform_unwrap.resize(lay.n);
    const double tau_end = n.sim.t_end_s * omega0 * sp.epsilon;
    for (std::size_t p = 0; p < n.platforms.size(); ++p)
      regimes.emplace_back(tau_end, sp.epsilon, networkPlatformRules());
  }
  PlatformsVerdict verdicts() const;
  double amplitude(const std::vector<double>& y, int j) const {
    return std::hypot(y[lay.theta(j)], y[lay.omega(j)] / omega[j]) / sp.angle_scale;
  }
};

NetworkVerdict::NetworkVerdict(const Network& net) : impl_(std::make_unique<Impl>(net)) {}
NetworkVerdict::~NetworkVerdict() = default;

void NetworkVerdict::stateSample(double t, const std::vector<double>& y,
                                 const std::vector<PlatformMode>&) {
  Impl& m = *impl_;
  const double tau = t * m.omega0 * m.sp.epsilon;
  std::vector<double> phi(m.lay.n);
  for (int j = 0; j < m.lay.n; ++j)
    phi[j] = pendulumPhase(y[m.lay.theta(j)], y[m.lay.omega(j)], m.omega[j]);
  // the network's row, global numbering
  EnvelopeRow env;
  env.tau = tau;
  const int j1 = m.swinging_index[0];
  for (int i = 0; i < m.net.numMetronomes(); ++i) {
    const int j = m.swinging_index[i];
    env.A.push_back(j < 0 ? 0.0 : m.amplitude(y, j));
    if (i > 0) env.psi.push_back(j < 0 || j1 < 0 ? 0.0 : m.unwrap[i - 1](phi[j1] - phi[j]));
  }
  // each platform: its order parameter, and its own envelope row for its regime
  std::vector<Order> groups;
  for (int p = 0; p < m.lay.platforms; ++p) {
    const network::Block& b = m.eq.block(p);
    groups.push_back(orderParameter(
        std::vector<double>(phi.begin() + b.first, phi.begin() + b.first + b.count)));
    if (b.count == 0) continue;
    EnvelopeRow row;
    row.tau = tau;
    for (int j = b.first; j < b.first + b.count; ++j) {
      row.A.push_back(m.amplitude(y, j));
      if (j > b.first) row.psi.push_back(m.platform_unwrap[j](phi[b.first] - phi[j]));
    }
    m.regimes[p].add(row);
  }
  m.window.add(t, groups);
  m.all = orderParameter(phi);
  env.r = m.all.r;
  m.last = env;
  m.phi = phi;
  m.groups = groups;
  m.seen = true;
}

bool NetworkVerdict::empty() const {
  return !impl_->seen;
}

// The platforms' verdicts and the label: classifyPlatforms on each platform's own window.
PlatformsVerdict NetworkVerdict::Impl::verdicts() const {
  std::vector<std::vector<double>> theta_c(net.platforms.size());
  for (std::size_t p = 0; p < net.platforms.size(); ++p)
    for (const MetronomeSpec& ms : net.platforms[p].rig.metronomes)
      if (!ms.locked) theta_c[p].push_back(ms.theta_c_rad / sp.angle_scale);
  return classifyPlatforms(window, regimes, theta_c);
}

std::string NetworkVerdict::label() const {
  return impl_->verdicts().label;
}

std::vector<std::string> NetworkVerdict::platformRegimes() const {
  std::vector<std::string> names;
  for (const RegimeVerdict& v : impl_->verdicts().platforms) names.push_back(regimeName(v));
  return names;
}

const EnvelopeRow& NetworkVerdict::last() const {
  return impl_->last;
}

const std::vector<double>& NetworkVerdict::phases() const {
  return impl_->phi;
}

const std::vector<Order>& NetworkVerdict::groups() const {
  return impl_->groups;
}

const Order& NetworkVerdict::overall() const {
  return impl_->all;
}

const NetworkWindow& NetworkVerdict::window() const {
  return impl_->window;
}

}  // namespace metrosync
