#pragma once
// Compliance of one loaded tooth pair per unit face width, plane strain, split by cause. The teeth are built in at
// their root circles: what lies below (the flexspline's rim, the circular spline's ring) is the FEM's, so nothing here
// counts it twice. SI units; compliances in m of approach along the line of action per N/m of line load (m²/N).
//
// Each tooth is a cantilever on its radial centre line (external flexspline tooth pointing outwards, internal
// circular-spline tooth pointing inwards), with the half-thickness y(x) of its ACTUAL outline (involute from
// gear/tooth_profile.hpp, and the same quarter-ellipse root fillet as flexspline_outline; the circular spline's root is
// rounded by the same rule mirrored), sampled finely and integrated numerically from the root circle to the load.
//
// Deflection convention (Weber 1949): the tooth's deflection is the displacement, along the load, of the point C of its
// centre line at the height of the contact point P; the flattening between P and the centre line is the contact
// term. With the line load w along the unit vector f at P, and a virtual unit load along f at C, the principle of
// virtual work over the sections x (distance along the centre line, built in at the root x_r) gives
//   δ_b = ∫_{x_r}^{x_C} [ M M̄ / (E′ I) + κ V V̄ / (G A) + N N̄ / (E′ A) ] dx,          E′ = E/(1 − ν²), κ = 1.2,
//   I = (2y)³/12, A = 2y (per unit width), M = (P − X)×w f, M̄ = (C − X)×f, V, N the transverse and axial parts.
// This is the potential-energy method of Yang & Lin (1987, J. Mech. Trans. Autom. Des. 109:189, eqs. 5–7) with the
// shear term of Tian (2004, MSc thesis, U. Alberta, eq. 2.17) and the axial term of Yang & Lin's eq. 7, written for the
// Weber read-out point instead of the work-conjugate one, and integrated over the real outline (fillet included) as
// Chen & Shao (2011, Mech. Mach. Theory 46:1144) do.
//
// Fillet/foundation (the local deformation of the body at the tooth's base, which a ring or a built-in root does not
// have), Sainsot, Velex & Duverger (2004, J. Mech. Des. 126:748, eq. 3 and table 1):
//   δ_f = w cos²α_m / E · [ L* (u_f/S_f)² + M* (u_f/S_f) + P* (1 + Q* tan²α_m) ],
//   X* = A/θ_f² + B h_f² + C h_f/θ_f + D/θ_f + E h_f + F   (X = L, M, P, Q; table 1),
// α_m the angle between the load and the normal to the centre line, S_f = 2 r_f θ_f the root's arc thickness, θ_f its half angle, h_f = r_f/r_int the root over the body's bore radius, u_f
// measured from the root circle to where the line of action crosses the centre line. The fit covers gears of ~20–100
// teeth (θ_f ≳ 0.03); beyond it (the strain wave gear's z ~ 200, θ_f ≈ 0.009) its 1/θ_f² terms run away, so the
// coefficients are taken at FoundationFit's edge (θ_f ≥ 0.03, h_f ≤ 1.6; h_f = 1.6 stands for a solid body).
//
// Against the explicit-tooth plane-strain FEM (tests/gear: the same outline, the body held at its bore, Weber's
// read-out) this method is SOFTER: bending + foundation = 1.20× the FEM at the pitch point of a standard z = 30 tooth,
// 1.13× near its tip, and 1.62× / 1.43× for the seed's flexspline tooth on its 0.7 mm rim (mid-flank / tip), where
// the foundation fit is extrapolated. The beam part alone is 1.22× a standard tooth built in just below its root. It is
// an upper bound of the tooth's compliance, not a 5 % one.
//
// Contact flattening, Weber & Banaschek (1953; the form used in ISO 6336-1's background, Schmidt 1973): approach of
// the two centre lines by the local flattening,
//   δ_H = 2 w (1 − ν²)/(π E) · [ ln(2 h_1 / b) + ln(2 h_2 / b) − ν/(1 − ν) ],   b = sqrt(8 w ρ (1 − ν²)/(π E)),
// h_i the distance from the contact point to tooth i's centre line along the line of action, b the Hertzian
// half-width, ρ the relative radius of curvature (1/ρ = 1/ρ_1 ± 1/ρ_2, minus for the internal gear). It depends on the
// load (weakly, through ln w): the compliance reported is the secant δ_H/w at the given line load. The formula
// assumes h ≫ b; a body's term where ln(2h/b) < ν/(2(1 − ν)) (h ≲ 0.6 b: the conformal internal contact of small
// teeth at tens of N/mm) is taken as zero, not negative.
//
// Circular spline (internal, z_c ~ 200): treated exactly like the flexspline's tooth, on its own outline (the tooth
// between two involute spaces, thickness 2πR/z_c − space width, growing towards its root), pointing inwards. Its
// contact point is the conjugate point of the internal involute pair at its zero-backlash centre distance
// (inv α_w = inv α + 2 tan α (x_c − x_f)/(z_c − z_f), r_bc tan α_c − r_bf tan α_f = a_w sin α_w), clamped to the
// circular spline's active flank: an idealisation of the strain wave mesh, whose deformed flexspline makes no
// conjugate pair (it moves the contact on the stiff circular-spline tooth a little, which changes its small share).
#include "common/material.hpp"
#include "gear/gear.hpp"

namespace sw {

/// Compliance of one tooth pair per unit face width, split by cause (m of approach along the line of action per N/m of
/// line load, i.e. m²/N): the teeth alone, built in at their roots (the rim's compliance is the FEM's).
struct ToothPairCompliance {
  double bending_f = 0, bending_c = 0;        ///< bending + shear + compression of each tooth (flexspline, circular spline)
  double foundation_f = 0, foundation_c = 0;  ///< fillet/foundation rotation and shift at each tooth's base
  double contact = 0;                         ///< Hertzian flattening of the pair (both bodies), secant at the line load
  double total() const { return bending_f + bending_c + foundation_f + foundation_c + contact; }
  /// Single-pair stiffness c′ in N/(mm·µm) of face width, the unit of ISO 6336-1 (1 N/(mm·µm) = 1e9 N/m²).
  double stiffness_N_per_mm_um() const { return 1e-9 / total(); }
};

/// Line load at which the contact term is evaluated unless told otherwise: 100 N/mm, the lowest load for which ISO
/// 6336-1 gives c′ (F_t·K_A/b ≥ 100 N/mm).
inline constexpr double kReferenceLineLoad_N_per_m = 1e5;

/// The range of Sainsot et al.'s table-1 fit used for the foundation term (see the header comment).
struct FoundationFit {
  static constexpr double kMinRootHalfAngle_rad = 0.03;  ///< θ_f below this is taken as this (z ≳ 100 teeth)
  static constexpr double kMaxBodyRatio = 1.6;           ///< h_f = r_f/r_int above this is taken as this
};

/// At the contact point on the flexspline's flank at radius `contact_radius_f_m` (its own frame), load along the
/// involute's normal (line of action), both gears as in `g` (the circular spline internal). `rim_inner_radius_m` is the
/// flexspline's bore (h_f = r_f/r_int of the foundation term; 0 = a solid body, h_f at the fit's edge); the circular
/// spline is taken as a thick ring. Throws InputError when the radius lies outside the flexspline's active flank
/// [form radius, tip radius] or the line load is not positive.
/// `contact_radius_c_m` > 0 places the load on the circular spline's tooth at that radius (where the teeth really
/// touch, e.g. its tip corner), clamped to its active flank; 0 takes the conjugate point.
ToothPairCompliance tooth_pair_compliance(const GearParams& g, const Material& m, double contact_radius_f_m,
                                          double line_load_N_per_m = kReferenceLineLoad_N_per_m,
                                          double rim_inner_radius_m = 0.0, double contact_radius_c_m = 0.0);

/// A standard external spur pair cut by the ISO 53 basic rack (h_a* = 1, h_f* = 1.25; the root rounded by the same
/// quarter-ellipse fillet as the flexspline's outline), for the check against ISO 6336-1.
struct SpurPair {
  int teeth_1 = 30, teeth_2 = 30;
  double profile_shift_1 = 0, profile_shift_2 = 0;
  double module_m = 1e-3;
  double pressure_angle_rad = 0.3490658503988659;  ///< 20°
  double bore_ratio = 0;  ///< r_f/r_int of both bodies (0 = solid, the fit's edge)
};

/// Same as tooth_pair_compliance for the external pair: contact at radius `contact_radius_1_m` on gear 1's flank, the
/// conjugate point on gear 2 at the zero-backlash centre distance. Gear "f" of the result is gear 1, "c" gear 2.
ToothPairCompliance spur_pair_compliance(const SpurPair& p, const Material& m, double contact_radius_1_m,
                                         double line_load_N_per_m = kReferenceLineLoad_N_per_m);

/// Radius of the pitch point on gear 1 of the pair (the operating pitch radius r_w1).
double spur_pitch_radius_1(const SpurPair& p);

/// ISO 6336-1:2006 method B, eq. (71)/table 9: theoretical single stiffness c′_th = 1/q′ of solid spur gears,
/// N/(mm·µm), q′ = C1 + C2/z_n1 + C3/z_n2 + C4 x1 + C5 x1/z_n1 + C6 x2 + C7 x2/z_n2 + C8 x1² + C9 x2² (a fit of
/// Schmidt's 1973 calculations, stated to ±5 % for the ISO basic rack, x1 ≥ x2, −0.5 ≤ x1 + x2 ≤ 2).
double iso6336_theoretical_single_stiffness(int zn1, int zn2, double x1, double x2);

/// Gear parameters describing gear `which` (1 or 2) of a spur pair as an external "flexspline" tooth of this module
/// (a shaper of many teeth stands for the rack): used to mesh the standard tooth with the same outline code.
GearParams spur_gear_as_external(const SpurPair& p, int which);

}  // namespace sw
