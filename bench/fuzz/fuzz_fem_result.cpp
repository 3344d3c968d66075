// libFuzzer target: sw::read_fem_compensation (result.json written by `strainwave fem`) on arbitrary bytes.
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
  return 0;
}
