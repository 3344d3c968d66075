// libFuzzer target: the readers of contact.json (written by `strainwave contact`) on arbitrary bytes:
// sw::read_contact_result, the typed value, and sw::read_contact_curve, the torque-twist loop's middle line that
// reconcile reads (then read at torques across it by sw::twist_at). What reads as a typed value must be written and
// read again to the same text.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

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
  try {
    const std::string text = sw::contact_json(sw::read_contact_result(path));
    const auto again = sw::fuzz::write_input(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), "again.json");
    if (sw::contact_json(sw::read_contact_result(again)) != text) std::abort();
  } catch (const sw::InputError&) {
  }
  return 0;
}
