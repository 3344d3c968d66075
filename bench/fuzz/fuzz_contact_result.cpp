// libFuzzer target: the readers of contact.json (written by `strainwave contact`) on arbitrary bytes:
// sw::read_contact_result, the typed value, and sw::read_contact_curve, the torque-twist loop's middle line that
// reconcile reads (then read at torques across it by sw::twist_at). What reads as a typed value must be written and
// read again to the same text.
#include <cstddef>
#include <cstdint>

#include "bench/fuzz/fuzz_file.hpp"
#include "common/error.hpp"
#include "contact/torque_twist.hpp"
#include "io/contact_output.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = sw::fuzz::write_input(data, size, "contact.json");
  try {
    const sw::ContactCurve c = sw::read_contact_curve(path);
    const auto& t = c.middle_line.torque_Nm;
    for (int k = 0; k <= 8; ++k) (void)sw::twist_at(c.middle_line, t.front() + (t.back() - t.front()) * k / 8);
  } catch (const sw::InputError&) {
  }
  sw::fuzz::expect_written_back(path, sw::read_contact_result, sw::contact_json);
  return 0;
}
