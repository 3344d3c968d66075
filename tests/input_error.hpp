#pragma once
// The one line an InputError says, for the tests of bad input: what `f` throws, or "(no InputError)" when it throws
// nothing (so a test's find() of the expected words fails with something to read).
#include <functional>
#include <string>

#include "common/error.hpp"

namespace sw::testing {

inline std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

}  // namespace sw::testing
