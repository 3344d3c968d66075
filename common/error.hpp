#pragma once
// The one exception type for bad input (case files, recordings, meshing requests, singular systems).
// Its message is a single line: where (file / field), the value, the constraint, and the fix.
#include <stdexcept>
#include <string>

namespace sw {

class InputError : public std::runtime_error {
public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

/// Calls f(); an InputError it throws gets "`file`: " in front. A stage takes its own input, not the case file, and
/// says what is wrong; the caller that read the file completes the message with it.
template <class F>
decltype(auto) naming_file(const std::string& file, F&& f) {
  try {
    return f();
  } catch (const InputError& e) {
    throw InputError(file + ": " + e.what());
  }
}

}  // namespace sw
