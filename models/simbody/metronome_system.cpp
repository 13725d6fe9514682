#include "models/simbody/metronome_system.h"

#include <stdexcept>

#include "contact/simbody/smooth_friction_element.h"
#include "models/minimal_equations.h"

namespace metrosync {

using namespace SimTK;

void DissipationMeter::realizeTopology(State& s) const {
  z_ = s.allocateZ(forces_.getMySubsystemIndex(), Vector(2, 0.0));
}

double DissipationMeter::dampingLoss(const State& s) const {
  return s.getZ(forces_.getMySubsystemIndex())[z_];
}

double DissipationMeter::frictionLoss(const State& s) const {
  return s.getZ(forces_.getMySubsystemIndex())[z_ + 1];
}

void DissipationMeter::realizeAcceleration(const State& s) const {
  // damping power: sum of nu-bar L^2 thetadot^2 over the pivots
  double damping = 0.0;
  for (const auto& [pin, c] : dampers_) {
    const double w = pin.getOneU(s, MobilizerUIndex(0));
    damping += c * w * w;
  }
  // friction power, the law's (bound*|xdot| while slipping, c xdot^2 viscous)
  double friction = 0.0;
  if (slider_) {
    const double v = slider_->getOneU(s, MobilizerUIndex(0));
    const PlatformMode m = coulomb_ ? coulomb_->mode(s) : PlatformMode::Stuck;
    friction = friction_.power(v, m);
  }
  Vector& zdot = s.updZDot(forces_.getMySubsystemIndex());
  zdot[z_] = damping;
  zdot[z_ + 1] = friction;
}

MetronomeSystem::MetronomeSystem(const Rig& rig) : rig_(rig), matter_(system_), forces_(system_) {
  const double g = rig_.gravity_m_s2;
  Force::Gravity(forces_, matter_, -YAxis, g);

  const PlatformFriction friction = platformFriction(rig_);
  platform_friction_ = friction;
  has_platform_ = friction.platformMoves();
  MobilizedBody parent = matter_.Ground();
  if (has_platform_) {
    // the slider carries everything that does not swing: board, boxes, locked pendulums
    double carried = rig_.platform.mass_kg;
    for (const auto& m : rig_.metronomes)
      carried += m.box_mass_kg + (m.locked ? m.pendulum_mass_kg : 0.0);
    if (!(carried > 0)) throw std::invalid_argument("platform mass must be > 0");
    Body::Rigid board(MassProperties(carried, Vec3(0), UnitInertia(1)));
    slider_ = MobilizedBody::Slider(matter_.Ground(), Transform(), board, Transform());
    parent = slider_;
    if (rig_.platform.spring_N_m > 0)
      Force::MobilityLinearSpring(forces_, slider_, MobilizerQIndex(0), rig_.platform.spring_N_m,
                                  0.0);
    if (friction.setValued()) {
      auto* element = new CoulombElement(forces_, slider_, friction.dry);
      Force::Custom(forces_, element);  // takes ownership
      coulomb_ = element;
    } else if (friction.kind != PlatformFriction::Kind::None) {
      Force::Custom(forces_, new SmoothFrictionElement(slider_, friction));
    }
  }

  pins_.resize(rig_.metronomes.size());
  std::vector<std::pair<MobilizedBody, double>> dampers;
  for (size_t i = 0; i < rig_.metronomes.size(); ++i) {
    const MetronomeSpec& m = rig_.metronomes[i];
    if (m.locked) continue;
    const double mass = m.pendulum_mass_kg, L = m.length_m, I = m.inertia_kgm2;
    // inertia about the pivot: I about z (the pin axis); the other two moments chosen so that
    // the central inertia (I - m L^2 on every axis) is valid for a point pendulum too
    const double d = I - mass * L * L;
    Body::Rigid bob(MassProperties(mass, Vec3(0, -L, 0), Inertia(I, d, I)));
    // pivots spaced along the board; the spacing does not enter e1.1 (constants c_i)
    const Vec3 pivot(0.1 * static_cast<double>(i), 0, 0);
    pins_[i] = MobilizedBody::Pin(parent, Transform(pivot), bob, Transform());
    const double c = m.damping_kg_s * L * L;  // torque -nu-bar L^2 thetadot (e1.1a)
    if (c > 0) {
      Force::MobilityLinearDamper(forces_, pins_[i], MobilizerUIndex(0), c);
      dampers.emplace_back(pins_[i], c);
    }
  }

  auto* meter = new DissipationMeter(forces_, std::move(dampers),
                                     has_platform_ ? &slider_ : nullptr, coulomb_, friction);
  Force::Custom(forces_, meter);
  meter_ = meter;
  system_.realizeTopology();
}

double MetronomeSystem::x(const State& s) const {
  return has_platform_ ? slider_.getOneQ(s, MobilizerQIndex(0)) : 0.0;
}
double MetronomeSystem::xdot(const State& s) const {
  return has_platform_ ? slider_.getOneU(s, MobilizerUIndex(0)) : 0.0;
}
double MetronomeSystem::theta(const State& s, int i) const {
  return swings(i) ? pins_[i].getOneQ(s, MobilizerQIndex(0)) : 0.0;
}
double MetronomeSystem::thetadot(const State& s, int i) const {
  return swings(i) ? pins_[i].getOneU(s, MobilizerUIndex(0)) : 0.0;
}
void MetronomeSystem::setXDot(State& s, double v) const {
  if (has_platform_) slider_.setOneU(s, MobilizerUIndex(0), v);
}

State MetronomeSystem::initialState() {
  State s = system_.getDefaultState();
  if (has_platform_) {
    slider_.setOneQ(s, MobilizerQIndex(0), rig_.platform.start_x_m);
    slider_.setOneU(s, MobilizerUIndex(0), rig_.platform.start_v_m_s);
  }
  for (size_t i = 0; i < rig_.metronomes.size(); ++i) {
    if (!swings(static_cast<int>(i))) continue;
    pins_[i].setOneQ(s, MobilizerQIndex(0), rig_.metronomes[i].start_angle_rad);
    pins_[i].setOneU(s, MobilizerUIndex(0), rig_.metronomes[i].start_rate_rad_s);
  }
  system_.realize(s, Stage::Velocity);
  return s;
}

}  // namespace metrosync
