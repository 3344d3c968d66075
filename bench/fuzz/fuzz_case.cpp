// libFuzzer target: sw::parse_case on arbitrary text. InputError is the documented answer to bad input; any other
// exception escapes and libFuzzer reports it as a crash (uncaught exception -> abort).
#include <cstddef>
#include <cstdint>
#include <string>

#include "common/error.hpp"
#include "io/case.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const sw::Case c = sw::parse_case(text, "fuzz.toml");
    (void)sw::describe_case(c);
  } catch (const sw::InputError&) {
  }
  return 0;
}
