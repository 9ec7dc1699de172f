#include "dresskit/testing/data.h"

#include <cstdlib>

namespace dresskit::testing {

std::string data_dir() {
  const char* env = std::getenv("DRESSKIT_DATA_DIR");
  return env && *env ? env : DRESSKIT_DEFAULT_DATA_DIR;
}

bool in_ci() {
  const char* ci = std::getenv("CI");
  return ci && std::string(ci) == "true";
}

}  // namespace dresskit::testing
