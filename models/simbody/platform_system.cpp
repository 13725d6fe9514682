#include "models/simbody/platform_system.h"

#include <cmath>
#include <stdexcept>

#include "contact/simbody/smooth_friction_element.h"

namespace metrosync {

using namespace SimTK;

namespace {

// The ground springs and dampers of stacked platforms (-k_p x_p - c_p xdot_p) and the couplings
// (-k (x_a - x_b) - c (xdot_a - xdot_b) on a, the opposite on b), on the platforms' absolute
// coordinates, applied as forces along x on the platforms' bodies; the springs' potential energy
// for the ledger. (A table platform's ground spring and damper are mobility forces on its slider.)
class NetworkSprings : public Force::Custom::Implementation {
 public:
  explicit NetworkSprings(const PlatformSystem& ns) : ns_(ns) {}
  void calcForce(const State& s, Vector_<SpatialVec>& bodyForces, Vector_<Vec3>&,
                 Vector&) const override {
    const network::NetworkEquations& eq = ns_.equations();
    auto push = [&](int p, double F) {
      if (ns_.moves(p)) bodyForces[ns_.slider(p).getMobilizedBodyIndex()][1][0] += F;
    };
    for (int p = 0; p < ns_.numPlatforms(); ++p) {
      const network::Block& b = eq.block(p);
      if (stacked(p) && (b.k != 0 || b.c != 0)) push(p, -b.k * ns_.x(s, p) - b.c * ns_.xdot(s, p));
    }
    for (const Coupling& k : ns_.network().couplings) {
      const double F = -k.k_N_m * (ns_.x(s, k.a) - ns_.x(s, k.b)) -
                       k.c_Ns_m * (ns_.xdot(s, k.a) - ns_.xdot(s, k.b));
      push(k.a, F);
      push(k.b, -F);
    }
  }
  Real calcPotentialEnergy(const State& s) const override {
    double e = 0.0;
    for (int p = 0; p < ns_.numPlatforms(); ++p) {
      if (!stacked(p)) continue;  // a table platform's spring is a mobility spring
      const double x = ns_.x(s, p);
      e += 0.5 * ns_.equations().block(p).k * x * x;
    }
    for (const Coupling& k : ns_.network().couplings) {
      const double d = ns_.x(s, k.a) - ns_.x(s, k.b);
      e += 0.5 * k.k_N_m * d * d;
    }
    return e;
  }
  bool dependsOnlyOnPositions() const override { return false; }

 private:
  bool stacked(int p) const { return ns_.moves(p) && !ns_.onGround(p); }
  const PlatformSystem& ns_;
};

// Integrates, as continuous state variables z, the power taken out by the pivot dampers, by the
// contacts' friction, and (a third z, only when the network has any) by the ground and coupling
// dampers (joules): no z that stays 0, so that a single rig integrates the state it always did.
// A pendulum's air drag (pendulum.air_drag, issue 41): the pivot torque -d u |u| on its pin's
// rate u.
class AirDrag : public Force::Custom::Implementation {
 public:
  AirDrag(const MobilizedBody& pin, double drag) : pin_(pin), drag_(drag) {}
  void calcForce(const State& s, Vector_<SpatialVec>&, Vector_<Vec3>&,
                 Vector& mobility_forces) const override {
    const double u = pin_.getOneU(s, MobilizerUIndex(0));
    pin_.applyOneMobilityForce(s, MobilizerUIndex(0), -drag_ * u * std::abs(u), mobility_forces);
  }
  Real calcPotentialEnergy(const State&) const override { return 0; }

 private:
  const MobilizedBody pin_;
  double drag_;
};

class NetworkMeter : public Force::Custom::Implementation {
 public:
  NetworkMeter(const GeneralForceSubsystem& forces, const PlatformSystem& ns, ZIndex& z,
               bool dampers)
      : forces_(forces), ns_(ns), z_(z), dampers_(dampers) {}
  void calcForce(const State&, Vector_<SpatialVec>&, Vector_<Vec3>&, Vector&) const override {}
  Real calcPotentialEnergy(const State&) const override { return 0; }
  void realizeTopology(State& s) const override {
    z_ = s.allocateZ(forces_.getMySubsystemIndex(), Vector(dampers_ ? 3 : 2, 0.0));
  }
  void realizeAcceleration(const State& s) const override {
    const network::NetworkEquations& eq = ns_.equations();
    double damping = 0.0, friction = 0.0, dampers = 0.0;
    for (int j = 0; j < ns_.numPendulums(); ++j) {
      const double w = ns_.thetadot(s, j);
      damping += eq.pendulum(j).damping * w * w;             // nu-bar L^2 thetadot^2
      damping += eq.pendulum(j).drag * std::abs(w) * w * w;  // d |thetadot|^3 (air drag)
    }
    for (int p = 0; p < ns_.numPlatforms(); ++p) {
      const network::Block& b = eq.block(p);
      if (!b.moves) continue;
      const PlatformMode m = ns_.contact(p) ? ns_.contact(p)->mode(s) : PlatformMode::Stuck;
      friction += b.friction.power(ns_.slipVelocity(s, p), m);
      const double v = ns_.xdot(s, p);
      dampers += b.c * v * v;
    }
    for (const Coupling& k : ns_.network().couplings) {
      const double u = ns_.xdot(s, k.a) - ns_.xdot(s, k.b);
      dampers += k.c_Ns_m * u * u;
    }
    Vector& zdot = s.updZDot(forces_.getMySubsystemIndex());
    zdot[z_] = damping;
    zdot[z_ + 1] = friction;
    if (dampers_) zdot[z_ + 2] = dampers;
  }

 private:
  const GeneralForceSubsystem& forces_;
  const PlatformSystem& ns_;
  ZIndex& z_;
  bool dampers_;
};

}  // namespace

PlatformSystem::PlatformSystem(const Network& net)
    : net_(net), eq_(net_), matter_(system_), forces_(system_) {
  Force::Gravity(forces_, matter_, -YAxis, net_.gravity_m_s2);
  const int np = numPlatforms();
  sliders_.resize(np);
  contacts_.assign(np, nullptr);
  parent_.assign(np, -1);
  pins_.resize(eq_.layout().n);
  owner_.resize(eq_.layout().n);
  std::vector<char> made(np, 0);
  for (int p = 0; p < np; ++p) addPlatform(p, made);
  for (int p = 0; p < np; ++p) addPendulums(p);
  if (needsSprings()) Force::Custom(forces_, new NetworkSprings(*this));
  for (int p = 0; p < np; ++p) has_dampers_ = has_dampers_ || (moves(p) && eq_.block(p).c != 0);
  for (const Coupling& k : net_.couplings) has_dampers_ = has_dampers_ || k.c_Ns_m != 0;
  Force::Custom(forces_, new NetworkMeter(forces_, *this, z_, has_dampers_));
  system_.realizeTopology();
}

// Platform p's slider and its contact's law, after the platform it rests on (a stack is built
// from the bottom; the loader has refused cycles).
void PlatformSystem::addPlatform(int p, std::vector<char>& made) {
  if (made[p]) return;
  made[p] = 1;
  const network::Block& b = eq_.block(p);
  if (!b.moves) return;
  MobilizedBody parent = matter_.Ground();
  if (b.below >= 0 && eq_.block(b.below).moves) {
    addPlatform(b.below, made);
    parent = sliders_[b.below];
    parent_[p] = b.below;
  }
  // the slider carries everything that does not swing: board, boxes, locked pendulums
  const Rig& rig = net_.platforms[p].rig;
  double carried = rig.platform.mass_kg;
  for (const MetronomeSpec& m : rig.metronomes)
    carried += m.box_mass_kg + (m.locked ? m.pendulum_mass_kg : 0.0);
  if (!(carried > 0))
    throw std::invalid_argument("platform " + net_.platforms[p].name + ": mass must be > 0");
  Body::Rigid board(MassProperties(carried, Vec3(0), UnitInertia(1)));
  sliders_[p] = MobilizedBody::Slider(parent, Transform(), board, Transform());
  if (parent_[p] < 0) {  // on Ground: the slider's coordinate is x_p
    if (b.k > 0) Force::MobilityLinearSpring(forces_, sliders_[p], MobilizerQIndex(0), b.k, 0.0);
    if (b.c > 0) Force::MobilityLinearDamper(forces_, sliders_[p], MobilizerUIndex(0), b.c);
  }
  if (b.friction.setValued()) {
    auto* element = new CoulombContact(forces_, sliders_[p], b.friction);
    Force::Custom(forces_, element);  // takes ownership
    contacts_[p] = element;
  } else if (b.friction.exertsForce()) {
    Force::Custom(forces_, new SmoothFrictionElement(sliders_[p], b.friction));
  }
}

void PlatformSystem::addPendulums(int p) {
  const network::Block& b = eq_.block(p);
  MobilizedBody parent = matter_.Ground();
  if (b.moves) parent = sliders_[p];
  for (int j = b.first; j < b.first + b.count; ++j) {
    const network::PendulumConstants& q = eq_.pendulum(j);
    const int i = q.rig_index - net_.firstMetronome(p);  // its index on the platform
    const MetronomeSpec& m = net_.platforms[p].rig.metronomes[i];
    const double mass = m.pendulum_mass_kg, L = m.length_m, I = m.inertia_kgm2;
    // inertia about the pivot: I about z (the pin axis); the other two moments chosen so that
    // the central inertia (I - m L^2 on every axis) is valid for a point pendulum too
    const double d = I - mass * L * L;
    Body::Rigid bob(MassProperties(mass, Vec3(0, -L, 0), Inertia(I, d, I)));
    // pivots spaced along the board; the spacing does not enter e1.1 (constants c_i)
    const Vec3 pivot(0.1 * static_cast<double>(i), 0, 0);
    owner_[j] = p;
    pins_[j] = MobilizedBody::Pin(parent, Transform(pivot), bob, Transform());
    if (q.damping > 0)
      Force::MobilityLinearDamper(forces_, pins_[j], MobilizerUIndex(0), q.damping);
    if (q.drag > 0) Force::Custom(forces_, new AirDrag(pins_[j], q.drag));
  }
}

bool PlatformSystem::needsSprings() const {
  if (!net_.couplings.empty()) return true;
  for (int p = 0; p < numPlatforms(); ++p)
    if (moves(p) && !onGround(p) && (eq_.block(p).k != 0 || eq_.block(p).c != 0)) return true;
  return false;
}

double PlatformSystem::x(const State& s, int p) const {
  if (!moves(p)) return 0.0;
  const double q = sliders_[p].getOneQ(s, MobilizerQIndex(0));
  return parent_[p] >= 0 ? q + x(s, parent_[p]) : q;
}

double PlatformSystem::xdot(const State& s, int p) const {
  if (!moves(p)) return 0.0;
  const double u = sliders_[p].getOneU(s, MobilizerUIndex(0));
  return parent_[p] >= 0 ? u + xdot(s, parent_[p]) : u;
}

double PlatformSystem::slipVelocity(const State& s, int p) const {
  return moves(p) ? sliders_[p].getOneU(s, MobilizerUIndex(0)) : 0.0;
}

double PlatformSystem::theta(const State& s, int j) const {
  return pins_[j].getOneQ(s, MobilizerQIndex(0));
}

double PlatformSystem::thetadot(const State& s, int j) const {
  return pins_[j].getOneU(s, MobilizerUIndex(0));
}

double PlatformSystem::dampingLoss(const State& s) const {
  return s.getZ(forces_.getMySubsystemIndex())[z_];
}
double PlatformSystem::frictionLoss(const State& s) const {
  return s.getZ(forces_.getMySubsystemIndex())[z_ + 1];
}
double PlatformSystem::damperLoss(const State& s) const {
  return has_dampers_ ? s.getZ(forces_.getMySubsystemIndex())[z_ + 2] : 0.0;
}

void PlatformSystem::layoutState(const State& s, std::vector<double>& y) const {
  const network::Layout& lay = eq_.layout();
  y.assign(lay.dim(), 0.0);
  for (int p = 0; p < lay.platforms; ++p) {
    y[lay.x(p)] = x(s, p);
    y[lay.v(p)] = xdot(s, p);
  }
  for (int j = 0; j < lay.n; ++j) {
    y[lay.theta(j)] = theta(s, j);
    y[lay.omega(j)] = thetadot(s, j);
  }
  y[lay.dampingWork()] = dampingLoss(s);
  y[lay.frictionWork()] = frictionLoss(s);
  if (lay.dampers) y[lay.damperWork()] = damperLoss(s);
}

State PlatformSystem::initialState() {
  State s = system_.getDefaultState();
  for (int p = 0; p < numPlatforms(); ++p) {
    if (!moves(p)) continue;
    const PlatformSpec& ps = net_.platforms[p].rig.platform;
    const int below = parent_[p];
    const PlatformSpec* bs = below >= 0 ? &net_.platforms[below].rig.platform : nullptr;
    // the slider's coordinate is relative to the platform below: the rig's starts are absolute
    sliders_[p].setOneQ(s, MobilizerQIndex(0), ps.start_x_m - (bs ? bs->start_x_m : 0.0));
    sliders_[p].setOneU(s, MobilizerUIndex(0), ps.start_v_m_s - (bs ? bs->start_v_m_s : 0.0));
  }
  for (int j = 0; j < numPendulums(); ++j) {
    const network::PendulumConstants& q = eq_.pendulum(j);
    const int p = owner_[j];
    const MetronomeSpec& m = net_.platforms[p].rig.metronomes[q.rig_index - net_.firstMetronome(p)];
    pins_[j].setOneQ(s, MobilizerQIndex(0), m.start_angle_rad);
    pins_[j].setOneU(s, MobilizerUIndex(0), m.start_rate_rad_s);
  }
  system_.realize(s, Stage::Velocity);
  return s;
}

}  // namespace metrosync
