#pragma once
// Torsional compliance of the circular spline: a ring fixed on its outer rim (bolt circle), loaded by the tooth forces
// at its tooth circle. Idealisation: an annular plate of the face width b in circumferential shear, the torque passing
// from the root circle r_root to the fixed radius r_fix as the shear flow T/(2π·r²) per unit width; the rotation of the
// tooth circle against the rim is
//     φ/T = 1/(4π·G·b) · (1/r_root² − 1/r_fix²)
// (the closed form the flexspline FEM's cup theory uses for the diaphragm, fem/flexspline_analysis.hpp
// CupTorsionTheory). What it leaves out: the teeth's own bending (the tooth-pair stiffness), the ring's ovalisation
// under the two mesh zones' radial forces, the bolts' and the housing's compliance. SI units.
#include <string>

#include "gear/gear.hpp"

namespace sw {

/// [circular_spline]: the ring's fixed outer radius and its axial width. Metres.
struct CircularSplineParams {
  double outer_radius_m = 0;  ///< r_fix: where the ring is held (outer rim / bolt circle)
  double width_m = 0;         ///< b: axial width of the ring in shear
};

/// Outer radius of the design rule, metres: 0.7 × the pitch diameter z_c·m (an outer diameter of about 1.4 pitch
/// diameters; our reading of the component sets' dimension tables, an estimate, not a drawing).
inline constexpr double kCircularSplineOuterDiameterPerPitchDiameter = 1.4;

/// The default of an absent [circular_spline] table or key: outer radius by the rule above, width = the flexspline's
/// toothed face width (the teeth the ring carries; the soft estimate: a real ring is wider than its teeth).
CircularSplineParams default_circular_spline(const GearParams& gear, double face_width_m);

/// Checks outer_radius_m > root_radius_m (the circular spline's root circle) and width_m > 0. Throws InputError
/// "circular_spline.outer_radius_mm = 20; must be > the circular spline's root radius 21.9 mm", prefixed by `file`.
void validate_circular_spline(const CircularSplineParams& c, double root_radius_m, const std::string& file = "");

/// φ/T of the ring (rad/(N·m)) between its root circle (root_radius_m) and outer_radius_m, shear modulus G (Pa).
/// Throws InputError for a ring that fails validate_circular_spline or G ≤ 0.
double circular_spline_compliance_rad_per_Nm(const CircularSplineParams& c, double root_radius_m,
                                             double shear_modulus_Pa);

}  // namespace sw
