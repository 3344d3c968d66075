#include "generator/bearing_friction.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "common/error.hpp"
#include "common/format.hpp"
#include "generator/bearing_life.hpp"

namespace sw {
namespace {

/// Palmgren's viscous term switches form at ν·n = 2000 mm²/s·rpm (Palmgren 1959; Harris & Kotzalas vol. 1).
constexpr double kViscousThreshold = 2000.0;
/// Palmgren's viscous-term constants, N·mm with ν in mm²/s, n in rpm, d_m in mm: 1e−7 above, 160e−7 below.
constexpr double kViscousFactor = 1e-7;
constexpr double kViscousFloorFactor = 160e-7;
/// Stribeck's load distribution of a zero-clearance radial ball bearing, Q = Q_max·cos^1.5 ψ (Hertz point contact,
/// load ∝ approach^1.5).
constexpr double kStribeckExponent = 1.5;

/// (1/2π)∫_{−π/2}^{π/2} cos^a ψ dψ = B(1/2, (a+1)/2)/(2π), the load integral of a half-circle zone.
double zone_integral(double a) {
  return std::sqrt(std::numbers::pi) * std::tgamma(0.5 * (a + 1.0)) / std::tgamma(0.5 * a + 1.0) /
         (2.0 * std::numbers::pi);
}

}  // namespace

void validate_palmgren_coefficients(const PalmgrenCoefficients& c, const std::string& where) {
  const std::string at = (where.empty() ? std::string("palmgren") : where) + ".";
  if (!(c.f0 > 0 && c.f0 <= 10))
    throw InputError(at + "f0 = " + six_digits(c.f0) + "; must be in (0, 10] (deep-groove ball bearings: 0.7-2 grease, 2 oil bath, 4 oil jet)");
  if (!(c.z > 0 && c.z <= 0.01))
    throw InputError(at + "z = " + six_digits(c.z) + "; must be in (0, 0.01] (deep-groove ball bearings: 0.0004-0.0006)");
  if (!(c.y > 0 && c.y <= 1))
    throw InputError(at + "y = " + six_digits(c.y) + "; must be in (0, 1] (deep-groove ball bearings: 0.55)");
}

double palmgren_equivalent_load_N(const GeneratorBearing& b, const std::vector<double>& Q, double y) {
  validate_generator_bearing(b);
  if (!(y > 0 && y <= 1)) throw InputError("palmgren.y = " + six_digits(y) + "; must be in (0, 1]");
  if (static_cast<int>(Q.size()) != b.balls)
    throw InputError(six_digits(static_cast<double>(Q.size())) + " ball loads for a bearing of " + six_digits(b.balls) +
                     " balls; need one load per ball");
  double sum = 0;
  for (double q : Q) {
    if (!(q >= 0)) throw InputError("ball load " + six_digits(q) + " N; must be >= 0 (a ball only pushes)");
    sum += std::pow(q, 1.0 + y);
  }
  const double Z = b.balls;
  const double J_r = zone_integral(kStribeckExponent + 1.0);          // Σ Q cos ψ = Z·Q_max·J_r
  const double J_p = zone_integral(kStribeckExponent * (1.0 + y));    // Σ Q^(1+y) = Z·Q_max^(1+y)·J_p
  return Z * J_r * std::pow(sum / (Z * J_p), 1.0 / (1.0 + y));
}

BearingFrictionMoment palmgren_friction_moment(const GeneratorBearing& b, const std::vector<double>& Q,
                                               double relative_speed_rpm, double nu, const PalmgrenCoefficients& c) {
  validate_palmgren_coefficients(c, "");
  if (!(nu > 0)) throw InputError("lubricant viscosity " + six_digits(nu) + " mm^2/s; must be > 0");
  if (!std::isfinite(relative_speed_rpm)) throw InputError("relative ring speed " + six_digits(relative_speed_rpm) + " rpm; must be finite");
  BearingFrictionMoment m;
  m.equivalent_load_N = palmgren_equivalent_load_N(b, Q, c.y);
  m.static_rating_N = basic_static_load_rating_N(b);
  const double dm_mm = 2.0 * b.pitch_radius_m * 1e3, dm3 = dm_mm * dm_mm * dm_mm;
  const double n = std::abs(relative_speed_rpm);
  double M0_Nmm = 0;
  if (n > 0)
    M0_Nmm = nu * n >= kViscousThreshold ? kViscousFactor * c.f0 * std::pow(nu * n, 2.0 / 3.0) * dm3
                                         : kViscousFloorFactor * c.f0 * dm3;
  const double f1 = c.z * std::pow(m.equivalent_load_N / m.static_rating_N, c.y);
  const double M1_Nmm = f1 * m.equivalent_load_N * dm_mm;
  m.viscous_Nm = M0_Nmm * 1e-3;
  m.load_Nm = M1_Nmm * 1e-3;
  m.total_Nm = m.viscous_Nm + m.load_Nm;
  return m;
}

double palmgren_breakaway_moment_Nm(const GeneratorBearing& b, const std::vector<double>& Q,
                                    const PalmgrenCoefficients& c) {
  // n = 0: no viscous term; ν is then irrelevant (any positive value).
  return palmgren_friction_moment(b, Q, 0.0, 1.0, c).load_Nm;
}

}  // namespace sw
