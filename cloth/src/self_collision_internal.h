#pragma once
// Shared by the cloth–cloth collision pass (self_collision.cpp) and the crossing counts
// (crossings.cpp).
#include <vector>

namespace dresskit::cloth::detail {

/// Representatives of particles joined as one (seams): the given ones, or each particle its own.
std::vector<int> representatives(std::vector<int> joined, int particles);

}  // namespace dresskit::cloth::detail
