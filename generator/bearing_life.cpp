#include "generator/bearing_life.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.hpp"
#include "common/format.hpp"

namespace sw {
namespace {

/// ISO 281:2007 Table 2, column "single-row radial contact groove ball bearings": f_c at γ = 0.01, 0.02, …, 0.40.
constexpr std::array<double, 40> kIso281Fc = {
    29.1, 35.8, 40.3, 43.8, 46.7, 49.1, 51.1, 52.8, 54.3, 55.5,  // 0.01–0.10
    56.6, 57.5, 58.2, 58.8, 59.3, 59.6, 59.8, 59.9, 60.0, 59.9,  // 0.11–0.20
    59.8, 59.6, 59.3, 59.0, 58.6, 58.2, 57.7, 57.1, 56.6, 56.0,  // 0.21–0.30
    55.3, 54.6, 53.9, 53.2, 52.4, 51.7, 50.9, 50.0, 49.2, 48.4}; // 0.31–0.40

/// ISO 76:2006 Table 1, column "radial contact groove ball bearings": f_0 at γ = 0.00, 0.01, …, 0.40.
constexpr std::array<double, 41> kIso76F0 = {
    14.7,                                                        // 0.00
    14.9, 15.1, 15.3, 15.5, 15.7, 15.9, 16.1, 16.3, 16.5, 16.4,  // 0.01–0.10
    16.1, 15.9, 15.6, 15.4, 15.2, 14.9, 14.7, 14.4, 14.2, 14.0,  // 0.11–0.20
    13.7, 13.5, 13.2, 13.0, 12.8, 12.5, 12.3, 12.1, 11.8, 11.6,  // 0.21–0.30
    11.4, 11.2, 10.9, 10.7, 10.5, 10.3, 10.0, 9.8, 9.6, 9.4};    // 0.31–0.40

/// Both tables step γ by 0.01.
constexpr double kTableStep = 0.01;

/// Linear interpolation in a table whose first row is at γ = first, step kTableStep.
template <std::size_t N>
double interpolate(const std::array<double, N>& table, double first, double gamma) {
  const double x = (gamma - first) / kTableStep;
  const std::size_t k = std::min<std::size_t>(static_cast<std::size_t>(std::floor(x)), N - 2);
  const double t = x - static_cast<double>(k);
  return table[k] + t * (table[k + 1] - table[k]);
}

/// ISO 281:2007 §6.1.1: eq. (2) holds for D_w ≤ 25.4 mm, eq. (3) (3.647·D_w^1.4) above.
constexpr double kLargeBallLimit_mm = 25.4;
constexpr double kLargeBallFactor = 3.647;

/// D_w^1.8 or 3.647·D_w^1.4 (mm), the ball-size term of ISO 281 eq. (2)/(3).
double ball_size_term(double D_mm) {
  return D_mm <= kLargeBallLimit_mm ? std::pow(D_mm, 1.8) : kLargeBallFactor * std::pow(D_mm, 1.4);
}

/// Lundberg–Palmgren's raceway constant for point contact, N/mm^1.8: 98.1 × λ = 0.95 (Harris & Kotzalas vol. 2).
constexpr double kRacewayConstant = 93.2;
/// Lundberg–Palmgren's Weibull slope of a ball bearing, e = 10/9: L = (L_i^−e + L_o^−e)^(−1/e).
constexpr double kWeibullSlope = 10.0 / 9.0;
/// Life exponent of ball contacts (ISO 281, Lundberg–Palmgren): L = (Q_c/Q_e)³.
constexpr double kLifeExponent = 3.0;

double gamma_of(const GeneratorBearing& b) { return b.ball_diameter_m / (2.0 * b.pitch_radius_m); }

/// (ΣQ^p / Z)^(1/p)
double power_mean(const std::vector<double>& Q, double p) {
  double s = 0;
  for (double q : Q) s += std::pow(q, p);
  return std::pow(s / static_cast<double>(Q.size()), 1.0 / p);
}

double raceway_life(double Qc, double Qe) {
  return Qe > 0 ? std::pow(Qc / Qe, kLifeExponent) : std::numeric_limits<double>::infinity();
}

}  // namespace

double iso281_fc_radial_ball(double gamma) {
  if (!(gamma >= 0.01 && gamma <= 0.40))
    throw InputError("D_w*cos(alpha)/D_pw = " + six_digits(gamma) +
                     "; ISO 281 Table 2 gives f_c for 0.01 to 0.40 (ball diameter / pitch diameter of the bearing)");
  return interpolate(kIso281Fc, 0.01, gamma);
}

double iso76_f0_radial_ball(double gamma) {
  if (!(gamma >= 0.0 && gamma <= 0.40))
    throw InputError("D_w*cos(alpha)/D_pw = " + six_digits(gamma) + "; ISO 76 Table 1 gives f_0 for 0 to 0.40");
  return interpolate(kIso76F0, 0.0, gamma);
}

double basic_dynamic_load_rating_N(const GeneratorBearing& b) {
  validate_generator_bearing(b);
  const double Z = b.balls, D_mm = b.ball_diameter_m * 1e3;
  // i = 1 row, cos α = 1: (i·cos α)^0.7 = 1.
  return kRatingFactorRadialBall * iso281_fc_radial_ball(gamma_of(b)) * std::pow(Z, 2.0 / 3.0) * ball_size_term(D_mm);
}

double basic_static_load_rating_N(const GeneratorBearing& b) {
  validate_generator_bearing(b);
  const double D_mm = b.ball_diameter_m * 1e3;
  return iso76_f0_radial_ball(gamma_of(b)) * b.balls * D_mm * D_mm;  // i = 1, cos α = 1
}

RacewayRatings raceway_dynamic_load_ratings_N(const GeneratorBearing& b) {
  validate_generator_bearing(b);
  const double g = gamma_of(b), D_mm = b.ball_diameter_m * 1e3, Z = b.balls;
  const double common = kRatingFactorRadialBall * kRacewayConstant * std::pow(g, 0.3) * ball_size_term(D_mm) *
                        std::pow(Z, -1.0 / 3.0);
  const double fi = b.inner_groove_conformity, fo = b.outer_groove_conformity;
  RacewayRatings r;
  r.inner_N = common * std::pow(2 * fi / (2 * fi - 1), 0.41) * std::pow(1 - g, 1.39) / std::cbrt(1 + g);
  r.outer_N = common * std::pow(2 * fo / (2 * fo - 1), 0.41) * std::pow(1 + g, 1.39) / std::cbrt(1 - g);
  return r;
}

BearingLife rating_life_from_ball_loads(const GeneratorBearing& b, const std::vector<double>& Q, LoadFixedTo fixed_to) {
  const RacewayRatings Qc = raceway_dynamic_load_ratings_N(b);
  if (static_cast<int>(Q.size()) != b.balls)
    throw InputError(six_digits(static_cast<double>(Q.size())) + " ball loads for a bearing of " + six_digits(b.balls) +
                     " balls; need one load per ball");
  for (double q : Q)
    if (!(q >= 0)) throw InputError("ball load " + six_digits(q) + " N; must be >= 0 (a ball only pushes)");
  // The raceway that turns relative to the load: cubic mean; the one standing still on it: 10/3 mean.
  const double rotating = power_mean(Q, 3.0), standing = power_mean(Q, 10.0 / 3.0);
  BearingLife L;
  L.inner_equivalent_load_N = fixed_to == LoadFixedTo::kInnerRing ? standing : rotating;
  L.outer_equivalent_load_N = fixed_to == LoadFixedTo::kInnerRing ? rotating : standing;
  L.inner_life_Mrev = raceway_life(Qc.inner_N, L.inner_equivalent_load_N);
  L.outer_life_Mrev = raceway_life(Qc.outer_N, L.outer_equivalent_load_N);
  const double s = std::pow(L.inner_life_Mrev, -kWeibullSlope) + std::pow(L.outer_life_Mrev, -kWeibullSlope);
  L.life_Mrev = s > 0 ? std::pow(s, -1.0 / kWeibullSlope) : std::numeric_limits<double>::infinity();
  return L;
}

double ring_relative_speed_rpm(double input_speed_rpm, double ratio) {
  if (!(std::abs(ratio) > 1.0))
    throw InputError("ratio = " + six_digits(ratio) + "; must satisfy |ratio| > 1 (input speed / output speed, signed)");
  return std::abs(input_speed_rpm * (1.0 - 1.0 / ratio));
}

double life_hours(double life_Mrev, double relative_speed_rpm) {
  if (!(relative_speed_rpm > 0))
    throw InputError("relative ring speed " + six_digits(relative_speed_rpm) + " rpm; must be > 0 for a life in hours");
  return life_Mrev * 1e6 / (60.0 * relative_speed_rpm);
}

double generator_bearing_l10_hours(const GeneratorBearing& b, const std::vector<double>& Q, double input_speed_rpm,
                                   double ratio) {
  return life_hours(rating_life_from_ball_loads(b, Q, LoadFixedTo::kInnerRing).life_Mrev,
                    ring_relative_speed_rpm(input_speed_rpm, ratio));
}

}  // namespace sw
