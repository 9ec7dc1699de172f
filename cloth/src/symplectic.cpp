// Symplectic (semi-implicit) Euler: velocities from the forces, then positions from the velocities.
#include "dresskit/cloth/simulator.h"

namespace dresskit::cloth {

void ClothSimulator::step_symplectic(StepResult&) {
  const Eigen::MatrixX3d f = forces();
  for (int i = 0; i < x_.rows(); ++i) {
    if (pinned_[i]) continue;
    v_.row(i) += dt_ / model_.mass(i) * f.row(i);
    x_.row(i) += dt_ * v_.row(i);
  }
}

}  // namespace dresskit::cloth
