#pragma once
// Where a limit is first reached along a load: the limit searches of the datasheet (first yield, infinite life,
// ratcheting) each look for the smallest torque at which a predicate turns true.
#include <utility>

namespace sw {

/// The bracket (last torque that holds, first that fails) of the first torque in (from, to] at which `fails` turns
/// true, given that it holds at `from` and fails at `to`: first a scan of `scan_steps` equal steps for the first
/// failing one (the predicate need not be monotonic in the torque; 0: no scan), then bisection to hi − lo ≤ tol·hi.
template <class Fails>
std::pair<double, double> first_crossing(double from, double to, int scan_steps, double tol, const Fails& fails) {
  double lo = from, hi = to;
  for (int k = 1; k < scan_steps; ++k) {
    const double T = from + (to - from) * k / scan_steps;
    if (fails(T)) {
      hi = T;
      break;
    }
    lo = T;
  }
  while (hi - lo > tol * hi) {
    const double mid = 0.5 * (lo + hi);
    (fails(mid) ? hi : lo) = mid;
  }
  return {lo, hi};
}

}  // namespace sw
