// libFuzzer target: sw::read_neutral_curve_csv (neutral_curve.csv written by `strainwave fem`) on arbitrary bytes.
#include <cstddef>
#include <cstdint>

#include "bench/fuzz/fuzz_file.hpp"
#include "common/error.hpp"
#include "io/fem_output.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = sw::fuzz::write_input(data, size, "neutral_curve.csv");
  try {
    (void)sw::read_neutral_curve_csv(path);
  } catch (const sw::InputError&) {
  }
  return 0;
}
