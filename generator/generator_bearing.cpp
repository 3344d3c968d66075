#include "generator/generator_bearing.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "common/error.hpp"
#include "common/format.hpp"

namespace sw {
namespace {

[[noreturn]] void reject(const std::string& file, const std::string& key, double value, const std::string& expectation) {
  throw InputError((file.empty() ? "" : file + ": ") + "wave_generator.bearing." + key + " = " + six_digits(value) + "; " +
                   expectation);
}

/// Hertz point contact of two bodies of one material with principal relative curvatures ρ_x, ρ_y (1/m, aligned
/// axes) under normal load Q: exact, with the complete elliptic integrals (see the header).
HertzPointContact hertz_point_contact(double rho_x, double rho_y, double E_star, double Q) {
  HertzPointContact c;
  c.curvature_sum_per_m = rho_x + rho_y;
  c.curvature_difference = std::abs(rho_x - rho_y) / c.curvature_sum_per_m;
  const double A = 0.5 * std::min(rho_x, rho_y), B = 0.5 * std::max(rho_x, rho_y);
  if (Q <= 0) return c;
  if (B - A <= 1e-12 * B) {  // circular contact: a³ = 3QR/(4E*), δ = a²/R with 1/R = 2A
    const double R = 0.5 / A;
    c.semi_major_m = c.semi_minor_m = std::cbrt(3.0 * Q * R / (4.0 * E_star));
    c.approach_m = c.semi_major_m * c.semi_major_m / R;
    return c;
  }
  // B/A as a function of e is increasing from 1 (e = 0) to infinity (e = 1): bisection on e (60 halvings: e to
  // 1e-18, far below the 1e-15 the integrals carry).
  const double ratio = B / A;
  auto g = [](double e) {
    const double K = std::comp_ellint_1(e), E = std::comp_ellint_2(e);
    return (E / (1.0 - e * e) - K) / (K - E);
  };
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 200 && hi - lo > 1e-16; ++it) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < ratio ? lo : hi) = mid;
  }
  const double e = 0.5 * (lo + hi);
  const double K = std::comp_ellint_1(e), E = std::comp_ellint_2(e);
  const double a3 = 3.0 * Q * (K - E) / (2.0 * std::numbers::pi * E_star * A * e * e);
  c.eccentricity = e;
  c.semi_major_m = std::cbrt(a3);
  c.semi_minor_m = c.semi_major_m * std::sqrt(1.0 - e * e);
  c.approach_m = A * e * e * c.semi_major_m * c.semi_major_m * K / (K - E);
  return c;
}

double contact_modulus(const GeneratorBearing& b) {
  return b.youngs_modulus_Pa / (2.0 * (1.0 - b.poisson_ratio * b.poisson_ratio));
}

}  // namespace

double bearing_pitch_radius_m(double bore_radius_m, double ball_diameter_m) {
  return bore_radius_m - (kOuterRingWallPerBallDiameter + 0.5) * ball_diameter_m;
}

const std::vector<CaseKey<GeneratorBearing>>& generator_bearing_keys() {
  using B = GeneratorBearing;
  // A conformity at or below 0.5 makes the groove tighter than the ball; at 1 and beyond the groove is flatter than
  // any bearing's (Harris & Kotzalas ch. 2: deep-groove bearings 0.515–0.53).
  const auto conformity = within(0.5, 1, true, true, "groove radius / ball diameter; deep-groove bearings 0.515-0.53");
  static const std::vector<CaseKey<B>> keys = {
      integer_key<B>("balls", &B::balls, at_least(3), "the bearing's balls; they fit on the pitch circle")
          .with_default(kRequired),
      number_key<B>("ball_diameter_mm", &B::ball_diameter_m, 1e-3, "mm", above(0),
                    "D; the pitch radius is the bore's less 0.75 D")
          .with_default(kRequired),
      number_key<B>("inner_groove_conformity", &B::inner_groove_conformity, 1, "", conformity,
                    "f_i, the inner race's (on the cam) groove radius / D"),
      number_key<B>("outer_groove_conformity", &B::outer_groove_conformity, 1, "", conformity,
                    "f_o, the flexible outer race's groove radius / D"),
  };
  return keys;
}

void validate_generator_bearing(const GeneratorBearing& b, const std::string& file) {
  check_key_ranges(b, generator_bearing_keys(), "wave_generator.bearing", file.empty() ? "" : file + ": ");
  const double D = b.ball_diameter_m;
  if (!(b.pitch_radius_m > D))
    reject(file, "ball_diameter_mm", D * 1e3,
           "must be < the pitch radius " + six_digits(b.pitch_radius_m * 1e3) +
               " mm (bore radius less 0.75 ball diameters): the balls do not fit inside the flexspline");
  if (!(b.balls * D < 2.0 * std::numbers::pi * b.pitch_radius_m))
    reject(file, "balls", b.balls,
           "must be < 2*pi*pitch radius / ball diameter = " +
               six_digits(std::floor(2.0 * std::numbers::pi * b.pitch_radius_m / D)) + " (the balls must fit on the circle)");
  if (!(b.youngs_modulus_Pa > 0)) reject(file, "youngs_modulus_Pa", b.youngs_modulus_Pa, "must be > 0");
  if (!(b.poisson_ratio > -1.0 && b.poisson_ratio < 0.5)) reject(file, "poisson_ratio", b.poisson_ratio, "must be in (-1, 0.5)");
}

HertzPointContact inner_race_contact(const GeneratorBearing& b, double Q) {
  validate_generator_bearing(b);
  const double D = b.ball_diameter_m;
  const double r_race = b.pitch_radius_m - 0.5 * D;  // groove bottom of the inner race: convex in the rolling plane
  return hertz_point_contact(2.0 / D + 1.0 / r_race, 2.0 / D - 1.0 / (b.inner_groove_conformity * D),
                             contact_modulus(b), Q);
}

HertzPointContact outer_race_contact(const GeneratorBearing& b, double Q) {
  validate_generator_bearing(b);
  const double D = b.ball_diameter_m;
  const double r_race = b.pitch_radius_m + 0.5 * D;  // groove bottom of the outer race: concave in the rolling plane
  return hertz_point_contact(2.0 / D - 1.0 / r_race, 2.0 / D - 1.0 / (b.outer_groove_conformity * D),
                             contact_modulus(b), Q);
}

double ball_approach_m(const GeneratorBearing& b, double Q) {
  if (!(Q >= 0)) throw InputError("ball load " + six_digits(Q) + " N; must be >= 0 (a ball only pushes)");
  return inner_race_contact(b, Q).approach_m + outer_race_contact(b, Q).approach_m;
}

double ball_approach_derivative_m_per_N(const GeneratorBearing& b, double Q) {
  if (!(Q > 0)) {
    if (Q == 0) return std::numeric_limits<double>::infinity();
    throw InputError("ball load " + six_digits(Q) + " N; must be >= 0 (a ball only pushes)");
  }
  return 2.0 / 3.0 * ball_approach_m(b, Q) / Q;
}

}  // namespace sw
