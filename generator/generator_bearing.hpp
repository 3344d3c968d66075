#pragma once
// The wave generator's flexible ball bearing: Hertzian point contacts of a ball with the inner race (on the cam) and
// the outer race (the flexible ring pressed into the flexspline's bore), and the radial approach of the two races
// under a ball load Q. SI units. Standard library only (and common/case_keys.hpp), so that the case's option structs
// can hold it.
//
// Geometry (Harris & Kotzalas, Rolling Bearing Analysis, 5th ed. 2006, vol. 1 "Essential Concepts of Bearing
// Technology", ch. 2 "Rolling bearing macrogeometry", the ball–raceway curvature sum and difference of a radial
// deep-groove bearing, contact angle 0, zero clearance): ball diameter D, pitch diameter d_m, groove radii
// r_i = f_i·D and r_o = f_o·D, γ = D/d_m. Written out, as they enter the code:
//   inner race  Σρ_i = (1/D)·(4 − 1/f_i + 2γ/(1 − γ)),   F(ρ)_i = (1/f_i + 2γ/(1 − γ)) / (4 − 1/f_i + 2γ/(1 − γ))
//   outer race  Σρ_o = (1/D)·(4 − 1/f_o − 2γ/(1 + γ)),   F(ρ)_o = (1/f_o − 2γ/(1 + γ)) / (4 − 1/f_o − 2γ/(1 + γ))
// Each contact is an elliptical Hertz contact (Harris & Kotzalas ch. 6 "Contact stress and deformation", point
// contact; Johnson, Contact Mechanics, 1985, §4.2) solved exactly with the complete elliptic integrals (std::comp_ellint_1/2): with
// A ≤ B the principal relative curvatures (A + B = Σρ/2, B − A = Σρ·F(ρ)/2) the eccentricity e of the contact
// ellipse solves B/A = [E(e)/(1 − e²) − K(e)] / [K(e) − E(e)]; then a³ = 3Q·(K − E)/(2π·E*·A·e²), b = a·√(1 − e²),
// and the approach is δ = A·e²·a²·K/(K − E), i.e. δ ∝ Q^(2/3) exactly (1/E* = 2(1 − ν²)/E, ball and races of one
// steel). The ball's approach is δ_i + δ_o.
//
// Idealisations: the races keep their undeformed curvature (the generator's ovalisation changes the race curvature by
// 3·w0/r_p², about 3 % at w0 = m); no clearance, no preload beyond what the caller's ball load holds; no centrifugal
// force (quasi-static); rings rigid beyond the Hertzian zone (their bending is the flexspline's and the cam's part).
#include <string>
#include <vector>

#include "common/case_keys.hpp"

namespace sw {

/// A deep-groove ball bearing between the cam and the flexspline. Metres; conformity f = groove radius / D.
struct GeneratorBearing {
  int balls = 0;
  double ball_diameter_m = 0;
  double inner_groove_conformity = 0.52;  ///< f_i: inner race (on the cam)
  double outer_groove_conformity = 0.53;  ///< f_o: outer race (the flexible ring, flexspline side)
  /// d_m/2: the ball centres' circle. Resolved from the flexspline's bore by bearing_pitch_radius_m when the case is
  /// read (not a case key).
  double pitch_radius_m = 0;
  double youngs_modulus_Pa = 208e9;  ///< bearing steel (AISI 52100 / 100Cr6), balls and races alike
  double poisson_ratio = 0.3;
};

/// Wall of the flexible outer ring from its groove bottom to the flexspline's bore, in ball diameters. Assumption (not
/// a published rule): thin-section rings about a quarter of a ball diameter thick under the groove.
inline constexpr double kOuterRingWallPerBallDiameter = 0.25;

/// Pitch radius of a bearing whose outer ring sits in a bore of radius bore_radius_m: the outer ring's outside is the
/// bore, its wall under the groove kOuterRingWallPerBallDiameter·D, the ball centres D/2 further in:
/// r_p = r_bore − (0.25 + 0.5)·D. The cam's radius under the inner ring follows (r_p − D/2 − the inner ring's wall).
double bearing_pitch_radius_m(double bore_radius_m, double ball_diameter_m);

/// The [wave_generator] bearing = {...} table's schema (common/case_keys.hpp).
const std::vector<CaseKey<GeneratorBearing>>& generator_bearing_keys();

/// Checks the bearing (balls ≥ 3, D > 0, 0.5 < f < 1 for both races, pitch radius > D so the inner race exists,
/// balls fit on the pitch circle: z·D < 2π·r_p, E > 0, −1 < ν < 0.5). Throws InputError naming the key in mm, e.g.
/// "wave_generator.bearing.inner_groove_conformity = 0.49; must be in (0.5, 1) ...", prefixed by `file` if not empty.
void validate_generator_bearing(const GeneratorBearing& b, const std::string& file = "");

/// One ball–race contact: curvature sum Σρ (1/m), curvature difference F(ρ), and for a load the semi-axes and the
/// approach.
struct HertzPointContact {
  double curvature_sum_per_m = 0;  ///< Σρ
  double curvature_difference = 0; ///< F(ρ), in [0, 1)
  double eccentricity = 0;         ///< e of the contact ellipse
  double semi_major_m = 0, semi_minor_m = 0;  ///< a (across the rolling direction), b
  double approach_m = 0;           ///< δ: ball centre to race, along the load
};

/// The inner-race (cam side) contact under ball load Q ≥ 0 (N).
HertzPointContact inner_race_contact(const GeneratorBearing& b, double ball_load_N);
/// The outer-race (flexspline side) contact under ball load Q ≥ 0 (N).
HertzPointContact outer_race_contact(const GeneratorBearing& b, double ball_load_N);

/// Radial approach of the inner and outer race under ball load Q ≥ 0 (N): δ_i + δ_o, metres; exactly ∝ Q^(2/3).
double ball_approach_m(const GeneratorBearing& b, double ball_load_N);

/// d(ball_approach_m)/dQ = (2/3)·δ/Q (m/N), the ball's tangent compliance; +infinity at Q = 0.
double ball_approach_derivative_m_per_N(const GeneratorBearing& b, double ball_load_N);

}  // namespace sw
