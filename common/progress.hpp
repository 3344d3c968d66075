#pragma once
// Progress lines on stderr ("[  1.23 s] phase: detail"), silenced by --quiet; wall-clock timing of phases.
#include <chrono>
#include <cstdio>
#include <string>

namespace sw {

/// Global switch set once by the CLI (--quiet).
inline bool& quiet_progress() {
  static bool quiet = false;
  return quiet;
}

/// Seconds since the first call in this process.
inline double elapsed_s() {
  static const auto start = std::chrono::steady_clock::now();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Prints "[  t s] message" on stderr unless quiet.
inline void progress(const std::string& message) {
  if (!quiet_progress()) std::fprintf(stderr, "[%7.2f s] %s\n", elapsed_s(), message.c_str());
}

/// Stopwatch: seconds since construction or the last lap().
class Stopwatch {
public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }
private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace sw
