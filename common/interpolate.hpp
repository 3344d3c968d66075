#pragma once
// A table read piecewise-linearly between its points and held at its end values beyond them.
#include <algorithm>
#include <cstddef>
#include <vector>

namespace sw {

/// y at x on the polyline through (xs[k], ys[k]), xs increasing (one entry or more, ys as many); beyond the first or
/// last x, the first or last y.
inline double interpolate_clamped(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  const auto hi = std::upper_bound(xs.begin(), xs.end(), x);
  if (hi == xs.begin()) return ys.front();
  if (hi == xs.end()) return ys.back();
  const std::size_t k = static_cast<std::size_t>(hi - xs.begin());
  const double t = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
  return ys[k - 1] + t * (ys[k] - ys[k - 1]);
}

}  // namespace sw
