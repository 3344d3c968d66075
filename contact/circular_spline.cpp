#include "contact/circular_spline.hpp"

#include <numbers>
#include <sstream>

#include "common/error.hpp"

namespace sw {
namespace {

std::string mm(double m) {
  std::ostringstream s;
  s << m * 1e3;
  return s.str();
}

}  // namespace

CircularSplineParams default_circular_spline(const GearParams& gear, double face_width_m) {
  const double pitch_diameter = gear.module_m * gear.teeth_circular;
  return {0.5 * kCircularSplineOuterDiameterPerPitchDiameter * pitch_diameter, face_width_m};
}

void validate_circular_spline(const CircularSplineParams& c, double root_radius_m, const std::string& file) {
  const std::string at = file.empty() ? "" : file + ": ";
  if (!(c.width_m > 0)) throw InputError(at + "circular_spline.width_mm = " + mm(c.width_m) + "; must be > 0");
  if (!(c.outer_radius_m > root_radius_m))
    throw InputError(at + "circular_spline.outer_radius_mm = " + mm(c.outer_radius_m) +
                     "; must be > the circular spline's root radius " + mm(root_radius_m) + " mm (from [gear])");
}

double circular_spline_compliance_rad_per_Nm(const CircularSplineParams& c, double root_radius_m,
                                             double shear_modulus_Pa) {
  validate_circular_spline(c, root_radius_m);
  if (!(shear_modulus_Pa > 0)) throw InputError("circular spline: shear modulus must be > 0");
  const double r1 = root_radius_m, r2 = c.outer_radius_m;
  return (1.0 / (r1 * r1) - 1.0 / (r2 * r2)) / (4.0 * std::numbers::pi * shear_modulus_Pa * c.width_m);
}

}  // namespace sw
