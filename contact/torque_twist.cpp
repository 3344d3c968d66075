#include "contact/torque_twist.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace sw {

double twist_at(const TorqueTwist& c, double T) {
  const auto& t = c.torque_Nm;
  if (t.empty() || T < t.front() - 1e-12 * std::abs(t.front()) || T > t.back() + 1e-12 * std::abs(t.back()))
    throw std::out_of_range("twist_at: torque outside the curve");
  if (T == 0) {  // the mean of the limits from both sides
    double lo = 0, hi = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] <= 0) lo = c.twist_rad[i];
      if (t[t.size() - 1 - i] >= 0) hi = c.twist_rad[t.size() - 1 - i];
    }
    return 0.5 * (lo + hi);
  }
  // The segment [i, i+1] holding T, excluding the zero-width jump at T = 0.
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    if (t[i + 1] == t[i]) continue;
    if (T >= t[i] && T <= t[i + 1]) {
      const double s = (T - t[i]) / (t[i + 1] - t[i]);
      return c.twist_rad[i] + s * (c.twist_rad[i + 1] - c.twist_rad[i]);
    }
  }
  return T < 0 ? c.twist_rad.front() : c.twist_rad.back();
}

double lost_motion_rad(const TorqueTwist& c, double T_R, double fraction) {
  return twist_at(c, fraction * T_R) - twist_at(c, -fraction * T_R);
}

double SegmentLaw::twist_rad(double T) const {
  const double m = std::abs(T);
  const double a = std::min(m, t1_Nm), b = std::clamp(m - t1_Nm, 0.0, t2_Nm - t1_Nm), d = std::max(0.0, m - t2_Nm);
  return std::copysign(a / k1_Nm_per_rad + b / k2_Nm_per_rad + d / k3_Nm_per_rad, T);
}

namespace {
double odd(const TorqueTwist& c, double T) { return 0.5 * (twist_at(c, T) - twist_at(c, -T)); }
}  // namespace

SegmentLaw segment_law(const TorqueTwist& c, double t1, double t2, double T_R) {
  if (!(0 < t1 && t1 < t2 && t2 < T_R)) throw std::invalid_argument("segment_law: need 0 < T1 < T2 < T_R");
  SegmentLaw s;
  s.t1_Nm = t1;
  s.t2_Nm = t2;
  const double p1 = odd(c, t1), p2 = odd(c, t2), pr = odd(c, T_R);
  s.k1_Nm_per_rad = t1 / p1;
  s.k2_Nm_per_rad = (t2 - t1) / (p2 - p1);
  s.k3_Nm_per_rad = (T_R - t2) / (pr - p2);
  return s;
}

SegmentLaw fitted_segment_law(const TorqueTwist& c, double T_R) {
  constexpr int kGrid = 200, kSamples = 100;
  std::vector<double> T(kSamples), phi(kSamples);
  for (int k = 0; k < kSamples; ++k) {
    T[k] = T_R * (k + 1) / kSamples;
    phi[k] = odd(c, T[k]);
  }
  SegmentLaw best;
  double best_err = std::numeric_limits<double>::infinity();
  for (int i = 1; i < kGrid - 1; ++i)
    for (int j = i + 1; j < kGrid; ++j) {
      const SegmentLaw s = segment_law(c, T_R * i / kGrid, T_R * j / kGrid, T_R);
      if (!(s.k1_Nm_per_rad > 0 && s.k2_Nm_per_rad > 0 && s.k3_Nm_per_rad > 0)) continue;
      double err = 0;
      for (int k = 0; k < kSamples; ++k) err += std::pow(s.twist_rad(T[k]) - phi[k], 2);
      if (err < best_err) {
        best_err = err;
        best = s;
      }
    }
  best.breakpoints_fitted = true;
  return best;
}

}  // namespace sw
