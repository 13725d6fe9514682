#include "tools/cli/animation_track.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "models/network_equations.h"
#include "models/scaling.h"
#include "sim/engines/direct/direct_engine.h"

namespace metrosync::cli {

namespace {

using animation::Contact;
using animation::FrameState;
using animation::Scene;

// A tick's flash fades out over this many frames (a fixed number of frames, so that it is seen
// at any --speed).
constexpr double kFlashFrames = 2.5;
// An event row whose |theta_i| is this close to theta_c,i (relative) is pendulum i's tick: the
// engines end a tick's window a few ulps past the crossing (docs/events.md).
constexpr double kTickMatch = 1e-6;
// Network traces keep at most about this many points (a polyline per metronome per frame).
constexpr std::size_t kMaxTracePoints = 800;

// The state at one instant, physical units, every metronome (locked ones at 0).
struct Snapshot {
  double t = 0.0;
  std::vector<double> x, v, theta, omega;
  std::vector<Contact> contact;
};

struct Tick {
  double t;
  int i;
};

Contact contactOf(bool coulomb, int mode) {
  if (!coulomb) return Contact::Smooth;
  return mode == 0 ? Contact::Stuck : (mode > 0 ? Contact::SlipPositive : Contact::SlipNegative);
}

// Cubic Hermite interpolation of q with rate qd between t0 (a) and t1 (b), at fraction s of h.
double hermite(double a, double da, double b, double db, double h, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * a + (s3 - 2 * s2 + s) * h * da + (-2 * s3 + 3 * s2) * b +
         (s3 - s2) * h * db;
}

// Puts snapshots (in time order) on the frame grid.
class FrameGrid {
 public:
  explicit FrameGrid(const AnimationRequest& r)
      : dt_(r.frameInterval()), first_(r.firstFrameIndex()), n_(r.frameCount()) {}

  void add(const Snapshot& s, std::vector<FrameState>& out) {
    while (next_ < n_ && timeOf(next_) <= s.t) {
      out.push_back(have_ && s.t > prev_.t ? between(prev_, s, timeOf(next_)) : at(s, s.t));
      ++next_;
    }
    prev_ = s;
    have_ = true;
  }
  // as the engines' sample times (sim/events/sample_schedule.h), bit for bit
  double timeOf(long k) const { return static_cast<double>(first_ + k) * dt_; }

 private:
  static FrameState at(const Snapshot& s, double t) {
    FrameState f;
    f.t = t;
    f.x = s.x;
    f.contact = s.contact;
    f.theta = s.theta;
    f.flash.assign(s.theta.size(), 0.0);
    return f;
  }
  static FrameState between(const Snapshot& a, const Snapshot& b, double t) {
    const double h = b.t - a.t, s = std::clamp((t - a.t) / h, 0.0, 1.0);
    FrameState f = at(s < 0.5 ? a : b, t);
    for (std::size_t p = 0; p < a.x.size(); ++p)
      f.x[p] = hermite(a.x[p], a.v[p], b.x[p], b.v[p], h, s);
    for (std::size_t i = 0; i < a.theta.size(); ++i)
      f.theta[i] = hermite(a.theta[i], a.omega[i], b.theta[i], b.omega[i], h, s);
    return f;
  }

  double dt_;
  long first_, n_, next_ = 0;
  bool have_ = false;
  Snapshot prev_;
};

// The flashes (from the ticks), the traces drawn in each frame, the largest excursion.
void finishFrames(AnimationTrack& tr, std::vector<Tick> ticks, const AnimationRequest& req) {
  std::sort(ticks.begin(), ticks.end(), [](const Tick& a, const Tick& b) { return a.t < b.t; });
  tr.ticks.assign(tr.scene.metronomes.size(), 0);
  for (const Tick& k : ticks) ++tr.ticks[k.i];
  const double fade = kFlashFrames * req.frameInterval();
  Scene& sc = tr.scene;
  std::size_t first = 0, trace = 0;
  for (FrameState& f : tr.frames) {
    while (first < ticks.size() && ticks[first].t <= f.t - fade) ++first;
    for (std::size_t k = first; k < ticks.size() && ticks[k].t <= f.t; ++k)
      f.flash[ticks[k].i] = std::max(f.flash[ticks[k].i], 1.0 - (f.t - ticks[k].t) / fade);
    while (trace < sc.trace_tau.size() && sc.trace_tau[trace] <= f.t * sc.tau_per_s) ++trace;
    f.trace_points = trace;
    for (double x : f.x) sc.max_abs_x_m = std::max(sc.max_abs_x_m, std::abs(x));
  }
}

void setTraceWindow(Scene& sc, const AnimationRequest& req) {
  sc.tau_from = req.from * sc.tau_per_s;
  sc.tau_to = req.to * sc.tau_per_s;
  sc.width = req.width;
  sc.height = req.height;
  sc.title = req.title;
}

void addThetaC(Scene& sc, double tc) {
  for (double x : sc.theta_c_scaled)
    if (std::abs(x - tc) <= 1e-9 * std::abs(tc)) return;
  sc.theta_c_scaled.push_back(tc);
}

animation::ScenePlatform platformOf(const std::string& name, const PlatformSpec& p) {
  animation::ScenePlatform sp;
  sp.name = name;
  sp.fixed = !p.friction.platformMoves();
  sp.coulomb = p.friction.setValued();  // stick/slip: drawn with its modes
  sp.ground_spring = p.spring_N_m > 0;
  return sp;
}

void addMetronomes(Scene& sc, animation::ScenePlatform& plat, const Rig& rig) {
  for (const MetronomeSpec& m : rig.metronomes) {
    plat.metronomes.push_back(static_cast<int>(sc.metronomes.size()));
    sc.metronomes.push_back({m.name, m.length_m, m.theta_c_rad, m.locked});
  }
}

}  // namespace

long AnimationRequest::frameCount() const {
  return std::lround((to - from) * fps / speed);
}

long AnimationRequest::firstFrameIndex() const {
  return std::lround(from / frameInterval());
}

// --- one platform -------------------------------------------------------------------------

namespace {

class RigSink : public RunSink {
 public:
  RigSink(const Rig& rig, const ScaledParams& sp, const AnimationRequest& req, AnimationTrack& tr)
      : rig_(rig), tr_(tr), grid_(req) {
    const bool scaled = rig.units == Units::Scaled;
    t_unit_ = scaled ? sp.time_scale_s : 1.0;
    x_unit_ = scaled ? sp.x_scale_m : 1.0;
    a_unit_ = scaled ? sp.angle_scale : 1.0;
  }
  void trajectoryRow(const std::vector<double>& row) override {
    const Snapshot s = snapshot(row);
    grid_.add(s, tr_.frames);
  }
  void envelopeRow(const EnvelopeRow& row) override {
    const Scene& sc = tr_.scene;
    const double slack = 1e-12 * std::max(1.0, std::abs(sc.tau_to));
    if (row.tau < sc.tau_from - slack || row.tau > sc.tau_to + slack) return;
    tr_.scene.trace_tau.push_back(row.tau);
    tr_.scene.trace_A.push_back(row.A);
  }
  void eventRow(const char* kind, const std::vector<double>& row) override {
    if (std::strcmp(kind, "tick") != 0) return;
    const Snapshot s = snapshot(row);
    for (std::size_t i = 0; i < rig_.metronomes.size(); ++i) {
      const double tc = rig_.metronomes[i].theta_c_rad;
      if (!rig_.metronomes[i].locked && std::abs(std::abs(s.theta[i]) - tc) <= kTickMatch * tc)
        ticks.push_back({s.t, static_cast<int>(i)});
    }
  }
  std::vector<Tick> ticks;

 private:
  // a row of trajectory.csv (t, x, xdot, theta_i, thetadot_i..., platform) in physical units
  Snapshot snapshot(const std::vector<double>& row) const {
    Snapshot s;
    s.t = row[0] * t_unit_;
    s.x = {row[1] * x_unit_};
    s.v = {row[2] * x_unit_ / t_unit_};
    for (std::size_t i = 0; i < rig_.metronomes.size(); ++i) {
      s.theta.push_back(row[3 + 2 * i] * a_unit_);
      s.omega.push_back(row[4 + 2 * i] * a_unit_ / t_unit_);
    }
    s.contact = {
        contactOf(rig_.platform.friction.setValued(), static_cast<int>(std::lround(row.back())))};
    return s;
  }

  const Rig& rig_;
  AnimationTrack& tr_;
  FrameGrid grid_;
  double t_unit_ = 1, x_unit_ = 1, a_unit_ = 1;
};

Scene rigScene(const Rig& rig, const ScaledParams& sp, const AnimationRequest& req) {
  Scene sc;
  sc.physical = rig.units == Units::Physical;
  sc.tau_per_s = sp.epsilon / sp.time_scale_s;
  setTraceWindow(sc, req);
  animation::ScenePlatform plat = platformOf("platform", rig.platform);
  addMetronomes(sc, plat, rig);
  sc.platforms.push_back(plat);
  for (std::size_t i = 0; i < rig.metronomes.size(); ++i)
    if (!rig.metronomes[i].locked) addThetaC(sc, sp.theta_c[i]);
  return sc;
}

}  // namespace

AnimationTrack trackRig(Rig rig, const Engine& engine, const AnimationRequest& req) {
  rig.sim.t_end_s = req.to;
  rig.sim.sample_s = req.frameInterval();
  const ScaledParams sp = computeScaled(rig);
  AnimationTrack tr;
  tr.scene = rigScene(rig, sp, req);
  RigSink sink(rig, sp, req, tr);
  const RunReport rep = engine.run(rig, sink);
  tr.complete = rep.complete;
  tr.failure = rep.failure;
  finishFrames(tr, sink.ticks, req);
  return tr;
}

// --- a network ------------------------------------------------------------------------------

namespace {

// The scales of the network's first swinging metronome (as its envelope.csv,
// tools/report/network_files.cpp).
ScaledParams networkScales(const Network& net) {
  Rig rig = net.platforms[0].rig;
  rig.metronomes.clear();
  for (const NetworkPlatform& p : net.platforms)
    for (const MetronomeSpec& m : p.rig.metronomes)
      if (!m.locked && rig.metronomes.empty()) rig.metronomes.push_back(m);
  if (!rig.platform.friction.platformMoves()) rig.platform.friction = FrictionLaw::none();
  return computeScaled(rig);
}

class NetworkTrackSink : public StateSink {
 public:
  NetworkTrackSink(const Network& net, const ScaledParams& sp, const AnimationRequest& req,
                   AnimationTrack& tr)
      : eq_(net), lay_(eq_.layout()), sp_(sp), tr_(tr), grid_(req), n_(net.numMetronomes()) {
    for (int j = 0; j < lay_.n; ++j)
      omega_.push_back(std::sqrt(eq_.pendulum(j).mgL / eq_.pendulum(j).inertia));
    const long frames = std::max(1L, req.frameCount());
    stride_ = std::max<long>(1, frames / static_cast<long>(kMaxTracePoints));
  }
  void stateSample(double t, const std::vector<double>& y,
                   const std::vector<PlatformMode>& modes) override;
  std::vector<Tick> ticks;

 private:
  void detectTicks(const Snapshot& s);
  void addTrace(const Snapshot& s);

  network::NetworkEquations eq_;
  network::Layout lay_;
  const ScaledParams& sp_;
  AnimationTrack& tr_;
  FrameGrid grid_;
  int n_;
  std::vector<double> omega_;
  std::vector<double> prev_theta_;
  double prev_t_ = 0.0;
  long stride_ = 1, seen_ = 0;
};

void NetworkTrackSink::stateSample(double t, const std::vector<double>& y,
                                   const std::vector<PlatformMode>& modes) {
  Snapshot s;
  s.t = t;
  for (int p = 0; p < lay_.platforms; ++p) {
    s.x.push_back(y[lay_.x(p)]);
    s.v.push_back(y[lay_.v(p)]);
    const network::Block& b = eq_.block(p);
    s.contact.push_back(contactOf(b.friction.setValued() && b.moves, static_cast<int>(modes[p])));
  }
  s.theta.assign(n_, 0.0);
  s.omega.assign(n_, 0.0);
  for (int j = 0; j < lay_.n; ++j) {
    s.theta[eq_.pendulum(j).rig_index] = y[lay_.theta(j)];
    s.omega[eq_.pendulum(j).rig_index] = y[lay_.omega(j)];
  }
  detectTicks(s);
  addTrace(s);
  grid_.add(s, tr_.frames);
}

// A tick between two samples: side s theta passed theta_c outwards (the escapement's witness
// s theta - theta_c rising, docs/events.md; through zero too, when a frame interval is a large
// part of a swing), dated by linear interpolation between the two samples.
void NetworkTrackSink::detectTicks(const Snapshot& s) {
  for (int j = 0; j < lay_.n && !prev_theta_.empty(); ++j) {
    const Escapement e = eq_.escapement(j);
    const int i = eq_.pendulum(j).rig_index;
    if (!e.active()) continue;
    for (double side : {1.0, -1.0}) {
      const double a = side * prev_theta_[i], b = side * s.theta[i];
      if (a < e.theta_c && b >= e.theta_c)
        ticks.push_back({prev_t_ + (e.theta_c - a) / (b - a) * (s.t - prev_t_), i});
    }
  }
  prev_theta_ = s.theta;
  prev_t_ = s.t;
}

// Instantaneous amplitudes sqrt(theta^2 + (thetadot / omega)^2), scaled (as the network's
// envelope.csv), every stride_-th sample in the window.
void NetworkTrackSink::addTrace(const Snapshot& s) {
  Scene& sc = tr_.scene;
  const double tau = s.t * sc.tau_per_s;
  if (tau < sc.tau_from || tau > sc.tau_to || seen_++ % stride_ != 0) return;
  std::vector<double> A(n_, 0.0);
  for (int j = 0; j < lay_.n; ++j) {
    const int i = eq_.pendulum(j).rig_index;
    A[i] = std::hypot(s.theta[i], s.omega[i] / omega_[j]) / sp_.angle_scale;
  }
  sc.trace_tau.push_back(tau);
  sc.trace_A.push_back(A);
}

Scene networkScene(const Network& net, const ScaledParams& sp, const AnimationRequest& req) {
  Scene sc;
  sc.tau_per_s = sp.epsilon / sp.time_scale_s;
  setTraceWindow(sc, req);
  for (const NetworkPlatform& p : net.platforms) {
    animation::ScenePlatform plat = platformOf(p.name, p.rig.platform);
    plat.on = p.on;
    addMetronomes(sc, plat, p.rig);
    sc.platforms.push_back(plat);
    for (const MetronomeSpec& m : p.rig.metronomes)
      if (!m.locked) addThetaC(sc, m.theta_c_rad / sp.angle_scale);
  }
  for (const Coupling& c : net.couplings) sc.couplings.push_back({c.a, c.b});
  return sc;
}

}  // namespace

AnimationTrack trackNetwork(Network net, const Engine& engine, const AnimationRequest& req) {
  net.sim.t_end_s = req.to;
  net.sim.sample_s = req.frameInterval();
  const ScaledParams sp = networkScales(net);
  AnimationTrack tr;
  tr.scene = networkScene(net, sp, req);
  NetworkTrackSink sink(net, sp, req, tr);
  const RunReport rep = engine.run(net, sink);
  tr.complete = rep.complete;
  tr.failure = rep.failure;
  finishFrames(tr, sink.ticks, req);
  return tr;
}

}  // namespace metrosync::cli
