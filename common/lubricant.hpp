#pragma once
// A lubricant's kinematic viscosity at temperature from its two catalogue viscosities (40 °C and 100 °C), by the
// Walther equation of ASTM D341 (ASTM D341-20, "Standard Practice for Viscosity-Temperature Equations and Charts for
// Liquid Petroleum or Hydrocarbon Products", §5, eq. (1)–(3); the same line as D341-09's charts):
//   log10 log10(ν + 0.7) = A − B·log10 T,      ν in mm²/s, T in kelvin,
// A and B from the two given points. The constant 0.7 is D341's Z = ν + 0.7, valid for ν ≥ 2.0 mm²/s (below that
// D341-20 adds exponential correction terms to Z, not implemented here: a result below 2.0 mm²/s is refused). D341
// holds only where the oil is a homogeneous liquid, between its cloud point and its initial boiling point (D341 §3);
// the caller's temperatures must stay there. A grease is described by its base oil (Palmgren's friction and the film
// models use the base oil's viscosity; the soap's own rheology is not modelled).
//
// Idealisations: a Newtonian oil whose viscosity–temperature line is straight on D341's chart (not for oils thickened
// with polymer viscosity-index improvers, whose curve bends); no pressure or shear dependence.
#include <string>
#include <vector>

#include "common/case_keys.hpp"

namespace sw {

/// An oil or a grease (then: its base oil's viscosities). mm²/s (cSt) as catalogues print them.
struct Lubricant {
  std::string kind = "grease";        ///< "grease" or "oil"
  double viscosity_40C_mm2_s = 0;     ///< kinematic viscosity at 40 °C
  double viscosity_100C_mm2_s = 0;    ///< kinematic viscosity at 100 °C
  double temperature_C = 20;          ///< where it works: the temperature its viscosity is taken at (the case's)
};

/// Lowest kinematic viscosity for which D341's Z = ν + 0.7 holds (ASTM D341-20 §5.1: 2.0 mm²/s).
inline constexpr double kWaltherMinViscosity_mm2_s = 2.0;

/// The [lubricant] table's schema (common/case_keys.hpp); every key but kind is required.
const std::vector<CaseKey<Lubricant>>& lubricant_keys();

/// Checks the lubricant: kind "grease" or "oil"; ν100 ≥ 2.0 mm²/s (D341's range, see above); ν40 > ν100 (an oil thins
/// as it warms); ν40 ≤ 2e7 mm²/s (the top of D341's charts); the temperature above absolute zero. Throws InputError "<where>.<key> = value; expectation",
/// `where` being the key path of the lubricant (e.g. "wave_generator.lubricant"; "lubricant" when empty).
void validate_lubricant(const Lubricant& lubricant, const std::string& where);

/// Kinematic viscosity (mm²/s) at temperature_C by the Walther line through (T1_C, ν1) and (T2_C, ν2), ASTM D341.
/// Preconditions: T1 ≠ T2, both ν ≥ 2.0 mm²/s, temperatures above absolute zero; otherwise InputError. Reproduces
/// the two given points to rounding. Throws InputError when the result falls below 2.0 mm²/s (outside D341's Z).
double walther_kinematic_viscosity_mm2_s(double T1_C, double nu1_mm2_s, double T2_C, double nu2_mm2_s,
                                         double temperature_C);

/// The lubricant's (base oil's) kinematic viscosity (mm²/s) at temperature_C, by ASTM D341 through its 40 °C and
/// 100 °C values. Validates the lubricant (validate_lubricant with where "lubricant") and refuses a result below 2.0
/// mm²/s, like walther_kinematic_viscosity_mm2_s.
double kinematic_viscosity_mm2_s(const Lubricant& lubricant, double temperature_C);

}  // namespace sw
