#pragma once
// Gear parameters of a strain wave gear set (the case file's [gear] table), SI units.
namespace sw {

struct GearParams {
  double module_m = 0.2e-3;
  int teeth_flexspline = 190;        ///< z_f (external teeth on the flexspline)
  int teeth_circular = 192;          ///< z_c (internal teeth on the rigid circular spline), z_c > z_f
  double pressure_angle_rad = 0.3490658503988659;  ///< α = 20°
  double profile_shift_flexspline = 1.52;          ///< x_f
  double profile_shift_circular = 1.57;            ///< x_c
  int cutter_teeth = 80;             ///< z_0 of the shaper cutter that generates the flexspline teeth
  double addendum_coefficient = 1.0;       ///< h_a* (not in the case file yet: standard basic rack)
  double tip_clearance_coefficient = 0.25; ///< c* (not in the case file yet: standard basic rack)
};

}  // namespace sw
