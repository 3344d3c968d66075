#pragma once
// What this process has used so far: the figure result.json, the benches and the PETSc ranks report.
#include <sys/resource.h>

namespace sw {

/// Peak resident set size of this process so far (bytes).
inline long peak_rss_bytes() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss * 1024L;
}

}  // namespace sw
