#pragma once
// The wave generator's ball bearing: its load ratings and its basic rating life L10 from the load of every ball.
//
// Ratings of the bearing (radial deep-groove ball bearing, one row i = 1, contact angle α = 0, steel of contemporary
// quality), D_w = ball diameter, D_pw = pitch diameter, Z = balls, γ = D_w·cos α / D_pw, lengths in mm, forces in N:
//  - basic dynamic load rating, ISO 281:2007 §6.1.1 eq. (2) for D_w ≤ 25.4 mm, eq. (3) above:
//      C_r = b_m·f_c·(i·cos α)^0.7·Z^(2/3)·D_w^1.8   resp.   3.647·b_m·f_c·(i·cos α)^0.7·Z^(2/3)·D_w^1.4,
//    b_m = 1.3 (ISO 281:2007 Table 1, radial ball bearings), f_c from ISO 281:2007 Table 2 (single-row radial contact
//    groove ball bearings) at γ, linearly interpolated between its rows as the table's footnote prescribes;
//  - basic static load rating, ISO 76:2006 §6.1.1: C_0r = f_0·i·Z·D_w²·cos α, f_0 from ISO 76:2006 Table 1 (radial
//    contact groove ball bearings), linearly interpolated.
// Raceway ratings and the life from ball loads (Lundberg & Palmgren, "Dynamic capacity of rolling bearings", Acta
// Polytechnica Mech. Eng. Ser. 1(3), 1947; as written in Harris & Kotzalas, Rolling Bearing Analysis, 5th ed. 2006,
// vol. 2 "Advanced Concepts of Bearing Technology", the fatigue-life chapter's raceway ratings for point contact, and
// used for raceways by ISO/TS 16281:2008), f = groove radius / D_w:
//   Q_ci = b_m·93.2·(2f_i/(2f_i − 1))^0.41·(1 − γ)^1.39/(1 + γ)^(1/3)·(γ/cos α)^0.3·D_w^1.8·Z^(−1/3)
//   Q_co = b_m·93.2·(2f_o/(2f_o − 1))^0.41·(1 + γ)^1.39/(1 − γ)^(1/3)·(γ/cos α)^0.3·D_w^1.8·Z^(−1/3)
// (93.2 N/mm^1.8 = Lundberg–Palmgren's 98.1 times their reduction factor λ = 0.95; b_m multiplies each raceway
// rating here as it multiplies C_r in ISO 281, so that both routes carry one material factor; D_w > 25.4 mm:
// 3.647·D_w^1.4 for D_w^1.8, as in ISO 281 eq. (3)). The equivalent ball load of a raceway is its cubic mean
// Q_e = (ΣQ_j³/Z)^(1/3) when the raceway turns relative to the load (each of its points passes under every ball
// load), and the 10/3 mean (ΣQ_j^(10/3)/Z)^(3/10) when it stands still relative to the load (its most loaded point
// stays loaded). Each raceway lives L = (Q_c/Q_e)³ million revolutions of the rings relative to each other, and the
// bearing L = (L_i^(−10/9) + L_o^(−10/9))^(−9/10) (Lundberg–Palmgren's product of survivals, Weibull slope 10/9).
//
// In a wave generator the ball loads are set by the elliptical cam: the load zone (two opposite lobes at the major
// axis) turns with the cam, i.e. with the INNER ring. The inner raceway is therefore stationary relative to the load
// (10/3 mean), and the OUTER raceway, which turns relative to the cam, sees every ball pass under the rotating load
// (cubic mean). A shaft bearing in a housing under a fixed radial load is the other way round. Both are offered. The
// weaker raceway (the convex inner one) thus gets the harsher 10/3 mean in a generator: for the same ball loads it
// lives shorter than a shaft bearing, as ISO 281's old rotation factor V = 1.2 for a load turning with the inner ring
// said. ISO's f_c table is Lundberg–Palmgren's f_c for r_i = r_o = 0.52·D_w (tests/generator/test_bearing_life.cpp);
// with the looser outer groove of the default f_o = 0.53 this route gives 7–22 % less life than (C_r/P)³.
//
// Idealisations: the balls' loads are quasi-static (no centrifugal force, no gyroscopic moment), contact angle 0; the
// rating life is ISO 281's basic L10 (90 % reliability, a1 = 1, no a_ISO lubrication/contamination factor); the flexible
// outer ring's bending stress and its ovalisation of the groove do not enter the rating (ISO 281 assumes rigid rings);
// the ratings assume contemporary through-hardened bearing steel (b_m = 1.3).
#include <string>
#include <vector>

#include "generator/generator_bearing.hpp"

namespace sw {

/// ISO 281:2007 Table 1: rating factor b_m of radial ball bearings (contemporary steel and manufacture).
inline constexpr double kRatingFactorRadialBall = 1.3;

/// ISO 281:2007 Table 2, single-row radial contact groove ball bearings: f_c at γ = D_w·cos α/D_pw (0.01 ≤ γ ≤ 0.40,
/// linear interpolation between rows). Throws InputError outside the table (the standard gives no value there).
double iso281_fc_radial_ball(double gamma);

/// ISO 76:2006 Table 1, radial contact groove ball bearings: f_0 at γ (0 ≤ γ ≤ 0.40, linear interpolation). Throws
/// InputError outside the table.
double iso76_f0_radial_ball(double gamma);

/// Basic dynamic radial load rating C_r (N) of the bearing by ISO 281:2007 eq. (2)/(3) (see the header). Validates b.
double basic_dynamic_load_rating_N(const GeneratorBearing& b);

/// Basic static radial load rating C_0r (N) of the bearing by ISO 76:2006 (see the header). Validates b.
double basic_static_load_rating_N(const GeneratorBearing& b);

/// Lundberg–Palmgren basic dynamic load ratings of the inner and outer raceway (N), for 10^6 revolutions of the rings
/// relative to each other at 90 % survival (see the header).
struct RacewayRatings {
  double inner_N = 0;
  double outer_N = 0;
};
/// The raceway ratings Q_ci, Q_co of the bearing (validates b).
RacewayRatings raceway_dynamic_load_ratings_N(const GeneratorBearing& b);

/// Which ring the load zone stands still on.
enum class LoadFixedTo {
  kInnerRing,  ///< wave generator: the lobes turn with the cam and the inner ring; the outer raceway turns under them
  kOuterRing,  ///< shaft bearing under a load fixed in the housing: the inner raceway turns under the load
};

/// The rating life and its parts, in millions of revolutions of the rings relative to each other.
struct BearingLife {
  double inner_equivalent_load_N = 0;  ///< Q_ei
  double outer_equivalent_load_N = 0;  ///< Q_eo
  double inner_life_Mrev = 0;          ///< L_i = (Q_ci/Q_ei)³; +infinity without load
  double outer_life_Mrev = 0;          ///< L_o = (Q_co/Q_eo)³
  double life_Mrev = 0;                ///< L10 = (L_i^(−10/9) + L_o^(−10/9))^(−9/10)
};

/// L10 of the bearing from the normal load of each of its balls (N, one per ball position, b.balls of them, each
/// ≥ 0, in any order: the means do not depend on where the loads sit) with the load zone fixed to `fixed_to`. All
/// loads zero gives an infinite life. Throws InputError on a count other than b.balls or a negative load.
BearingLife rating_life_from_ball_loads(const GeneratorBearing& b, const std::vector<double>& ball_loads_N,
                                        LoadFixedTo fixed_to);

/// Speed of the generator's inner ring (cam, input) relative to its outer ring (flexspline, output), rpm ≥ 0:
/// |n_in·(1 − 1/ratio)|, ratio = n_in/n_out signed (negative when the output turns against the input, e.g. a cup
/// drive with the circular spline fixed: ratio = −z_f/(z_c − z_f)); |ratio| > 1 else InputError.
double ring_relative_speed_rpm(double input_speed_rpm, double ratio);

/// Hours of a life in millions of relative revolutions at a relative speed (rpm > 0): 10^6·L/(60·n).
double life_hours(double life_Mrev, double relative_speed_rpm);

/// The wave generator bearing's L10 in hours from its ball loads (load zone fixed to the inner ring) at input speed
/// (rpm) and ratio (signed, see ring_relative_speed_rpm).
double generator_bearing_l10_hours(const GeneratorBearing& b, const std::vector<double>& ball_loads_N,
                                   double input_speed_rpm, double ratio);

}  // namespace sw
