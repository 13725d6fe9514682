#include "sim/engines/simbody/integrators.h"

#include <stdexcept>

namespace metrosync {

using namespace SimTK;

std::unique_ptr<Integrator> makeSimbodyIntegrator(const std::string& name, const System& sys) {
  if (name == "rk-merson") return std::make_unique<RungeKuttaMersonIntegrator>(sys);
  if (name == "rk-feldberg") return std::make_unique<RungeKuttaFeldbergIntegrator>(sys);
  if (name == "rk3") return std::make_unique<RungeKutta3Integrator>(sys);
  if (name == "rk2") return std::make_unique<RungeKutta2Integrator>(sys);
  if (name == "cpodes")
    return std::make_unique<CPodesIntegrator>(sys, CPodes::Adams, CPodes::Functional);
  if (name == "verlet") return std::make_unique<VerletIntegrator>(sys);
  if (name == "semi-explicit-euler2") return std::make_unique<SemiExplicitEuler2Integrator>(sys);
  throw std::invalid_argument("unknown integrator '" + name + "'");
}

}  // namespace metrosync
