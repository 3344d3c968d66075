// libFuzzer target: sw::reconcile::parse_recording on arbitrary text, then the accessors a caller uses on the result
// and format_recording(), whose output must parse again. InputError is the documented answer to bad input.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "common/error.hpp"
#include "reconcile/recording.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  sw::reconcile::Recording r;
  try {
    r = sw::reconcile::parse_recording(text, "fuzz.csv");
  } catch (const sw::InputError&) {
    return 0;
  }
  for (const auto& name : r.columns)
    if (r.column(name) == nullptr || r.column(name)->size() != r.rows()) std::abort();
  for (const auto& [key, value] : r.metadata) {
    try {
      (void)r.meta_number(key);
    } catch (const sw::InputError&) {
    }
  }
  // What was accepted once must be accepted again after writing it out.
  (void)sw::reconcile::parse_recording(sw::reconcile::format_recording(r), "fuzz_roundtrip.csv");
  return 0;
}
