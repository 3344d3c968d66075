#include "contact/torque_twist.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/error.hpp"
#include "common/format.hpp"

namespace sw {
namespace {

/// The analysis samples its curve at T_R·s/N: the ends may differ from ±T_R by rounding. The curve's own readings at
/// ±T_R (the segment law) pass an end by this fraction of the end torque, along the end segment.
constexpr double kEndRounding = 1e-12;

/// Twist along segment (k, k + 1) at torque T.
double along(const TorqueTwist& c, std::size_t k, double T) {
  const auto& t = c.torque_Nm;
  const double s = (T - t[k]) / (t[k + 1] - t[k]);
  return c.twist_rad[k] + s * (c.twist_rad[k + 1] - c.twist_rad[k]);
}

}  // namespace

std::pair<double, double> twist_limits(const TorqueTwist& c, double T) {
  const auto& t = c.torque_Nm;
  const std::size_t i = std::lower_bound(t.begin(), t.end(), T) - t.begin();
  const std::size_t j = std::upper_bound(t.begin(), t.end(), T) - t.begin();
  if (j - i >= 2) return {c.twist_rad[i], c.twist_rad[j - 1]};  // a vertical step at T
  const double v = along(c, std::max<std::size_t>(i, 1) - 1, T);  // the first segment with a torque step holding T
  return {v, v};
}

double twist_at(const TorqueTwist& c, double T, double end_tolerance_Nm) {
  const auto& t = c.torque_Nm;
  assert(t.size() >= 2 && t.size() == c.twist_rad.size() && t.front() < t.back());
  if (!(T >= t.front() - end_tolerance_Nm && T <= t.back() + end_tolerance_Nm))
    throw InputError("torque " + six_digits(T) + " N*m is beyond the torque-twist curve, which covers [" + six_digits(t.front()) +
                     ", " + six_digits(t.back()) + "] N*m; the curve is not extrapolated");
  if (T <= t.front() || T >= t.back()) {
    // At or just beyond an end: the end segment (the first/last with a torque step), extended.
    std::size_t a = 0;
    if (T <= t.front()) {
      while (t[a + 1] == t.front()) ++a;
    } else {
      a = t.size() - 2;
      while (t[a] == t.back()) --a;
    }
    return along(c, a, T);
  }
  const auto [left, right] = twist_limits(c, T);
  return 0.5 * (left + right);
}

bool spans_torque(const TorqueTwist& b) { return b.torque_Nm.size() >= 2 && b.torque_Nm.back() > b.torque_Nm.front(); }

TorqueTwist middle_line(const TorqueTwist& loading, const TorqueTwist& unloading) {
  std::vector<const TorqueTwist*> branches{&loading};
  if (spans_torque(unloading)) branches.push_back(&unloading);
  const double lo = std::max(loading.torque_Nm.front(), branches.back()->torque_Nm.front());
  const double hi = std::min(loading.torque_Nm.back(), branches.back()->torque_Nm.back());
  assert(hi > lo);
  std::vector<double> grid;  // the union of the branches' torques
  for (const TorqueTwist* b : branches)
    for (double x : b->torque_Nm)
      if (x >= lo && x <= hi) grid.push_back(x);
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  TorqueTwist m;
  for (double x : grid) {
    double left = 0.0, right = 0.0;
    for (const TorqueTwist* b : branches) {
      const auto [l, r] = twist_limits(*b, x);
      left += l / branches.size();
      right += r / branches.size();
    }
    // Both limits where the line steps (a dead band crossed at x); at the ends only the side inside the curve.
    if (x > lo || right == left) {
      m.torque_Nm.push_back(x);
      m.twist_rad.push_back(left);
    }
    if (right != left && x < hi) {
      m.torque_Nm.push_back(x);
      m.twist_rad.push_back(right);
    }
  }
  return m;
}

double lost_motion_rad(const TorqueTwist& c, double T_R, double fraction) {
  return twist_at(c, fraction * T_R) - twist_at(c, -fraction * T_R);
}

LoadCycle last_load_cycle(const std::vector<double>& T) {
  if (T.size() < 3) throw std::invalid_argument("last_load_cycle: a cycle needs 3 points or more");
  LoadCycle c;
  c.end = T.size() - 1;
  for (std::size_t k = 0; k < T.size(); ++k)
    if (T[k] <= T[c.bottom]) c.bottom = k;
  for (std::size_t k = 0; k < c.bottom; ++k)
    if (T[k] >= T[c.top]) c.top = k;
  bool monotone = c.top < c.bottom && c.bottom < c.end;
  for (std::size_t k = c.top; k < c.end; ++k)
    monotone = monotone && (k < c.bottom ? T[k + 1] <= T[k] : T[k + 1] >= T[k]);
  if (!monotone)
    throw std::invalid_argument(
        "last_load_cycle: the path does not fall from its last top to its bottom and rise to its end");
  return c;
}

TorqueLoop loop_branches(const std::vector<double>& T, const std::vector<double>& psi, const LoadCycle& c,
                         double zero_torque_Nm) {
  assert(T.size() == psi.size() && c.end < T.size());
  const auto add = [&](TorqueTwist& b, std::size_t k) {
    b.torque_Nm.push_back(std::abs(T[k]) <= zero_torque_Nm ? 0.0 : T[k]);
    b.twist_rad.push_back(psi[k]);
  };
  TorqueLoop loop;
  for (std::size_t k = c.bottom + 1; k-- > c.top;) add(loop.unloading, k);
  for (std::size_t k = c.bottom; k <= c.end; ++k) add(loop.loading, k);
  return loop;
}

double loop_width_rad(const TorqueLoop& loop, double T) {
  return twist_at(loop.unloading, T) - twist_at(loop.loading, T);
}

double hysteresis_loss_rad(const TorqueLoop& loop) { return loop_width_rad(loop, 0.0); }

double rig_hysteresis_loss_rad(const TorqueLoop& loop) {
  return twist_limits(loop.unloading, 0.0).second - twist_limits(loop.loading, 0.0).first;
}

LoopWidth widest_loop_width(const TorqueLoop& loop) {
  const double lo = std::max(loop.loading.torque_Nm.front(), loop.unloading.torque_Nm.front());
  const double hi = std::min(loop.loading.torque_Nm.back(), loop.unloading.torque_Nm.back());
  std::vector<LoopWidth> at;
  for (const TorqueTwist* b : {&loop.loading, &loop.unloading})
    for (const double T : b->torque_Nm)
      if (T >= lo && T <= hi) at.push_back({loop_width_rad(loop, T), T});
  if (at.empty()) throw std::invalid_argument("widest_loop_width: the branches share no torque");
  double widest = at.front().width_rad;
  for (const LoopWidth& w : at) widest = std::max(widest, w.width_rad);
  const double tie = widest - 1e-9 * std::abs(widest);
  LoopWidth best{widest, lo};
  for (const LoopWidth& w : at)
    if (w.width_rad >= tie && w.torque_Nm >= best.torque_Nm) best = w;
  return best;
}

namespace {
/// ∫T dψ along a branch in its order, trapezoids.
double work_along(const TorqueTwist& b) {
  double w = 0;
  for (std::size_t k = 0; k + 1 < b.torque_Nm.size(); ++k)
    w += 0.5 * (b.torque_Nm[k] + b.torque_Nm[k + 1]) * (b.twist_rad[k + 1] - b.twist_rad[k]);
  return w;
}
}  // namespace

double loop_area_J(const TorqueLoop& loop) { return work_along(loop.loading) - work_along(loop.unloading); }

double SegmentLaw::twist_rad(double T) const {
  const double m = std::abs(T);
  const double a = std::min(m, t1_Nm), b = std::clamp(m - t1_Nm, 0.0, t2_Nm - t1_Nm), d = std::max(0.0, m - t2_Nm);
  const double beyond_t2 = d == 0 ? 0.0 : k3_Nm_per_rad > 0 ? d / k3_Nm_per_rad : std::numeric_limits<double>::quiet_NaN();
  return std::copysign(a / k1_Nm_per_rad + b / k2_Nm_per_rad + beyond_t2, T);
}

namespace {
/// The curve's odd part at T (up to its ends' rounding beyond ±T).
double odd(const TorqueTwist& c, double T) {
  const double rounding_Nm =
      kEndRounding * std::max(std::abs(c.torque_Nm.front()), std::abs(c.torque_Nm.back()));
  return 0.5 * (twist_at(c, T, rounding_Nm) - twist_at(c, -T, rounding_Nm));
}
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
