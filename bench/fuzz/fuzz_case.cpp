// libFuzzer target: sw::parse_case on arbitrary text. InputError is the documented answer to bad input; any other
// exception escapes and libFuzzer reports it as a crash (uncaught exception -> abort). What parses must be written
// (describe_case, the resolved case the outputs store) and read again without an error, and the written text must
// settle: the second writing equals the third (the first may differ from it in a comment on where a value came from,
// and in a default derived in SI that the written decimal reaches to 1 ulp).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "common/error.hpp"
#include "io/case.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sw::Case c;
  try {
    c = sw::parse_case(text, "fuzz.toml");
  } catch (const sw::InputError&) {
    return 0;
  }
  const std::string first = sw::describe_case(c);
  const std::string second = sw::describe_case(sw::parse_case(first, "written.toml"));  // must not throw
  const std::string third = sw::describe_case(sw::parse_case(second, "written.toml"));
  if (second != third) std::abort();
  return 0;
}
