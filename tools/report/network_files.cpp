#include "tools/report/network_files.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "base/number_text.h"
#include "models/network_equations.h"
#include "models/scaling.h"
#include "sim/analysis/network_regime.h"
#include "sim/analysis/network_verdict.h"
#include "sim/analysis/order_parameter.h"
#include "sim/analysis/regime.h"
#include "sim/record/atomic_file.h"
#include "sim/record/envelope.h"

namespace metrosync {

namespace {

// Rows kept for the plots: every other one is dropped when twice this many are held, so memory is
// bounded whatever the run's length (as the envelope's EnvelopeDecimator).
constexpr std::size_t kMaxPlotRows = 2000;

std::string csvLine(const std::vector<double>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + numberText(v[i], 17);
  return s;
}

}  // namespace

// The analysis (envelope, phases, order parameters, regime windows) is the sweep's own
// (sim/analysis/network_verdict.h); this only adds the trajectory and writes.
struct NetworkFiles::Impl {
  const Network& net;
  network::NetworkEquations eq;
  network::Layout lay;
  std::vector<int> swinging_index;  // (N metronomes) -> swinging pendulum or -1 (locked)
  AtomicFile trajectory, envelope, order;
  NetworkVerdict verdict;
  std::size_t stride = 1;
  long seen = 0;

  Impl(const OutputDir& dir, const Network& n);
  void writeHeaders();
};

NetworkFiles::Impl::Impl(const OutputDir& dir, const Network& n)
    : net(n),
      eq(n),
      lay(eq.layout()),
      trajectory(dir.file("trajectory.csv")),
      envelope(dir.file("envelope.csv")),
      order(dir.file("order.csv")),
      verdict(n) {
  swinging_index.assign(n.numMetronomes(), -1);
  for (int j = 0; j < lay.n; ++j) swinging_index[eq.pendulum(j).rig_index] = j;
  writeHeaders();
}

void NetworkFiles::Impl::writeHeaders() {
  std::string h = "t", o = "tau";
  for (const NetworkPlatform& p : net.platforms) {
    h += ",x_" + p.name + ",xdot_" + p.name + ",platform_" + p.name;
    o += ",r_" + p.name + ",Phi_" + p.name;
  }
  for (int i = 1; i <= net.numMetronomes(); ++i)
    h += ",theta_" + std::to_string(i) + ",thetadot_" + std::to_string(i);
  trajectory.writeLine(h);
  // a network is physical: t_s (seconds) last, as in every CSV of a physical rig
  envelope.writeLine(envelopeHeader(net.numMetronomes()) + ",t_s");
  order.writeLine(o + ",r,Phi,t_s");
}

NetworkFiles::NetworkFiles(const OutputDir& dir, const Network& net)
    : impl_(std::make_unique<Impl>(dir, net)) {}
NetworkFiles::~NetworkFiles() = default;

void NetworkFiles::add(double t, const std::vector<double>& y,
                       const std::vector<PlatformMode>& modes) {
  Impl& m = *impl_;
  m.verdict.stateSample(t, y, modes);
  std::vector<double> row{t};
  for (int p = 0; p < m.lay.platforms; ++p) {
    const bool coulomb = m.eq.block(p).friction.setValued() && m.eq.block(p).moves;
    const double u = m.eq.slipVelocity(y.data(), p);
    row.insert(row.end(), {y[m.lay.x(p)], y[m.lay.v(p)],
                           coulomb ? static_cast<double>(static_cast<int>(modes[p]))
                                   : static_cast<double>((u > 0) - (u < 0))});
  }
  for (int i = 0; i < m.net.numMetronomes(); ++i) {
    const int j = m.swinging_index[i];
    row.push_back(j < 0 ? 0.0 : y[m.lay.theta(j)]);
    row.push_back(j < 0 ? 0.0 : y[m.lay.omega(j)]);
  }
  m.trajectory.writeLine(csvLine(row));
  EnvelopeRow env = m.verdict.last();
  env.r = std::numeric_limits<double>::quiet_NaN();  // formatEnvelopeRow computes it, as before
  m.envelope.writeLine(formatEnvelopeRow(env) + "," + csvLine({t}));

  const std::vector<double>& phi = m.verdict.phases();
  std::vector<double> orow{env.tau}, raster{env.tau};
  for (int p = 0; p < m.lay.platforms; ++p) {
    const network::Block& b = m.eq.block(p);
    const Order& o = m.verdict.groups()[p];
    orow.insert(orow.end(), {o.r, o.Phi});
    for (int j = b.first; j < b.first + b.count; ++j) raster.push_back(wrapToPi(phi[j] - o.Phi));
  }
  orow.insert(orow.end(), {m.verdict.overall().r, m.verdict.overall().Phi});
  m.order.writeLine(csvLine(orow) + "," + csvLine({t}));
  keepForPlots(orow, raster);
}

void NetworkFiles::keepForPlots(const std::vector<double>& order,
                                const std::vector<double>& raster) {
  Impl& m = *impl_;
  if (m.seen++ % m.stride != 0) return;
  std::vector<double> o{order[0]};  // tau, r per platform, r overall
  for (std::size_t k = 1; k < order.size(); k += 2) o.push_back(order[k]);
  order_rows_.push_back(o);
  raster_rows_.push_back(raster);
  if (order_rows_.size() < 2 * kMaxPlotRows) return;
  for (std::size_t k = 0; 2 * k < order_rows_.size(); ++k) {
    order_rows_[k] = order_rows_[2 * k];
    raster_rows_[k] = raster_rows_[2 * k];
  }
  order_rows_.resize(order_rows_.size() / 2);
  raster_rows_.resize(raster_rows_.size() / 2);
  m.stride *= 2;
}

void NetworkFiles::commit() {
  impl_->trajectory.commit();
  impl_->envelope.commit();
  impl_->order.commit();
}

std::vector<std::string> NetworkFiles::fileNames() const {
  return {"trajectory.csv", "envelope.csv", "order.csv"};
}

namespace {

// A platform's final envelope: its metronomes' amplitudes (global numbers in its `metronomes`),
// their phases relative to its first, psi_k - psi_first of the network's (0 beside a locked one).
nlohmann::json platformFinal(const Network& net, int p, const EnvelopeRow& last) {
  const int first = net.firstMetronome(p);
  const std::vector<MetronomeSpec>& ms = net.platforms[p].rig.metronomes;
  auto psi = [&](int i) { return i == 0 ? 0.0 : last.psi[i - 1]; };  // psi_1 = 0
  std::vector<double> a, d;
  for (std::size_t k = 0; k < ms.size(); ++k) {
    const int i = first + static_cast<int>(k);
    a.push_back(last.A[i]);
    if (k == 0) continue;
    d.push_back(ms[k].locked || ms[0].locked ? 0.0 : psi(i) - psi(first));
  }
  return {{"tau", last.tau}, {"A", a}, {"psi", d}};
}

}  // namespace

nlohmann::json NetworkFiles::platformsJson(bool complete) const {
  const Impl& m = *impl_;
  const std::vector<std::string> regimes = m.verdict.platformRegimes();
  const std::vector<Order>& groups = m.verdict.groups();
  nlohmann::json platforms = nlohmann::json::object();
  for (int p = 0; p < m.lay.platforms; ++p) {
    const NetworkPlatform& np = m.net.platforms[p];
    std::vector<int> numbers;
    for (std::size_t i = 0; i < np.rig.metronomes.size(); ++i)
      numbers.push_back(m.net.firstMetronome(p) + static_cast<int>(i) + 1);
    platforms[np.name] = {{"regime", complete ? regimes[p] : "unknown"},
                          {"metronomes", numbers},
                          {"r", groups.empty() ? 0.0 : groups[p].r}};
    if (!m.verdict.empty()) platforms[np.name]["final"] = platformFinal(m.net, p, m.verdict.last());
  }
  return platforms;
}

// The label's window as a single run's `regime_window` (its start in tau, its rows), with each
// platform's mean r and the drift of its mean phase against the first platform's.
nlohmann::json NetworkFiles::regimeWindowJson() const {
  const Impl& m = *impl_;
  const NetworkWindow& w = m.verdict.window();
  const ScaledParams sp = computeScaled(m.net.scalesRig());
  nlohmann::json platforms = nlohmann::json::object();
  for (int p = 0; p < w.groups(); ++p)
    platforms[m.net.platforms[p].name] = {
        {"r_mean", w.meanR(p)}, {"dphi_range", w.dPhiRange(p)}, {"dphi_final", w.dPhiFinal(p)}};
  return {{"tau_start", w.tStart() / sp.time_scale_s * sp.epsilon},
          {"rows", w.rows()},
          {"platforms", platforms}};
}

nlohmann::json NetworkFiles::verdictJson(const RunReport& report) const {
  const Impl& m = *impl_;
  nlohmann::json j;
  j["platforms"] = platformsJson(report.complete);
  const std::string label = report.complete ? m.verdict.label() : "unknown";
  j["network"] = {{"regime", label}, {"r", m.verdict.overall().r}};
  j["regime"] = label;  // as a single run's: the network's label
  j["regime_window"] = regimeWindowJson();
  if (!m.verdict.empty()) {
    const EnvelopeRow& last = m.verdict.last();
    j["final"] = {{"tau", last.tau}, {"A", last.A}, {"psi", last.psi}};
  }
  return j;
}

}  // namespace metrosync
