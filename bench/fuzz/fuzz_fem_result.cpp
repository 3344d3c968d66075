// libFuzzer target: the readers of result.json (written by `strainwave fem`) on arbitrary bytes: sw::read_fem_result,
// the typed value, and sw::read_fem_compensation. What reads as a typed value must be written and read again to the
// same text (the reader and the writer share one field table).
#include <cstddef>
#include <cstdint>

#include "bench/fuzz/fuzz_file.hpp"
#include "common/error.hpp"
#include "io/fem_output.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = sw::fuzz::write_input(data, size, "result.json");
  try {
    (void)sw::read_fem_compensation(path);
  } catch (const sw::InputError&) {
  }
  sw::fuzz::expect_written_back(path, sw::read_fem_result, sw::fem_result_json);
  return 0;
}
