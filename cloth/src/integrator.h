#pragma once
// The time integrators behind one interface. Each advances the cloth over one step in its own file
// (symplectic.cpp, implicit.cpp, newton.cpp, projective.cpp) with its own options
// (SimulationOptions::linear, ::newton, ::projective) and keeps its own state from step to step
// (the implicit system's pattern, projective dynamics' factorisations and BDF2's history);
// ClothSimulator::try_step runs the constraints, sewing and collisions after it.
#include <memory>

#include "dresskit/cloth/simulator.h"

namespace dresskit::cloth {

class TimeIntegrator {
 public:
  virtual ~TimeIntegrator() = default;
  /// Moves the simulator's positions and velocities over its current step (dt_) under the forces;
  /// on failure sets r.ok = false and says why in r.failure.
  virtual void step(ClothSimulator& sim, StepResult& r) = 0;
  /// The state was set from outside (ClothSimulator::set_state): nothing may reach back past it.
  virtual void restart() {}
};

std::unique_ptr<TimeIntegrator> make_symplectic_euler();
std::unique_ptr<TimeIntegrator> make_implicit_euler();
std::unique_ptr<TimeIntegrator> make_newton();
std::unique_ptr<TimeIntegrator> make_projective();

}  // namespace dresskit::cloth
