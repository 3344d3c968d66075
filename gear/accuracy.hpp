#pragma once
// Flank tolerances of a cylindrical gear by ISO 1328-1:2013 (Cylindrical gears — ISO system of flank tolerance
// classification — Part 1), clause 5.3, for tolerance class A (1 finest … 11), d the reference diameter and m_n the
// normal module in mm, values in µm, unrounded (the standard rounds its tables; the model takes the formula):
//   single pitch           f_pT  = (0.001 d + 0.4 m_n + 5) · √2^(A−5)                      (5)
//   cumulative pitch       F_pT  = (0.002 d + 0.55 √d + 0.7 m_n + 12) · √2^(A−5)           (6)
//   profile slope          f_HαT = (0.4 m_n + 0.001 d + 4) · √2^(A−5)                      (7)
//   profile form           f_fαT = (0.55 m_n + 5) · √2^(A−5)                               (8)
//   profile total          F_αT  = √(f_HαT² + f_fαT²)                                      (9)
// The standard's scope is 0.5 ≤ m_n ≤ 70 mm and 5 ≤ d ≤ 15,000 mm; a strain wave gear's teeth are finer (m 0.2–0.7
// mm) and the formulas are then extrapolated (their module terms are small beside the constants): iso1328_scope
// says so for reports.
#include <optional>
#include <string>

namespace sw {

struct FlankTolerances {
  double single_pitch_um = 0;      ///< f_pT
  double cumulative_pitch_um = 0;  ///< F_pT
  double profile_slope_um = 0;     ///< f_HαT
  double profile_form_um = 0;      ///< f_fαT
  double profile_total_um = 0;     ///< F_αT
};

/// ISO 1328-1:2013's tolerances of class `tolerance_class` (1–11) for a gear of reference diameter and module (mm).
/// Throws InputError for a class outside 1–11 or a non-positive size.
FlankTolerances iso1328_tolerances(double reference_diameter_mm, double module_mm, int tolerance_class);

/// Empty when the gear lies in ISO 1328-1:2013's scope; otherwise what lies outside it, in one phrase ("m_n 0.216 mm
/// below the standard's 0.5 mm: the formulas extrapolated").
std::optional<std::string> iso1328_scope(double reference_diameter_mm, double module_mm);

}  // namespace sw
