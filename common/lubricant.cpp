#include "common/lubricant.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "common/error.hpp"

namespace sw {
namespace {

/// 0 °C in kelvin (SI definition).
constexpr double kZeroCelsius_K = 273.15;
/// ASTM D341-20 eq. (2) for ν ≥ 2.0 mm²/s: Z = ν + 0.7.
constexpr double kWaltherOffset_mm2_s = 0.7;
/// The top of ASTM D341's charts (2·10⁷ mm²/s).
constexpr double kWaltherMaxViscosity_mm2_s = 2e7;

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

double loglog(double nu) { return std::log10(std::log10(nu + kWaltherOffset_mm2_s)); }

}  // namespace

const std::vector<CaseKey<Lubricant>>& lubricant_keys() {
  using L = Lubricant;
  static const std::vector<CaseKey<L>> keys = {
      choice_key<L>("kind", &L::kind, {{"grease", std::string("grease")}, {"oil", std::string("oil")}},
                    "a grease (described by its base oil) or an oil"),
      number_key<L>("viscosity_40C_mm2_s", &L::viscosity_40C_mm2_s, 1, "mm^2/s",
                    within(-std::numeric_limits<double>::infinity(), kWaltherMaxViscosity_mm2_s, false, false,
                           "the top of ASTM D341's charts"),
                    "the (base) oil's kinematic viscosity at 40 C, > viscosity_100C_mm2_s")
          .with_default(kRequired),
      number_key<L>("viscosity_100C_mm2_s", &L::viscosity_100C_mm2_s, 1, "mm^2/s",
                    at_least(kWaltherMinViscosity_mm2_s, "ASTM D341's Walther equation holds from 2.0 mm^2/s"),
                    "the (base) oil's kinematic viscosity at 100 C")
          .with_default(kRequired),
      number_key<L>("temperature_C", &L::temperature_C, 1, "C", above(-kZeroCelsius_K, "absolute zero"),
                    "where it works: the temperature its viscosity is taken at (ASTM D341)")
          .with_default(kRequired),
  };
  return keys;
}

void validate_lubricant(const Lubricant& l, const std::string& where) {
  const std::string table = where.empty() ? std::string("lubricant") : where;
  if (l.kind != "grease" && l.kind != "oil")
    throw InputError(table + ".kind = \"" + l.kind + "\"; must be \"grease\" or \"oil\"");
  check_key_ranges(l, lubricant_keys(), table);
  if (!(l.viscosity_40C_mm2_s > l.viscosity_100C_mm2_s))
    throw InputError(table + ".viscosity_40C_mm2_s = " + num(l.viscosity_40C_mm2_s) +
                     "; must be > viscosity_100C_mm2_s = " + num(l.viscosity_100C_mm2_s) +
                     " (an oil thins as it warms; for a grease give its base oil's viscosities)");
}

double walther_kinematic_viscosity_mm2_s(double T1_C, double nu1, double T2_C, double nu2, double T_C) {
  for (double T : {T1_C, T2_C, T_C})
    if (!(T > -kZeroCelsius_K))
      throw InputError("temperature " + num(T) + " C; must be above absolute zero (-273.15 C)");
  for (double nu : {nu1, nu2})
    if (!(nu >= kWaltherMinViscosity_mm2_s && nu <= kWaltherMaxViscosity_mm2_s))
      throw InputError("kinematic viscosity " + num(nu) + " mm^2/s; must be in [2, 2e7] (ASTM D341's range)");
  if (T1_C == T2_C) throw InputError("the two viscosity temperatures are equal (" + num(T1_C) + " C); need two");
  const double x1 = std::log10(T1_C + kZeroCelsius_K), x2 = std::log10(T2_C + kZeroCelsius_K);
  const double B = (loglog(nu1) - loglog(nu2)) / (x2 - x1);  // log log Z = A − B log T
  const double A = loglog(nu1) + B * x1;
  const double nu = std::pow(10.0, std::pow(10.0, A - B * std::log10(T_C + kZeroCelsius_K))) - kWaltherOffset_mm2_s;
  if (!(nu >= kWaltherMinViscosity_mm2_s))
    throw InputError("kinematic viscosity at " + num(T_C) + " C comes out " + num(nu) +
                     " mm^2/s, below 2.0 mm^2/s where ASTM D341's Z = nu + 0.7 holds; the temperature is too high for "
                     "this oil");
  return nu;
}

double kinematic_viscosity_mm2_s(const Lubricant& l, double T_C) {
  validate_lubricant(l, "lubricant");
  return walther_kinematic_viscosity_mm2_s(40.0, l.viscosity_40C_mm2_s, 100.0, l.viscosity_100C_mm2_s, T_C);
}

}  // namespace sw
