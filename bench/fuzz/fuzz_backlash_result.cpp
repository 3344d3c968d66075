// libFuzzer target: sw::read_backlash_result (backlash.json written by `strainwave backlash`) on arbitrary bytes. What
// reads must be written and read again to the same text (the reader and the writer share one field table).
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "bench/fuzz/fuzz_file.hpp"
#include "common/error.hpp"
#include "io/backlash_output.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = sw::fuzz::write_input(data, size, "backlash.json");
  try {
    const std::string text = sw::backlash_json(sw::read_backlash_result(path));
    const auto again = sw::fuzz::write_input(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), "again.json");
    if (sw::backlash_json(sw::read_backlash_result(again)) != text) std::abort();
  } catch (const sw::InputError&) {
  }
  return 0;
}
