#pragma once
// The simulator's options for tests of one integrator's numerics: a fixed step of 1/240 s, no strain
// limiting and no air damping (the defaults add adaptive steps up to 1/120 s, a 10 % strain limit
// and air damping, which a closed-form comparison must not see).
#include "dresskit/cloth/simulator.h"

namespace dresskit::test {

inline cloth::SimulationOptions bare_options(cloth::Integrator integrator) {
  cloth::SimulationOptions o;
  o.integrator = integrator;
  o.dt = 1.0 / 240.0;
  o.adaptive = false;
  o.strain_limiting = false;
  o.air_damping = 0.0;
  return o;
}

}  // namespace dresskit::test
