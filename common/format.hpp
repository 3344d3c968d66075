#pragma once
// Numbers in the tool's messages.
#include <cstdio>
#include <string>

namespace sw {

/// v with six significant digits, as printf's %g: 0.3, 1.5e-05, 1234.57.
inline std::string six_digits(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// v formatted by one printf conversion (e.g. "%.3g"), for messages.
inline std::string formatted(const char* printf_format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, v);
  return buf;
}

}  // namespace sw
