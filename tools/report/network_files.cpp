#include "tools/report/network_files.h"

#include <cmath>
#include <sstream>

#include "models/network_equations.h"
#include "models/scaling.h"
#include "sim/analysis/network_regime.h"
#include "sim/analysis/order_parameter.h"
#include "sim/analysis/regime.h"
#include "sim/record/atomic_file.h"
#include "tools/report/plot.h"

namespace metrosync {

namespace {

constexpr double kTwoPi = 6.283185307179586;
// Rows kept for the plots: every other one is dropped when twice this many are held, so memory is
// bounded whatever the run's length (as the envelope's EnvelopeDecimator).
constexpr std::size_t kMaxPlotRows = 2000;

std::string csvLine(const std::vector<double>& v) {
  std::ostringstream os;
  os.precision(17);
  for (std::size_t i = 0; i < v.size(); ++i) os << (i ? "," : "") << v[i];
  return os.str();
}

}  // namespace

struct NetworkFiles::Impl {
  const Network& net;
  network::NetworkEquations eq;
  network::Layout lay;
  ScaledParams sp;
  double omega0 = 1.0;
  std::vector<double> omega;        // (n) each swinging pendulum's frequency
  std::vector<int> platform_of;     // (n) its platform
  std::vector<int> swinging_index;  // (N metronomes) -> swinging pendulum or -1 (locked)
  AtomicFile trajectory, envelope, order;
  std::vector<PhaseUnwrapper> unwrap;           // (N-1) psi_2..psi_N
  std::vector<PhaseUnwrapper> platform_unwrap;  // (n) psi within each platform
  std::vector<RegimeWindow> regimes;            // per platform
  NetworkWindow window;
  std::vector<Order> last_groups;
  Order last_all;
  std::size_t stride = 1;
  long seen = 0;

  Impl(const OutputDir& dir, const Network& n);
  void writeHeaders();
  std::vector<double> phases(const std::vector<double>& y) const;
  void platformEnvelope(int p, double tau, const std::vector<double>& y,
                        const std::vector<double>& phi);
};

NetworkFiles::Impl::Impl(const OutputDir& dir, const Network& n)
    : net(n),
      eq(n),
      lay(eq.layout()),
      sp(computeScaled(n.scalesRig())),
      trajectory(dir.file("trajectory.csv")),
      envelope(dir.file("envelope.csv")),
      order(dir.file("order.csv")),
      window(static_cast<int>(n.platforms.size()), n.sim.t_end_s, kTwoPi * sp.time_scale_s) {
  omega0 = 1.0 / sp.time_scale_s;
  swinging_index.assign(n.numMetronomes(), -1);
  for (int j = 0; j < lay.n; ++j) {
    const direct::PendulumConstants& q = eq.pendulum(j);
    omega.push_back(std::sqrt(q.mgL / q.inertia));
    swinging_index[q.rig_index] = j;
    int p = 0;
    while (j >= eq.block(p).first + eq.block(p).count) ++p;
    platform_of.push_back(p);
  }
  unwrap.resize(std::max(0, n.numMetronomes() - 1));
  platform_unwrap.resize(lay.n);
  const double tau_end = n.sim.t_end_s * omega0 * sp.epsilon;
  for (std::size_t p = 0; p < n.platforms.size(); ++p) regimes.emplace_back(tau_end, sp.epsilon);
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

std::vector<double> NetworkFiles::Impl::phases(const std::vector<double>& y) const {
  std::vector<double> phi(lay.n);
  for (int j = 0; j < lay.n; ++j)
    phi[j] = pendulumPhase(y[lay.theta(j)], y[lay.omega(j)], omega[j]);
  return phi;
}

// Platform p's own envelope row (its metronomes, the first as reference) for its regime.
void NetworkFiles::Impl::platformEnvelope(int p, double tau, const std::vector<double>& y,
                                          const std::vector<double>& phi) {
  const network::Block& b = eq.block(p);
  EnvelopeRow row;
  row.tau = tau;
  for (int j = b.first; j < b.first + b.count; ++j) {
    const double a = std::hypot(y[lay.theta(j)], y[lay.omega(j)] / omega[j]);
    row.A.push_back(a / sp.angle_scale);
    if (j > b.first) row.psi.push_back(platform_unwrap[j](phi[b.first] - phi[j]));
  }
  if (b.count > 0) regimes[p].add(row);
}

NetworkFiles::NetworkFiles(const OutputDir& dir, const Network& net)
    : impl_(std::make_unique<Impl>(dir, net)) {}
NetworkFiles::~NetworkFiles() = default;

void NetworkFiles::sample(double t, const std::vector<double>& y,
                          const std::vector<PlatformMode>& modes) {
  Impl& m = *impl_;
  const double tau = t * m.omega0 * m.sp.epsilon;
  std::vector<double> row{t};
  for (int p = 0; p < m.lay.platforms; ++p) {
    const bool coulomb = m.eq.block(p).friction.setValued() && m.eq.block(p).moves;
    const double u = m.eq.slipVelocity(y.data(), p);
    row.insert(row.end(), {y[m.lay.x(p)], y[m.lay.v(p)],
                           coulomb ? static_cast<double>(static_cast<int>(modes[p]))
                                   : static_cast<double>((u > 0) - (u < 0))});
  }
  const std::vector<double> phi = m.phases(y);
  EnvelopeRow env;
  env.tau = tau;
  for (int i = 0; i < m.net.numMetronomes(); ++i) {
    const int j = m.swinging_index[i];
    row.push_back(j < 0 ? 0.0 : y[m.lay.theta(j)]);
    row.push_back(j < 0 ? 0.0 : y[m.lay.omega(j)]);
    env.A.push_back(j < 0 ? 0.0
                          : std::hypot(y[m.lay.theta(j)], y[m.lay.omega(j)] / m.omega[j]) /
                                m.sp.angle_scale);
    const int j1 = m.swinging_index[0];
    if (i > 0) env.psi.push_back(j < 0 || j1 < 0 ? 0.0 : m.unwrap[i - 1](phi[j1] - phi[j]));
  }
  m.trajectory.writeLine(csvLine(row));
  m.envelope.writeLine(formatEnvelopeRow(env) + "," + csvLine({t}));

  std::vector<double> orow{tau}, raster{tau};
  m.last_groups.clear();
  for (int p = 0; p < m.lay.platforms; ++p) {
    const network::Block& b = m.eq.block(p);
    const Order o =
        orderParameter(std::vector<double>(phi.begin() + b.first, phi.begin() + b.first + b.count));
    m.last_groups.push_back(o);
    orow.insert(orow.end(), {o.r, o.Phi});
    for (int j = b.first; j < b.first + b.count; ++j) raster.push_back(wrapToPi(phi[j] - o.Phi));
    m.platformEnvelope(p, tau, y, phi);
  }
  m.last_all = orderParameter(phi);
  orow.insert(orow.end(), {m.last_all.r, m.last_all.Phi});
  m.order.writeLine(csvLine(orow) + "," + csvLine({t}));
  m.window.add(t, m.last_groups);
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

nlohmann::json NetworkFiles::summary(const NetworkRunReport& report) const {
  const Impl& m = *impl_;
  nlohmann::json platforms = nlohmann::json::object();
  for (int p = 0; p < m.lay.platforms; ++p) {
    const NetworkPlatform& np = m.net.platforms[p];
    std::vector<int> numbers;
    std::vector<double> theta_c;
    std::vector<bool> locked;
    for (std::size_t i = 0; i < np.rig.metronomes.size(); ++i) {
      const MetronomeSpec& ms = np.rig.metronomes[i];
      numbers.push_back(m.net.firstMetronome(p) + static_cast<int>(i) + 1);
      if (ms.locked) continue;
      theta_c.push_back(ms.theta_c_rad / m.sp.angle_scale);
    }
    std::string regime = "unknown";
    if (report.complete && !theta_c.empty())
      regime = regimeName(classifyRegime(m.regimes[p], theta_c));
    platforms[np.name] = {{"regime", regime},
                          {"metronomes", numbers},
                          {"r", m.last_groups.empty() ? 0.0 : m.last_groups[p].r}};
  }
  nlohmann::json j;
  j["platforms"] = platforms;
  j["network"] = {{"regime", report.complete ? classifyNetwork(m.window) : "unknown"},
                  {"r", m.last_all.r}};
  j["complete"] = report.complete;
  if (!report.complete) j["failure"] = report.failure;
  j["engine"] = report.engine;
  j["integrator"] = report.integrator;
  j["counts"] = {{"steps", report.steps},           {"rhs_evals", report.rhs_evals},
                 {"events", report.events},         {"escapements", report.ticks},
                 {"stick_slip", report.stick_slip}, {"slip_reversals", report.slip_reversals}};
  const EnergyLedger& e = report.ledger;
  j["energy"] = {{"initial_J", e.initial_J},
                 {"final_J", e.final_J},
                 {"escapement_in_J", e.escapement_in_J},
                 {"damping_out_J", e.damping_out_J},
                 {"friction_out_J", e.friction_out_J},
                 {"residual_J", e.residual_J()},
                 {"relative_residual", e.relativeResidual()}};
  return j;
}

namespace {

std::string rowsText(const std::vector<std::vector<double>>& rows) {
  std::ostringstream os;
  os.precision(9);
  for (const auto& r : rows) {
    for (std::size_t k = 0; k < r.size(); ++k) os << (k ? " " : "") << r[k];
    os << "\n";
  }
  return os.str();
}

// one "tau metronome phase" line per metronome and kept sample, for a palette raster
std::string rasterText(const std::vector<std::vector<double>>& rows) {
  std::ostringstream os;
  os.precision(6);
  for (const auto& r : rows)
    for (std::size_t k = 1; k < r.size(); ++k) os << r[0] << " " << k << " " << r[k] << "\n";
  return os.str();
}

}  // namespace

std::vector<std::string> plotNetwork(const OutputDir& dir, const NetworkFiles& files,
                                     const Network& net, const std::string& title) {
  std::vector<std::string> made;
  const int groups = static_cast<int>(net.platforms.size());
  auto order_script = [&](const std::string& data, const std::string& png) {
    std::ostringstream s;
    s << "set terminal pngcairo size 1000,500\nset output '" << png << "'\n"
      << "set title '" << title << "' noenhanced\nset xlabel 'tau'\nset ylabel 'r'\n"
      << "set yrange [0:1.05]\nset key outside right\nplot ";
    for (int g = 0; g < groups; ++g)
      s << "'" << data << "' using 1:" << g + 2 << " with lines title 'r " << net.platforms[g].name
        << "' noenhanced, ";
    s << "'" << data << "' using 1:" << groups + 2 << " with lines lw 2 title 'r (all)'\n";
    return s.str();
  };
  if (drawPng(dir, "order.png", rowsText(files.orderRows()), order_script))
    made.push_back("order.png");
  auto raster_script = [&](const std::string& data, const std::string& png) {
    std::ostringstream s;
    s << "set terminal pngcairo size 1000,600\nset output '" << png << "'\n"
      << "set title '" << title << " - phase relative to its platform' noenhanced\n"
      << "set xlabel 'tau'\nset ylabel 'metronome'\nset cbrange [-pi:pi]\n"
      << "set palette model HSV functions gray, 1, 0.9\nunset key\n"  // cyclic: -pi = pi
      << "set yrange [0.5:" << net.numMetronomes() + 0.5 << "]\n"
      << "plot '" << data << "' using 1:2:3 with points pt 5 ps 0.4 palette\n";
    return s.str();
  };
  if (drawPng(dir, "raster.png", rasterText(files.rasterRows()), raster_script))
    made.push_back("raster.png");
  return made;
}

}  // namespace metrosync
