#include "gear/tooth_root.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "gear/tooth_profile.hpp"

namespace sw {

namespace {

[[noreturn]] void bad_input(const std::string& field, double value, const std::string& expectation) {
  std::ostringstream s;
  s << "tooth root: " << field << " = " << value << "; " << expectation;
  throw InputError(s.str());
}

void validate_teeth(const SpurTeeth& g) {
  if (g.teeth < 5) bad_input("teeth", g.teeth, "must be >= 5");
  if (!(g.module_m > 0)) bad_input("module_m", g.module_m, "must be > 0");
  const double alpha_deg = g.pressure_angle_rad * 180.0 / kPi;
  if (!(alpha_deg > 5.0 && alpha_deg < 45.0)) bad_input("pressure_angle_deg", alpha_deg, "must be in (5, 45)");
  if (!(g.addendum_coefficient > 0)) bad_input("addendum_coefficient", g.addendum_coefficient, "must be > 0");
  if (!(g.tool.addendum_coefficient > 0)) bad_input("tool.addendum_coefficient", g.tool.addendum_coefficient, "must be > 0");
  if (!(g.tool.tip_radius_coefficient >= 0))
    bad_input("tool.tip_radius_coefficient", g.tool.tip_radius_coefficient, "must be >= 0");
  // Half the tool's flat tip land, E/m of ISO 6336-3:2006 6.2: the tip radius must fit on the tool's tooth.
  const double a = g.pressure_angle_rad;
  const double land = kPi / 4.0 - g.tool.addendum_coefficient * std::tan(a) + g.tool.protuberance_coefficient / std::cos(a) -
                      (1.0 - std::sin(a)) * g.tool.tip_radius_coefficient / std::cos(a);
  if (land < 0)
    bad_input("tool.tip_radius_coefficient", g.tool.tip_radius_coefficient,
        "does not fit on the tool's tip (half tip land E/m = " + std::to_string(land) + " < 0); make it smaller");
}

/// Dietrich's stress correction factor Y_S, ISO 6336-3:2006 clause 7; q_s and whether it lies in the formula's
/// range 1 ≤ q_s < 8 go to the form.
void set_stress_correction(ToothRootForm& r) {
  const double L = r.critical_chord_m / r.bending_arm_m;
  r.notch_parameter = r.critical_chord_m / (2.0 * r.fillet_radius_m);
  r.notch_parameter_in_range = r.notch_parameter >= 1.0 && r.notch_parameter < 8.0;
  r.stress_correction = (1.2 + 0.13 * L) * std::pow(r.notch_parameter, 1.0 / (1.21 + 2.3 / L));
}

}  // namespace

double spur_tip_radius_m(const SpurTeeth& g, bool internal) {
  const double m = g.module_m;
  return internal ? m * (g.teeth / 2.0 - g.addendum_coefficient + g.profile_shift)
                  : m * (g.teeth / 2.0 + g.addendum_coefficient + g.profile_shift);
}

double spur_root_radius_m(const SpurTeeth& g, bool internal) {
  const double m = g.module_m;
  return internal ? m * (g.teeth / 2.0 + g.tool.addendum_coefficient + g.profile_shift)
                  : m * (g.teeth / 2.0 - g.tool.addendum_coefficient + g.profile_shift);
}

double spur_contact_ratio(const SpurTeeth& p, const SpurTeeth& w) {
  validate_teeth(p);
  validate_teeth(w);
  const double a = p.pressure_angle_rad, m = p.module_m;
  const int zs = p.teeth + w.teeth;
  const double alpha_w = inverse_involute(involute_function(a) + 2.0 * std::tan(a) * (p.profile_shift + w.profile_shift) / zs);
  const double centre_distance = m * zs / 2.0 * std::cos(a) / std::cos(alpha_w);
  auto approach = [&](const SpurTeeth& g) {
    const double ra = spur_tip_radius_m(g, false), rb = m * g.teeth / 2.0 * std::cos(a);
    return std::sqrt(ra * ra - rb * rb);
  };
  const double base_pitch = kPi * m * std::cos(a);
  return (approach(p) + approach(w) - centre_distance * std::sin(alpha_w)) / base_pitch;
}

double single_pair_outer_radius_m(const SpurTeeth& g, double contact_ratio, bool internal) {
  validate_teeth(g);
  if (!(contact_ratio >= 1.0)) bad_input("contact_ratio", contact_ratio, "must be >= 1");
  const double a = g.pressure_angle_rad, m = g.module_m;
  const double rb = m * g.teeth / 2.0 * std::cos(a), ra = spur_tip_radius_m(g, internal);
  if (!(ra > rb)) bad_input("addendum_coefficient", g.addendum_coefficient, "puts the tip inside the base circle");
  const double base_pitch = kPi * m * std::cos(a);
  const double roll = std::sqrt(ra * ra - rb * rb) + (internal ? 1.0 : -1.0) * base_pitch * (contact_ratio - 1.0);
  if (roll < 0) bad_input("contact_ratio", contact_ratio, "puts the single-pair point below the base circle");
  return std::hypot(roll, rb);
}

ToothRootForm external_root_form(const SpurTeeth& g, double load_radius_m) {
  validate_teeth(g);
  const double m = g.module_m, a = g.pressure_angle_rad, z = g.teeth, x = g.profile_shift;
  const double hfP = g.tool.addendum_coefficient, rho = g.tool.tip_radius_coefficient;  // in modules
  const double rb = m * z / 2.0 * std::cos(a), ra = spur_tip_radius_m(g, false);
  if (!(load_radius_m > rb && load_radius_m <= ra * (1.0 + 1e-12)))
    bad_input("load_radius_mm", load_radius_m * 1e3,
        "must lie on the flank, in (base radius " + std::to_string(rb * 1e3) + ", tip radius " + std::to_string(ra * 1e3) + "] mm");
  // ISO 6336-3:2006 6.2: E, G, H and the 30° tangent angle ϑ (lengths in modules).
  const double E = kPi / 4.0 - hfP * std::tan(a) + g.tool.protuberance_coefficient / std::cos(a) -
                   (1.0 - std::sin(a)) * rho / std::cos(a);
  const double G = rho - hfP + x;
  const double H = 2.0 / z * (kPi / 2.0 - E) - kPi / 3.0;
  auto f = [&](double t) { return t - 2.0 * G / z * std::tan(t) + H; };
  // f(0) = H; f increases up to cos²ϑ = 2G/z when G > 0 (beyond, a second, spurious root near π/2), else to π/2.
  double lo = 0.0, hi = kPi / 2.0 - 1e-9;
  if (G > 0) {
    if (2.0 * G / z >= 1.0) bad_input("profile_shift", x, "too large for the tooth count: no 30° tangent point in the fillet");
    hi = std::acos(std::sqrt(2.0 * G / z));
  }
  if (!(f(lo) < 0 && f(hi) > 0))
    bad_input("profile_shift", x, "leaves no 30° tangent point on the root fillet (ISO 6336-3 6.2 does not apply)");
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0 ? lo : hi) = mid;
  }
  const double t = 0.5 * (lo + hi);
  ToothRootForm r;
  r.tangent_angle_rad = t;
  r.critical_chord_m = m * (z * std::sin(kPi / 3.0 - t) + std::sqrt(3.0) * (G / std::cos(t) - rho));
  r.fillet_radius_m = m * (rho + 2.0 * G * G / (std::cos(t) * (z * std::cos(t) * std::cos(t) - 2.0 * G)));
  // Load at r_en: α_en, γ_e, α_Fen and the arm h_Fe.
  const double alpha_en = std::acos(rb / load_radius_m);
  const double gamma_e = (kPi / 2.0 + 2.0 * x * std::tan(a)) / z + involute_function(a) - involute_function(alpha_en);
  r.load_angle_rad = alpha_en - gamma_e;
  r.bending_arm_m = 0.5 * m *
                    ((std::cos(gamma_e) - std::sin(gamma_e) * std::tan(r.load_angle_rad)) * 2.0 * load_radius_m / m -
                     z * std::cos(kPi / 3.0 - t) - G / std::cos(t) + rho);
  if (!(r.critical_chord_m > 0)) bad_input("profile_shift", x, "gives a critical chord s_Fn <= 0 (undercut tooth)");
  if (!(r.bending_arm_m > 0)) bad_input("load_radius_mm", load_radius_m * 1e3, "gives a bending arm h_Fe <= 0");
  if (!(r.fillet_radius_m > 0)) bad_input("tool.tip_radius_coefficient", rho, "gives a fillet radius rho_F <= 0");
  // Y_F of ISO 6336-3:2006 6.2 and Y_S of clause 7.
  const double sm = r.critical_chord_m / m;
  r.form_factor = 6.0 * (r.bending_arm_m / m) * std::cos(r.load_angle_rad) / (sm * sm * std::cos(a));
  set_stress_correction(r);
  return r;
}

ToothRootForm internal_root_form(const SpurTeeth& g, double load_radius_m) {
  validate_teeth(g);
  const double m = g.module_m, a = g.pressure_angle_rad;
  const double hfP = g.tool.addendum_coefficient * m, rho = g.tool.tip_radius_coefficient * m;
  const double spr = g.tool.protuberance_coefficient * m;
  const double ra = spur_tip_radius_m(g, true), rf = spur_root_radius_m(g, true);
  const double rb = m * g.teeth / 2.0 * std::cos(a);
  if (!(ra > rb)) bad_input("addendum_coefficient", g.addendum_coefficient, "puts the internal tip inside the base circle");
  if (!(load_radius_m >= ra * (1.0 - 1e-12) && load_radius_m < rf))
    bad_input("load_radius_mm", load_radius_m * 1e3,
        "must lie on the internal tooth, in [tip radius " + std::to_string(ra * 1e3) + ", root radius " +
            std::to_string(rf * 1e3) + ") mm");
  if (!(rho > 0)) bad_input("tool.tip_radius_coefficient", 0.0, "must be > 0 for an internal gear (it is the fillet radius)");
  // The rack-shaped internal tooth (ISO 6336-3:2006 6.2, internal gears): the 30° tangent touches the root fillet of
  // radius ρ_fP (centre at depth ρ_fP, tangent to the root line and the flank) where its normal makes 30° with the
  // root line: half-chord = flank offset of the centre − ρ cos 30°, depth ρ (1 − sin 30°).
  constexpr double kTangent = kPi / 6.0;
  ToothRootForm r;
  r.critical_chord_m = 2.0 * (kPi * m / 4.0 + (hfP - rho) * std::tan(a) + (rho - spr) / std::cos(a) - rho * std::cos(kTangent));
  r.fillet_radius_m = rho;
  r.load_angle_rad = a;
  const double depth = rf - load_radius_m;                               // y_e, from the root line
  const double half_thickness = kPi * m / 4.0 + (hfP - depth) * std::tan(a);  // s_e at that depth
  r.bending_arm_m = depth - half_thickness * std::tan(a) - rho * (1.0 - std::sin(kTangent));
  if (!(r.critical_chord_m > 0)) bad_input("tool.tip_radius_coefficient", g.tool.tip_radius_coefficient, "gives s_Fn <= 0");
  if (!(r.bending_arm_m > 0)) bad_input("load_radius_mm", load_radius_m * 1e3, "gives a bending arm h_Fe <= 0");
  const double sm = r.critical_chord_m / m;
  r.form_factor = 6.0 * (r.bending_arm_m / m) * std::cos(r.load_angle_rad) / (sm * sm * std::cos(a));
  set_stress_correction(r);
  return r;
}

double rim_thickness_factor(double rim_thickness_m, double tooth_depth_m) {
  if (!(tooth_depth_m > 0)) bad_input("tooth_depth_mm", tooth_depth_m * 1e3, "must be > 0");
  if (rim_thickness_m == 0) return 1.0;  // solid gear
  const double ratio = rim_thickness_m / tooth_depth_m;
  // ISO 6336-3:2006 clause 8, external gears.
  if (!(ratio > kRimBackupRatioMin))
    bad_input("rim thickness / tooth depth s_R/h_t", ratio, "must be > 0.5 (ISO 6336-3's limit for Y_B)");
  if (ratio >= 1.2) return 1.0;
  return 1.6 * std::log(2.242 / ratio);
}

double nominal_root_stress_Pa(const ToothRootForm& form, double module_m, double tangential_force_N,
                              double face_width_m, const RootStressFactors& y) {
  if (!(module_m > 0)) bad_input("module_m", module_m, "must be > 0");
  if (!(face_width_m > 0)) bad_input("face_width_mm", face_width_m * 1e3, "must be > 0");
  if (!(tangential_force_N >= 0)) bad_input("tangential_force_N", tangential_force_N, "must be >= 0");
  // ISO 6336-3:2006 method B: σ_F0 = F_t/(b m_n) Y_F Y_S Y_β Y_B Y_DT.
  return tangential_force_N / (face_width_m * module_m) * form.form_factor * form.stress_correction * y.helix *
         y.rim_thickness * y.deep_tooth;
}

double tangential_force_at_root_stress_N(const ToothRootForm& form, double module_m, double allowable_stress_Pa,
                                         double face_width_m, const RootStressFactors& y) {
  if (!(allowable_stress_Pa > 0)) bad_input("allowable_stress_MPa", allowable_stress_Pa * 1e-6, "must be > 0");
  const double stress_per_newton = nominal_root_stress_Pa(form, module_m, 1.0, face_width_m, y);
  if (!(stress_per_newton > 0)) bad_input("form_factor * stress_correction", form.form_factor * form.stress_correction, "must be > 0");
  return allowable_stress_Pa / stress_per_newton;
}

SpurTeeth flexspline_teeth(const GearParams& g, double tool_tip_radius_coefficient) {
  validate_gear(g);
  SpurTeeth t;
  t.teeth = g.teeth_flexspline;
  t.module_m = g.module_m;
  t.pressure_angle_rad = g.pressure_angle_rad;
  t.profile_shift = g.profile_shift_flexspline;
  t.addendum_coefficient = g.addendum_coefficient_flexspline;
  t.tool.addendum_coefficient = g.dedendum_coefficient_flexspline;
  t.tool.tip_radius_coefficient = tool_tip_radius_coefficient;
  return t;
}

SpurTeeth circular_spline_teeth(const GearParams& g, double tool_tip_radius_coefficient) {
  validate_gear(g);
  SpurTeeth t;
  t.teeth = g.teeth_circular;
  t.module_m = g.module_m;
  t.pressure_angle_rad = g.pressure_angle_rad;
  t.profile_shift = g.profile_shift_circular;
  t.addendum_coefficient = g.addendum_coefficient_circular;
  t.tool.addendum_coefficient = g.dedendum_coefficient_circular;
  t.tool.tip_radius_coefficient = tool_tip_radius_coefficient;
  return t;
}

}  // namespace sw
