// libFuzzer target: sw::read_backlash_result (backlash.json written by `strainwave backlash`) on arbitrary bytes. What
// reads must be written and read again to the same text (the reader and the writer share one field table).
#include <cstddef>
#include <cstdint>

#include "bench/fuzz/fuzz_file.hpp"
#include "common/error.hpp"
#include "io/backlash_output.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = sw::fuzz::write_input(data, size, "backlash.json");
  sw::fuzz::expect_written_back(path, sw::read_backlash_result, sw::backlash_json);
  return 0;
}
