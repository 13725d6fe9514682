// Simbody's integrators by the names simulation.integrator accepts (simbodyIntegratorNames(),
// sim/engines/simbody/simbody_engine.h), for the one run loop (platform_run.h).
#pragma once

#include <Simbody.h>

#include <memory>
#include <string>

namespace metrosync {

// Throws std::invalid_argument for a name that is not one of simbodyIntegratorNames().
std::unique_ptr<SimTK::Integrator> makeSimbodyIntegrator(const std::string& name,
                                                         const SimTK::System& sys);

}  // namespace metrosync
