#include "gear/gear.hpp"

#include <sstream>

#include "common/constants.hpp"
#include "common/error.hpp"

namespace sw {

const std::vector<CaseKey<GearParams>>& gear_keys() {
  using G = GearParams;
  const auto proportion = within(0.1, 2.0, true, true);
  static const std::vector<CaseKey<G>> keys = {
      number_key<G>("module_mm", &G::module_m, 1e-3, "mm", above(0), "m, the module"),
      integer_key<G>("teeth_flexspline", &G::teeth_flexspline, at_least(4), "z_f, the flexspline's external teeth"),
      integer_key<G>("teeth_circular", &G::teeth_circular, at_least(5),
                     "z_c, the circular spline's internal teeth; z_c > z_f and z_c - z_f even (two engagement zones)"),
      number_key<G>("pressure_angle_deg", &G::pressure_angle_rad, kPi / 180.0, "deg", within(5, 45, true, true),
                    "alpha of the basic rack"),
      number_key<G>("profile_shift_flexspline", &G::profile_shift_flexspline, 1, "modules", any_value(),
                    "x_f, the flexspline's profile shift"),
      number_key<G>("profile_shift_circular", &G::profile_shift_circular, 1, "modules", any_value(),
                    "x_c, the circular spline's profile shift"),
      integer_key<G>("cutter_teeth", &G::cutter_teeth, at_least(8),
                     "z_0 of the shaper cutter that generates the flexspline's teeth"),
      number_key<G>("addendum_coefficient_flexspline", &G::addendum_coefficient_flexspline, 1, "modules", proportion,
                    "h_a,f*: the flexspline's tip above its shifted reference circle (ISO 53: 1)"),
      number_key<G>("addendum_coefficient_circular", &G::addendum_coefficient_circular, 1, "modules", proportion,
                    "h_a,c*: the circular spline's tip inside its shifted reference circle"),
      number_key<G>("dedendum_coefficient_flexspline", &G::dedendum_coefficient_flexspline, 1, "modules", proportion,
                    "h_f,f*: the shaper cutter's tip height, which cuts the flexspline's root (ISO 53: 1.25)"),
      number_key<G>("dedendum_coefficient_circular", &G::dedendum_coefficient_circular, 1, "modules", proportion,
                    "h_f,c*: the circular spline's root outside its shifted reference circle"),
      number_key<G>("tip_rounding_flexspline_mm", &G::tip_rounding_flexspline_m, 1e-3, "mm", at_least(0),
                    "radius rounding the flexspline tooth's tip corners, < module (0: sharp)"),
      number_key<G>("tip_rounding_circular_mm", &G::tip_rounding_circular_m, 1e-3, "mm", at_least(0),
                    "radius rounding the circular spline tooth's tip corners, < module (0: sharp)"),
  };
  return keys;
}

void validate_gear(const GearParams& g, const std::string& file) {
  const std::string at = file.empty() ? "" : file + ": ";
  check_key_ranges(g, gear_keys(), "gear", at);
  auto fail = [&](const std::string& key, double value, const std::string& expectation) {
    std::ostringstream s;
    s << at << "gear." << key << " = " << value << "; " << expectation;
    throw InputError(s.str());
  };
  if (g.teeth_circular <= g.teeth_flexspline)
    fail("teeth_circular", g.teeth_circular,
         "must be > gear.teeth_flexspline = " + std::to_string(g.teeth_flexspline) +
             " (the flexspline has fewer teeth than the circular spline)");
  if ((g.teeth_circular - g.teeth_flexspline) % 2 != 0)
    fail("teeth_circular", g.teeth_circular, "z_c - z_f must be even (a two-lobe wave generator engages two zones)");
  if (!(g.tip_rounding_flexspline_m < g.module_m))
    fail("tip_rounding_flexspline_mm", g.tip_rounding_flexspline_m * 1e3, "must be in [0, module)");
  if (!(g.tip_rounding_circular_m < g.module_m))
    fail("tip_rounding_circular_mm", g.tip_rounding_circular_m * 1e3, "must be in [0, module)");
}

}  // namespace sw
