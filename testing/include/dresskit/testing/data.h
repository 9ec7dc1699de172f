#pragma once
// Where the real test data lives: DRESSKIT_DATA_DIR, else ../shared/data beside the project.
#include <string>

namespace dresskit::testing {

std::string data_dir();
/// CI=true in the environment (a missing data folder is then a failure, not a skip).
bool in_ci();

}  // namespace dresskit::testing
