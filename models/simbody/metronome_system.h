// The full model (e1.1a-c) assembled as a Simbody MultibodySystem, with only what the rig needs:
//   Ground -> Slider (platform + boxes + locked pendulums; absent for a fixed platform)
//          -> Pin per swinging pendulum (mass m_i, centre of mass at L_i below the pivot,
//             inertia I_i about the pivot), gravity -g y,
//   a pivot damper (torque -nu-bar L^2 thetadot) only where nu-bar > 0,
//   the platform law (platformFriction(rig), models/minimal_equations.h): CoulombElement for the
//   set-valued Coulomb law, SmoothFrictionElement for a smooth law (viscous), nothing (none),
//   a platform spring only when the rig has one,
//   and a DissipationMeter integrating the damping and friction power for the energy ledger.
#pragma once

#include <Simbody.h>

#include <memory>
#include <vector>

#include "contact/platform_friction.h"
#include "contact/simbody/coulomb_element.h"
#include "models/rig.h"

namespace metrosync {

// Integrates, as two continuous state variables z, the power taken out by the pivot dampers and
// by platform friction (joules); read with dampingLoss()/frictionLoss().
class DissipationMeter : public SimTK::Force::Custom::Implementation {
 public:
  DissipationMeter(const SimTK::GeneralForceSubsystem& forces,
                   std::vector<std::pair<SimTK::MobilizedBody, double>> dampers,
                   const SimTK::MobilizedBody* slider, const CoulombElement* coulomb,
                   PlatformFriction friction)
      : forces_(forces),
        dampers_(std::move(dampers)),
        slider_(slider),
        coulomb_(coulomb),
        friction_(friction) {}

  double dampingLoss(const SimTK::State& s) const;
  double frictionLoss(const SimTK::State& s) const;

  void calcForce(const SimTK::State&, SimTK::Vector_<SimTK::SpatialVec>&,
                 SimTK::Vector_<SimTK::Vec3>&, SimTK::Vector&) const override {}
  SimTK::Real calcPotentialEnergy(const SimTK::State&) const override { return 0; }
  void realizeTopology(SimTK::State& s) const override;
  void realizeAcceleration(const SimTK::State& s) const override;

 private:
  const SimTK::GeneralForceSubsystem& forces_;
  std::vector<std::pair<SimTK::MobilizedBody, double>> dampers_;  // (pin, nu-bar L^2)
  const SimTK::MobilizedBody* slider_;
  const CoulombElement* coulomb_;
  PlatformFriction friction_;
  mutable SimTK::ZIndex z_;
};

class MetronomeSystem {
 public:
  explicit MetronomeSystem(const Rig& rig);
  MetronomeSystem(const MetronomeSystem&) = delete;
  MetronomeSystem& operator=(const MetronomeSystem&) = delete;

  const Rig& rig() const { return rig_; }
  bool hasPlatform() const { return has_platform_; }
  int numMetronomes() const { return static_cast<int>(rig_.metronomes.size()); }
  // Pin of metronome i; only valid when !rig().metronomes[i].locked.
  const SimTK::MobilizedBody::Pin& pin(int i) const { return pins_[i]; }
  bool swings(int i) const { return !rig_.metronomes[i].locked; }
  const SimTK::MobilizedBody::Slider& slider() const { return slider_; }
  // the set-valued law's element (friction().setValued() only), else nullptr
  const CoulombElement* coulomb() const { return coulomb_; }
  // the platform's law at its normal force (models/minimal_equations.h); Fixed without a platform
  const PlatformFriction& friction() const { return platform_friction_; }
  const DissipationMeter& meter() const { return *meter_; }

  SimTK::MultibodySystem& system() { return system_; }
  const SimTK::MultibodySystem& system() const { return system_; }
  const SimTK::SimbodyMatterSubsystem& matter() const { return matter_; }

  // Platform position/velocity and pendulum angle/rate (SI); 0 where absent.
  double x(const SimTK::State& s) const;
  double xdot(const SimTK::State& s) const;
  double theta(const SimTK::State& s, int i) const;
  double thetadot(const SimTK::State& s, int i) const;
  void setXDot(SimTK::State& s, double v) const;

  // The start state of the rig, realized to Velocity (friction mode not yet decided).
  SimTK::State initialState();

 private:
  Rig rig_;
  SimTK::MultibodySystem system_;
  SimTK::SimbodyMatterSubsystem matter_;
  SimTK::GeneralForceSubsystem forces_;
  bool has_platform_ = false;
  PlatformFriction platform_friction_;
  SimTK::MobilizedBody::Slider slider_;
  std::vector<SimTK::MobilizedBody::Pin> pins_;
  const CoulombElement* coulomb_ = nullptr;
  const DissipationMeter* meter_ = nullptr;
};

}  // namespace metrosync
