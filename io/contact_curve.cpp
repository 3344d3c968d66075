#include "io/contact_curve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "common/error.hpp"

namespace sw {
namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// Twist just below and just above torque x on a polyline with non-decreasing torque t (front() <= x <= back()):
/// they differ only at a vertical step.
std::pair<double, double> limits(const std::vector<double>& t, const std::vector<double>& phi, double x) {
  const std::size_t i = std::lower_bound(t.begin(), t.end(), x) - t.begin();
  const std::size_t j = std::upper_bound(t.begin(), t.end(), x) - t.begin();
  if (i < t.size() && t[i] == x) return {phi[i], phi[j - 1]};  // a point (or a vertical step) at x
  const double w = (x - t[i - 1]) / (t[i] - t[i - 1]);          // x inside the segment (i - 1, i)
  const double v = (1.0 - w) * phi[i - 1] + w * phi[i];
  return {v, v};
}

/// A branch of the loop with its torque ascending.
struct Branch {
  std::vector<double> t, phi;
  double front() const { return t.front(); }
  double back() const { return t.back(); }
};

}  // namespace

TorqueTwistCurve read_torque_twist(const std::string& path) {
  std::ifstream in(path);
  if (!in)
    throw InputError(path + ": cannot be read; give the contact.json written by `strainwave contact CASE.toml` "
                     "(or `strainwave run`)");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw InputError(path + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  auto number = [&](const nlohmann::json& obj, const std::string& key, const std::string& where) {
    if (!obj.is_object() || !obj.contains(key) || !obj[key].is_number())
      throw InputError(path + ": " + where + key + " missing or not a number; expected the contact result of "
                       "`strainwave contact` (SPEC.md \"Contact result\")");
    return obj[key].get<double>();
  };
  TorqueTwistCurve c;
  c.path = path;
  c.rated_torque_Nm = number(j, "rated_torque_Nm", "");
  if (!(c.rated_torque_Nm > 0.0))
    throw InputError(path + ": rated_torque_Nm = " + num(c.rated_torque_Nm) + "; must be > 0");
  if (j.contains("catalog") && j["catalog"].is_object()) {
    c.catalog_t1_Nm = number(j["catalog"], "T1_Nm", "catalog.");
    c.catalog_t2_Nm = number(j["catalog"], "T2_Nm", "catalog.");
  }
  if (!j.contains("torque_twist") || !j["torque_twist"].is_array() || j["torque_twist"].size() < 2)
    throw InputError(path + ": torque_twist missing or with fewer than 2 points; expected a list of {torque_Nm, "
                     "twist_rad} from -rated to +rated torque (and back)");
  const auto& list = j["torque_twist"];
  const std::size_t n = list.size();
  std::vector<double> t(n), phi(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string where = "torque_twist[" + std::to_string(i) + "].";
    t[i] = number(list[i], "torque_Nm", where);
    phi[i] = number(list[i], "twist_rad", where);
  }
  // The loading branch rises to the largest torque; the unloading branch, if any, falls back from there.
  std::size_t top = 0;
  while (top + 1 < n && t[top + 1] >= t[top]) ++top;
  auto wrong = [&](std::size_t i, const std::string& what) {
    return InputError(path + ": torque_twist[" + std::to_string(i) + "].torque_Nm = " + num(t[i]) + " after " +
                      num(t[i - 1]) + " " + what + "; expected torque rising from -rated to +rated (the loading "
                      "branch), then optionally falling back (the unloading branch)");
  };
  if (top == 0) throw wrong(1, "falls at the start");
  for (std::size_t i = top + 1; i < n; ++i)
    if (t[i] > t[i - 1]) throw wrong(i, "rises again on the unloading branch");
  Branch load{{t.begin(), t.begin() + top + 1}, {phi.begin(), phi.begin() + top + 1}};
  if (!(load.back() > load.front()))
    throw InputError(path + ": torque_twist: torque_Nm = " + num(load.front()) + " at every point; expected a curve "
                     "from -rated to +rated torque");
  std::vector<const Branch*> branches{&load};
  Branch unload{{t.rbegin(), t.rend() - top}, {phi.rbegin(), phi.rend() - top}};  // ascending
  if (unload.t.size() >= 2 && unload.back() > unload.front()) branches.push_back(&unload);
  const double lo = std::max(load.front(), branches.back()->front());
  const double hi = std::min(load.back(), branches.back()->back());
  if (!(hi > lo))
    throw InputError(path + ": torque_twist: the loading branch covers [" + num(load.front()) + ", " +
                     num(load.back()) + "] N*m and the unloading branch [" + num(unload.front()) + ", " +
                     num(unload.back()) + "] N*m; they must overlap");
  // Middle line on the union of the branches' torques: exact for piecewise-linear branches.
  std::vector<double> grid;
  for (const Branch* b : branches)
    for (double x : b->t)
      if (x >= lo && x <= hi) grid.push_back(x);
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  for (double x : grid) {
    double left = 0.0, right = 0.0;
    for (const Branch* b : branches) {
      const auto [l, r] = limits(b->t, b->phi, x);
      left += l / branches.size();
      right += r / branches.size();
    }
    // Both limits where the line steps (a dead band crossed at x); at the ends only the side inside the curve.
    if (x > lo || right == left) {
      c.torque_Nm.push_back(x);
      c.twist_rad.push_back(left);
    }
    if (right != left && x < hi) {
      c.torque_Nm.push_back(x);
      c.twist_rad.push_back(right);
    }
  }
  return c;
}

double twist_at(const TorqueTwistCurve& c, double x, double end_tolerance_Nm) {
  const auto& t = c.torque_Nm;
  const auto& phi = c.twist_rad;
  const std::size_t n = t.size();
  if (x < t.front() - end_tolerance_Nm || x > t.back() + end_tolerance_Nm)
    throw InputError(c.path + ": torque " + num(x) + " N*m is beyond the torque-twist curve, which covers [" +
                     num(t.front()) + ", " + num(t.back()) + "] N*m (rated " + num(c.rated_torque_Nm) +
                     " N*m); the curve is not extrapolated");
  if (x <= t.front() || x >= t.back()) {
    // At or just beyond an end: the end segment (the first/last with a torque step), extended.
    std::size_t a = 0;
    if (x <= t.front()) {
      while (t[a + 1] == t.front()) ++a;
    } else {
      a = n - 2;
      while (t[a] == t.back()) --a;
    }
    const std::size_t b = a + 1;
    return phi[a] + (x - t[a]) / (t[b] - t[a]) * (phi[b] - phi[a]);
  }
  const auto [l, r] = limits(t, phi, x);
  return 0.5 * (l + r);
}

}  // namespace sw
