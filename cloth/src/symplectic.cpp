// Symplectic (semi-implicit) Euler: velocities from the forces, then positions from the velocities.
#include "integrator.h"

namespace dresskit::cloth {

class SymplecticEuler final : public TimeIntegrator {
 public:
  void step(ClothSimulator& sim, StepResult&) override {
    const Eigen::MatrixX3d f = sim.forces();
    for (int i = 0; i < sim.x_.rows(); ++i) {
      if (sim.pinned_[i]) continue;
      sim.v_.row(i) += sim.dt_ / sim.model_.mass(i) * f.row(i);
      sim.x_.row(i) += sim.dt_ * sim.v_.row(i);
    }
  }
};

std::unique_ptr<TimeIntegrator> make_symplectic_euler() { return std::make_unique<SymplecticEuler>(); }

}  // namespace dresskit::cloth
