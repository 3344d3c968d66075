#include "gear/accuracy.hpp"

#include <cmath>
#include <cstdio>

#include "common/error.hpp"

namespace sw {

FlankTolerances iso1328_tolerances(double d, double m, int A) {
  if (A < 1 || A > 11)
    throw InputError("ISO 1328-1 tolerance class " + std::to_string(A) + "; expected a class from 1 to 11");
  if (!(d > 0) || !(m > 0))
    throw InputError("ISO 1328-1 tolerances need a positive reference diameter and module (mm)");
  const double step = std::pow(std::sqrt(2.0), A - 5);  // clause 5.2: each class √2 from the next
  FlankTolerances t;
  t.single_pitch_um = (0.001 * d + 0.4 * m + 5) * step;
  t.cumulative_pitch_um = (0.002 * d + 0.55 * std::sqrt(d) + 0.7 * m + 12) * step;
  t.profile_slope_um = (0.4 * m + 0.001 * d + 4) * step;
  t.profile_form_um = (0.55 * m + 5) * step;
  t.profile_total_um = std::hypot(t.profile_slope_um, t.profile_form_um);
  return t;
}

std::optional<std::string> iso1328_scope(double d, double m) {
  char b[160];
  if (m < 0.5) std::snprintf(b, sizeof b, "m_n %.3g mm below the standard's 0.5 mm: the formulas extrapolated", m);
  else if (m > 70) std::snprintf(b, sizeof b, "m_n %.3g mm above the standard's 70 mm: the formulas extrapolated", m);
  else if (d < 5) std::snprintf(b, sizeof b, "d %.3g mm below the standard's 5 mm: the formulas extrapolated", d);
  else if (d > 15000) std::snprintf(b, sizeof b, "d %.3g mm above the standard's 15,000 mm: the formulas extrapolated", d);
  else return std::nullopt;
  return std::string(b);
}

}  // namespace sw
