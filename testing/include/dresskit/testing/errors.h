#pragma once
// Tests of bad input: the message a call refuses it with.
#include <functional>
#include <string>

#include "dresskit/mesh/errors.h"

namespace dresskit::test {

/// What the InputError thrown by f says, or "no error" when f returns.
inline std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace dresskit::test
