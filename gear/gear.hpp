#pragma once
// Gear parameters of a strain wave gear set (the case file's [gear] table), SI units, and their validation.
#include <optional>
#include <string>
#include <vector>

#include "common/case_keys.hpp"

namespace sw {

struct GearParams {
  double module_m = 0.2e-3;
  int teeth_flexspline = 190;        ///< z_f (external teeth on the flexspline)
  int teeth_circular = 192;          ///< z_c (internal teeth on the rigid circular spline), z_c > z_f
  double pressure_angle_rad = 0.3490658503988659;  ///< α = 20°
  double profile_shift_flexspline = 1.52;          ///< x_f
  double profile_shift_circular = 1.57;            ///< x_c
  int cutter_teeth = 80;             ///< z_0 of the shaper cutter that generates the flexspline teeth
  /// Tooth proportions in modules. Defaults: the ISO 53 basic rack (h_a* = 1, h_f* = 1.25). Harmonic drives use
  /// short teeth (h_a* ≈ 0.6–0.8): the radial travel of a tooth between the axes is only 2·w0 ≈ 2·m.
  double addendum_coefficient_flexspline = 1.0;   ///< h_a,f*: tip above the shifted reference circle
  double addendum_coefficient_circular = 1.0;     ///< h_a,c*: tip inside the shifted reference circle
  double dedendum_coefficient_flexspline = 1.25;  ///< h_f,f*: the shaper cutter's tip height (root follows from it)
  double dedendum_coefficient_circular = 1.25;    ///< h_f,c*: root outside the shifted reference circle
  /// Radius of the arc that rounds each tooth's tip corners (tangent to the flank and to the tip circle), metres;
  /// 0: sharp corners.
  double tip_rounding_flexspline_m = 0;
  double tip_rounding_circular_m = 0;
};

/// The [gear] table's schema (common/case_keys.hpp).
const std::vector<CaseKey<GearParams>>& gear_keys();

/// Checks the ranges and the consistency of a gear set that can be made (tooth numbers, module, pressure angle,
/// proportions). Throws InputError "gear.<key> = value; expectation" naming the first violated constraint; `file` is
/// prefixed to the message when not empty.
void validate_gear(const GearParams& g, const std::string& file = "");

/// The reduction ratio z_f / (z_c − z_f) with the circular spline fixed; empty when it is not a whole number (or the
/// circular spline has no more teeth than the flexspline): no catalog row has such a ratio.
inline std::optional<int> reduction_ratio(const GearParams& g) {
  const int difference = g.teeth_circular - g.teeth_flexspline;
  if (difference <= 0 || g.teeth_flexspline % difference != 0) return std::nullopt;
  return g.teeth_flexspline / difference;
}

}  // namespace sw
