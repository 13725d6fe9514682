// The Siconos peer (see siconos_peer.h). Stages, top to bottom:
//   1. the model's coefficients, packed into the LagrangianDS's parameter vector z for the plugins
//   2. plugins: M(q), F_int(q, v) and its Jacobians in q and v (column-major, as Siconos's dense
//      matrices are)
//   3. the Siconos objects: DS, relay interaction, Moreau-Jean, relay problem, time-stepping
//   4. the step loop: escapement forces for the step, one Moreau-Jean step, tick detection,
//   platform
//      mode from the relay's impulse, envelope samples
#include "tools/bench/siconos_peer.h"

#include <SiconosKernel.hpp>
#include <chrono>
#include <cmath>
#include <sstream>

#include "models/scaling.h"
#include "tools/bench/sampled_envelope.h"

namespace metrosync::bench {

bool siconosAvailable() {
  return true;
}

std::string siconosUnsupported(const Rig& rig) {
  if (rig.platform.friction != FrictionLaw::coulomb(rig.platform.friction.valueOr("mu", 0.0)))
    return "platform friction law is not coulomb with one mu (the peer models Coulomb friction as "
           "a relay)";
  if (rig.platform.spring_N_m != 0) return "platform spring (not modelled by the peer)";
  for (const auto& m : rig.metronomes)
    if (m.locked) return "locked metronome (not modelled by the peer)";
  return "";
}

namespace {

// --- 1. coefficients in z: [N, M, g, then per pendulum: m_i L_i, I_i, nu-bar_i L_i^2] ----------
constexpr int kHead = 3;
constexpr int kPer = 3;

long g_fint_evals = 0;  // F_int evaluations of the current run (the peer is single-threaded)

// --- 2. plugins (signatures fixed by Siconos's PluginTypes.hpp) --------------------------------
// M(q): [[M, m_i L_i cos theta_i], [m_i L_i cos theta_i, diag(I_i)]]
void massPlugin(unsigned n, double* q, double* mass, unsigned, double* z) {
  for (unsigned k = 0; k < n * n; ++k) mass[k] = 0.0;
  mass[0] = z[1];
  for (unsigned i = 1; i < n; ++i) {
    const double* c = z + kHead + kPer * (i - 1);
    const double coupling = c[0] * std::cos(q[i]);
    mass[i] = coupling;      // (i, 0)
    mass[i * n] = coupling;  // (0, i)
    mass[i + i * n] = c[1];  // (i, i)
  }
}

// F_int(q, v), on the left-hand side with M(q) v':
//   platform (e1.1c):   - sum_i m_i L_i thetadot_i^2 sin theta_i
//   pendulum i (e1.1a): m_i g L_i sin theta_i + nu-bar_i L_i^2 thetadot_i
void fIntPlugin(double, unsigned n, double* q, double* v, double* f, unsigned, double* z) {
  ++g_fint_evals;
  const double g = z[2];
  f[0] = 0.0;
  for (unsigned i = 1; i < n; ++i) {
    const double* c = z + kHead + kPer * (i - 1);
    const double s = std::sin(q[i]);
    f[0] -= c[0] * v[i] * v[i] * s;
    f[i] = c[0] * g * s + c[2] * v[i];
  }
}

void jacFIntqPlugin(double, unsigned n, double* q, double* v, double* jac, unsigned, double* z) {
  const double g = z[2];
  for (unsigned k = 0; k < n * n; ++k) jac[k] = 0.0;
  for (unsigned i = 1; i < n; ++i) {
    const double* c = z + kHead + kPer * (i - 1);
    const double cs = std::cos(q[i]);
    jac[i * n] = -c[0] * v[i] * v[i] * cs;  // (0, i)
    jac[i + i * n] = c[0] * g * cs;         // (i, i)
  }
}

void jacFIntvPlugin(double, unsigned n, double* q, double* v, double* jac, unsigned, double* z) {
  for (unsigned k = 0; k < n * n; ++k) jac[k] = 0.0;
  for (unsigned i = 1; i < n; ++i) {
    const double* c = z + kHead + kPer * (i - 1);
    jac[i * n] = -2.0 * c[0] * v[i] * std::sin(q[i]);  // (0, i)
    jac[i + i * n] = c[2];                             // (i, i)
  }
}

class PeerRun {
 public:
  PeerRun(const Rig& rig, RunSink& sink, const SiconosOptions& opt)
      : rig_(rig),
        sp_(computeScaled(rig)),
        sink_(sink),
        opt_(opt),
        n_(static_cast<int>(rig.metronomes.size())),
        env_(sp_.epsilon, std::vector<bool>(n_, true), sink) {
    omega0_ = 1.0 / sp_.time_scale_s;
    report_.model = "full";
    report_.engine = "siconos";
    report_.integrator = "moreau-jean";
    report_.accuracy = opt.step_s;
    report_.counts.escapements.assign(n_, 0);
  }

  RunReport run();

 private:
  // scaled samples for the envelope: theta_i / sqrt(eps), thetadot_i / (sqrt(eps) omega0)
  // (t_scaled: scaled time, so that a sample lands exactly on a period boundary)
  void sample(double t_scaled, const double* q, const double* v) {
    for (int i = 0; i < n_; ++i) {
      th_[i] = q[i + 1] / sp_.angle_scale;
      w_[i] = v[i + 1] / (sp_.angle_scale * omega0_);
    }
    env_.sample(t_scaled, th_.data(), w_.data());
  }
  // the trajectory format of the engines, in the rig's units (sim/record/run_report.h)
  std::vector<double> makeRow(double t, const double* q, const double* v, int mode) const {
    const bool scaled = rig_.units == Units::Scaled;
    const double xs = scaled ? 1.0 / sp_.x_scale_m : 1.0;
    const double as = scaled ? 1.0 / sp_.angle_scale : 1.0;
    const double ts = scaled ? omega0_ : 1.0;
    std::vector<double> row = {t * ts, q[0] * xs, v[0] * xs / ts};
    for (int i = 0; i < n_; ++i) {
      row.push_back(q[i + 1] * as);
      row.push_back(v[i + 1] * as / ts);
    }
    row.push_back(mode);
    return row;
  }

  const Rig& rig_;
  ScaledParams sp_;
  RunSink& sink_;
  SiconosOptions opt_;
  int n_;
  EnvelopeRecorder env_;
  RunReport report_;
  double omega0_ = 1.0;
  std::vector<double> th_ = std::vector<double>(n_), w_ = std::vector<double>(n_);
};

RunReport PeerRun::run() {
  const auto wall0 = std::chrono::steady_clock::now();
  const unsigned ndof = static_cast<unsigned>(n_ + 1);
  const double h = opt_.step_s;
  const double t_end = rig_.sim.t_end_s;
  const double g = rig_.gravity_m_s2;
  const double bound =
      rig_.platform.friction.valueOr("mu", 0.0) * rig_.totalMass() * g * h;  // impulse per step
  g_fint_evals = 0;

  // --- 3. the Siconos objects ---------------------------------------------------------------
  SP::SiconosVector q0(new SiconosVector(ndof)), v0(new SiconosVector(ndof));
  q0->setValue(0, rig_.platform.start_x_m);
  v0->setValue(0, rig_.platform.start_v_m_s);
  SP::SiconosVector z(new SiconosVector(kHead + kPer * n_));
  z->setValue(0, n_);
  z->setValue(1, rig_.totalMass());
  z->setValue(2, g);
  for (int i = 0; i < n_; ++i) {
    const MetronomeSpec& m = rig_.metronomes[i];
    q0->setValue(i + 1, m.start_angle_rad);
    v0->setValue(i + 1, m.start_rate_rad_s);
    z->setValue(kHead + kPer * i + 0, m.pendulum_mass_kg * m.length_m);
    z->setValue(kHead + kPer * i + 1, m.inertia_kgm2);
    z->setValue(kHead + kPer * i + 2, m.damping_kg_s * m.length_m * m.length_m);
  }
  SP::LagrangianDS ds(new LagrangianDS(q0, v0));
  ds->setzPtr(z);
  ds->setComputeMassFunction(&massPlugin);
  ds->setComputeFIntFunction(&fIntPlugin);
  ds->setComputeJacobianFIntqFunction(&jacFIntqPlugin);
  ds->setComputeJacobianFIntqDotFunction(&jacFIntvPlugin);
  // escapement ticks as forces J-bar / h over one step (stage 4 fills it, constant in the step)
  SP::SiconosVector fext(new SiconosVector(ndof));
  ds->setFExtPtr(fext);

  // y = xdot (velocity level). The position-level output x + e only decides whether Siconos keeps
  // the interaction in its active set (as for a unilateral contact: active while y <= 0); the far
  // negative offset keeps the relay active whatever the platform's position.
  SP::SimpleMatrix C(new SimpleMatrix(1, ndof));
  C->setValue(0, 0, 1.0);
  SP::SiconosVector e(new SiconosVector(1));
  e->setValue(0, -1e9);
  SP::LagrangianLinearTIR relation(new LagrangianLinearTIR(C, e));
  SP::RelayNSL law(new RelayNSL(1, -bound, bound));
  SP::Interaction inter(new Interaction(law, relation));

  SP::NonSmoothDynamicalSystem nsds(new NonSmoothDynamicalSystem(0.0, t_end));
  nsds->insertDynamicalSystem(ds);
  nsds->link(inter, ds);
  SP::TimeDiscretisation td(new TimeDiscretisation(0.0, h));
  SP::MoreauJeanOSI osi(new MoreauJeanOSI(opt_.theta));
  SP::Relay relay(new Relay(SICONOS_RELAY_LEMKE));
  SP::TimeStepping sim(new TimeStepping(nsds, td, osi, relay));
  sim->setNewtonTolerance(opt_.newton_tol);
  sim->setNewtonMaxIteration(opt_.newton_max);
  sim->setWarnOnNonConvergence(false);

  // --- 4. the step loop ---------------------------------------------------------------------
  std::vector<double> q_prev(ndof), v_prev(ndof), q_now(ndof), v_now(ndof);
  for (unsigned k = 0; k < ndof; ++k) {
    q_prev[k] = q0->getValue(k);
    v_prev[k] = v0->getValue(k);
  }
  int mode = v_prev[0] > 0 ? 1 : (v_prev[0] < 0 ? -1 : 0);
  std::vector<double> tick_force(ndof, 0.0);  // generalized force for the coming step
  sink_.trajectoryRow(makeRow(0.0, q_prev.data(), v_prev.data(), mode));
  sample(0.0, q_prev.data(), v_prev.data());
  double t_prev = 0.0;
  long steps = 0;
  const long n_steps = static_cast<long>(std::ceil(t_end / h - 1e-9));
  try {
    sim->initialize();
    while (steps < n_steps && sim->hasNextEvent()) {
      for (unsigned k = 0; k < ndof; ++k) fext->setValue(k, tick_force[k]);
      sim->computeOneStep();
      const double t_now = sim->nextTime();
      for (unsigned k = 0; k < ndof; ++k) {
        q_now[k] = ds->q()->getValue(k);
        v_now[k] = ds->velocity()->getValue(k);
      }
      sim->nextStep();
      ++steps;
      for (unsigned k = 0; k < ndof; ++k) {
        if (!std::isfinite(q_now[k]) || !std::isfinite(v_now[k]))
          throw std::runtime_error("non-finite state");
      }

      // ticks: |theta_i| passed theta_c,i outwards during this step -> J-bar_i over the next step
      std::fill(tick_force.begin(), tick_force.end(), 0.0);
      bool ticked = false;
      for (int i = 0; i < n_; ++i) {
        const MetronomeSpec& m = rig_.metronomes[i];
        if (!(m.impulse_Nms > 0)) continue;
        const double th0 = q_prev[i + 1], th1 = q_now[i + 1], w1 = v_now[i + 1];
        const double side = th1 > 0 ? 1.0 : -1.0;
        if (side * th1 >= m.theta_c_rad && side * th0 < m.theta_c_rad && th1 * w1 > 0) {
          tick_force[i + 1] = side * m.impulse_Nms / h;
          ++report_.counts.escapements[i];
          ticked = true;
        }
      }
      // platform mode from the relay's impulse: interior of [-B, B] -> stuck
      const double lambda = inter->lambda(1)->getValue(0);
      const int new_mode = std::abs(lambda) < bound * (1 - 1e-6) ? 0 : (lambda < 0 ? 1 : -1);
      if (new_mode != mode) ++report_.counts.stick_slip;
      if (new_mode != mode || ticked) ++report_.counts.events;
      mode = new_mode;

      // envelope samples: period boundaries inside the step (linear), then the step's end
      const double ts_prev = t_prev * omega0_, ts_now = t_now * omega0_;
      while (env_.nextBoundary() < ts_now) {
        const double tb = env_.nextBoundary();
        const double a = (tb - ts_prev) / (ts_now - ts_prev);
        std::vector<double> qb(ndof), vb(ndof);
        for (unsigned k = 0; k < ndof; ++k) {
          qb[k] = q_prev[k] + a * (q_now[k] - q_prev[k]);
          vb[k] = v_prev[k] + a * (v_now[k] - v_prev[k]);
        }
        sample(tb, qb.data(), vb.data());
      }
      sample(ts_now, q_now.data(), v_now.data());
      q_prev.swap(q_now);
      v_prev.swap(v_now);
      t_prev = t_now;
    }
  } catch (const std::exception& ex) {
    report_.complete = false;
    std::ostringstream os;
    os << "simulation failed at t = " << t_prev << " s: " << ex.what();
    report_.failure = os.str();
  }
  report_.final_trajectory_row = makeRow(t_prev, q_prev.data(), v_prev.data(), mode);
  sink_.trajectoryRow(report_.final_trajectory_row);
  report_.final_row = env_.finish();
  report_.counts.steps = steps;
  report_.counts.rhs_evals = g_fint_evals;
  report_.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return report_;
}

}  // namespace

RunReport runSiconosPeer(const Rig& rig, RunSink& sink, const SiconosOptions& options) {
  PeerRun run(rig, sink, options);
  return run.run();
}

}  // namespace metrosync::bench
