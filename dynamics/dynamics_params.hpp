#pragma once
// The case file's [dynamics] table, SI units, and its schema. Header-only and dependent on the standard library
// (and common/case_keys.hpp) alone, so that io/case.hpp can hold it without depending on the dynamics module.
// Millimetre keys of the file are converted once by the case parser; every key has the default written here.
#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "common/case_keys.hpp"

namespace sw {

/// Which body is held, which one is driven at the prescribed speed and which one carries the load torque.
///   cs_fixed: circular spline fixed, wave generator driven, flexspline output (the usual reducer)
///   fs_fixed: flexspline (its flange) fixed, wave generator driven, circular spline output
///   wg_fixed: wave generator fixed, flexspline (its flange) driven, circular spline output
///   all_free: nothing fixed; wave generator driven, flexspline output with the load torque, circular spline free against
///             a viscous brake (the brake gives the two-degree-of-freedom differential its steady state)
enum class DynamicsConfiguration { CsFixed, FsFixed, WgFixed, AllFree };

/// Ramp shape of drive speed and load torque.
///   Paper: the seed paper's two-parabola STEP, with its printed typo corrected (second half 1 - ½((t2-t)/(t2-t1))²,
///          t1 the midpoint): C¹ continuous. Cubic: the multibody codes' STEP, Δ²(3 - 2Δ).
enum class RampShape { Paper, Cubic };

/// How the tooth pairs move. Moving: every tooth travels through the mesh with the generator's rotation relative to the
/// flexspline (clearances from the backlash module at the tooth's current angle). Frozen: the pairs of generator angle
/// 0 stay where they are (the passing of teeth only through the optional k(t)): the seed paper's model, the reference
/// the moving mesh's checks reduce to (dynamics/README.md).
enum class PairMotion { Moving, Frozen };
/// Stiffness of a moving pair. Teeth: the loaded contact's tooth-pair compliance (bending, foundation and flattening of
/// both teeth at the contact radius, gear/tooth_stiffness.hpp; linear). Constant: the paper's k·δ^m1 with k(t).
enum class PairStiffness { Teeth, Constant };
/// What joins the moving pairs. Fem: the flexspline body's condensed compliance of the loaded contact (the pairs and
/// the generator's stations coupled through the rim; the body's torsion is in it). Rigid: independent pairs.
enum class RimCoupling { Fem, Rigid };

struct DynamicsParams {
  DynamicsConfiguration configuration = DynamicsConfiguration::CsFixed;  ///< key `configuration`
  RampShape ramp_shape = RampShape::Paper;                               ///< key `ramp` = "paper" | "cubic"
  PairMotion pair_motion = PairMotion::Moving;          ///< key `pairs` = "moving" | "frozen"
  PairStiffness pair_stiffness = PairStiffness::Teeth;  ///< key `pair_stiffness` = "teeth" | "constant" (moving pairs)
  RimCoupling rim = RimCoupling::Fem;                   ///< key `rim` = "fem" | "rigid" (moving pairs)
  int compliance_phases = 8;   ///< rim = "fem": generator phases per tooth pitch at which the body compliance is solved
                               ///< (8: the slow run meets the loaded contact within 1 %; 4 gave 1.03 %)
  /// The solution is sampled this many times per output step, low-passed and decimated, so the contact forces' kinks
  /// do not alias into the spectra (1: plain samples, which alias whatever lies above the output's Nyquist frequency).
  int oversampling = 8;

  double drive_speed_rpm = 1000.0;     ///< final speed of the driven body, > 0
  double drive_ramp_start_s = 0.0;     ///< ramp from 0 ...
  double drive_ramp_end_s = 0.01;      ///< ... to drive_speed_rpm, > start
  double load_torque_Nm = 100.0;       ///< final load on the output body, >= 0, always resisting its motion
  double load_ramp_start_s = 0.01;
  double load_ramp_end_s = 0.02;       ///< > load_ramp_start_s

  // Tooth-pair contact f = k·δ^m1 + c·δ̇·|δ̇|^m2·δ^m3 for δ > 0 (clamped at 0: teeth push, never pull).
  double stiffness_N_per_m = 8.0e7;              ///< k0 (for m1 = 1: N/m; generally N/m^m1), > 0
  double stiffness_variation_N_per_m = 0.0;      ///< Δk in k(t) = k0 + Δk·sin(2π f_m t + φ), 0 <= Δk < k0
  double stiffness_phase_deg = 0.0;              ///< φ
  double damping_Ns_per_m = 1.0e3;               ///< c, >= 0
  double exponent_stiffness = 1.0;               ///< m1 >= 1
  double exponent_damping = 0.0;                 ///< m2 >= 0
  double exponent_indentation = 0.0;             ///< m3 >= 0

  // Flexspline torsional compliance between the toothed rim and the output flange (0 = one rigid body).
  double flexspline_compliance_rad_per_Nm = 0.0;      ///< C_τ (e.g. FEM result.json compliance_rad_per_Nm), >= 0
  double flexspline_torsion_damping_Nms_per_rad = 0.0;///< viscous damping in parallel with the spring 1/C_τ, >= 0

  /// all_free only: viscous brake on the circular spline, > 0; it reacts the load, so the circular spline creeps at
  /// ω_c = (z_c/z_f)·T/b, and it must exceed (z_c/z_f)²·T/(ω_w·(z_c/z_f − 1)) for the load to resist the flexspline.
  double circular_spline_drag_Nms_per_rad = 1000.0;
  double load_inertia_kgm2 = 0.0;        ///< added to the output body, >= 0
  /// Drag on the output body (bearings, seals, tooth friction lumped): −(T_c·tanh(ω/ω_s) + b·ω). SPEC's drag_torque.
  double output_drag_coulomb_Nm = 0.0;            ///< T_c >= 0
  double output_drag_viscous_Nms_per_rad = 0.0;   ///< b >= 0
  double drag_smoothing_rad_per_s = 1.0e-3;       ///< ω_s > 0: the Coulomb step is smoothed over this speed
  double circular_spline_outer_radius_m = 0.0;  ///< 0 = pitch radius + 2.25·module + 0.15·pitch radius
  double circular_spline_width_m = 0.0;         ///< 0 = flexspline.rim_width
  double base_clearance_m = 0.0;         ///< approximate clearance model only (until kinematics/ supplies clearances)

  double duration_s = 0.1;               ///< simulated time, > 0
  double output_step_s = 1.0e-5;        ///< sampling of dynamics.csv, > 0
  double steady_from_s = 0.05;           ///< start of the steady window used for means, balances and spectra
  double relative_tolerance = 1.0e-8;    ///< integrator (CVODE BDF) local error control
  double absolute_tolerance_rad = 1.0e-13;  ///< on the angles' deviation from the kinematic motion
};

/// Case-file spelling of a configuration ("cs_fixed", ...).
inline const char* to_string(DynamicsConfiguration c) {
  switch (c) {
    case DynamicsConfiguration::CsFixed: return "cs_fixed";
    case DynamicsConfiguration::FsFixed: return "fs_fixed";
    case DynamicsConfiguration::WgFixed: return "wg_fixed";
    case DynamicsConfiguration::AllFree: return "all_free";
  }
  return "?";
}

inline const char* to_string(RampShape r) { return r == RampShape::Paper ? "paper" : "cubic"; }
inline const char* to_string(PairMotion m) { return m == PairMotion::Moving ? "moving" : "frozen"; }
inline const char* to_string(PairStiffness k) { return k == PairStiffness::Teeth ? "teeth" : "constant"; }
inline const char* to_string(RimCoupling r) { return r == RimCoupling::Fem ? "fem" : "rigid"; }

/// Inverse of to_string(); nullopt for an unknown spelling (the parser names the allowed ones).
inline std::optional<DynamicsConfiguration> parse_configuration(const std::string& s) {
  for (auto c : {DynamicsConfiguration::CsFixed, DynamicsConfiguration::FsFixed, DynamicsConfiguration::WgFixed,
                 DynamicsConfiguration::AllFree})
    if (s == to_string(c)) return c;
  return std::nullopt;
}

inline std::optional<RampShape> parse_ramp_shape(const std::string& s) {
  if (s == "paper") return RampShape::Paper;
  if (s == "cubic") return RampShape::Cubic;
  return std::nullopt;
}

/// The case-file words of enumeration values, as to_string spells them (a choice key's words).
template <class E>
std::vector<std::pair<std::string, E>> words_of(std::initializer_list<E> values) {
  std::vector<std::pair<std::string, E>> words;
  for (const E v : values) words.emplace_back(to_string(v), v);
  return words;
}

/// The [dynamics] table's schema (common/case_keys.hpp): every key, its unit, range and meaning. validate() checks its
/// ranges, then the rules between keys; the case reader and writer and `strainwave keys` read it.
inline const std::vector<CaseKey<DynamicsParams>>& dynamics_keys() {
  using P = DynamicsParams;
  static const std::vector<CaseKey<P>> keys = {
      choice_key<P>("configuration", &P::configuration,
                    words_of({DynamicsConfiguration::CsFixed, DynamicsConfiguration::FsFixed,
                              DynamicsConfiguration::WgFixed, DynamicsConfiguration::AllFree}),
                    "which body is held: circular spline, flexspline, generator, or none (a brake on the circular "
                    "spline)"),
      choice_key<P>("ramp", &P::ramp_shape, words_of({RampShape::Paper, RampShape::Cubic}),
                    "shape of the speed and load ramps: the seed paper's two parabolas or the cubic STEP"),
      choice_key<P>("pairs", &P::pair_motion, words_of({PairMotion::Moving, PairMotion::Frozen}),
                    "tooth pairs travel through the mesh (moving) or stay at generator angle 0 (frozen, the paper's)"),
      choice_key<P>("pair_stiffness", &P::pair_stiffness,
                    words_of({PairStiffness::Teeth, PairStiffness::Constant}),
                    "a moving pair's stiffness: the teeth's own compliance, or the contact law k d^m1 below"),
      choice_key<P>("rim", &P::rim, words_of({RimCoupling::Fem, RimCoupling::Rigid}),
                    "moving pairs joined through the flexspline's condensed compliance (fem) or independent"),
      integer_key<P>("compliance_phases", &P::compliance_phases, at_least(1),
                     "rim = \"fem\": generator phases per tooth pitch at which the body's compliance is solved"),
      integer_key<P>("oversampling", &P::oversampling, at_least(1),
                     "samples per output step, low-passed before decimation (1: plain samples)"),
      number_key<P>("drive_speed_rpm", &P::drive_speed_rpm, 1, "rpm", above(0), "final speed of the driven body"),
      number_key<P>("drive_ramp_start_s", &P::drive_ramp_start_s, 1, "s", at_least(0), "the speed ramp's start"),
      number_key<P>("drive_ramp_end_s", &P::drive_ramp_end_s, 1, "s", any_value(),
                    "the speed ramp's end, > drive_ramp_start_s"),
      number_key<P>("load_torque_Nm", &P::load_torque_Nm, 1, "N m", at_least(0, "it always resists the output"),
                    "final load on the output body"),
      number_key<P>("load_ramp_start_s", &P::load_ramp_start_s, 1, "s", at_least(0), "the load ramp's start"),
      number_key<P>("load_ramp_end_s", &P::load_ramp_end_s, 1, "s", any_value(),
                    "the load ramp's end, > load_ramp_start_s"),
      number_key<P>("stiffness_N_per_m", &P::stiffness_N_per_m, 1, "N/m^m1", above(0),
                    "pair_stiffness = \"constant\": k0 of the contact law f = k d^m1 + c d' |d'|^m2 d^m3"),
      number_key<P>("stiffness_variation_N_per_m", &P::stiffness_variation_N_per_m, 1, "N/m^m1", at_least(0),
                    "dk of k(t) = k0 + dk sin(2 pi f_m t + phase), < stiffness_N_per_m"),
      number_key<P>("stiffness_phase_deg", &P::stiffness_phase_deg, 1, "deg", any_value(), "the phase of k(t)"),
      number_key<P>("damping_Ns_per_m", &P::damping_Ns_per_m, 1, "N s/m", at_least(0), "c of the contact law"),
      number_key<P>("exponent_stiffness", &P::exponent_stiffness, 1, "", at_least(1), "m1 of the contact law"),
      number_key<P>("exponent_damping", &P::exponent_damping, 1, "", at_least(0), "m2 of the contact law"),
      number_key<P>("exponent_indentation", &P::exponent_indentation, 1, "", at_least(0), "m3 of the contact law"),
      number_key<P>("flexspline_compliance_rad_per_Nm", &P::flexspline_compliance_rad_per_Nm, 1, "rad/(N m)",
                    at_least(0, "0 = rigid flexspline"),
                    "C_tau between the toothed rim and the output flange (rim = \"rigid\"; fem's result.json)"),
      number_key<P>("flexspline_torsion_damping_Nms_per_rad", &P::flexspline_torsion_damping_Nms_per_rad, 1,
                    "N m s/rad", at_least(0), "viscous damping in parallel with 1/C_tau"),
      number_key<P>("circular_spline_drag_Nms_per_rad", &P::circular_spline_drag_Nms_per_rad, 1, "N m s/rad", above(0),
                    "all_free: the viscous brake on the circular spline that reacts the load"),
      number_key<P>("load_inertia_kgm2", &P::load_inertia_kgm2, 1, "kg m^2", at_least(0),
                    "added to the output body's own"),
      number_key<P>("output_drag_coulomb_Nm", &P::output_drag_coulomb_Nm, 1, "N m", at_least(0),
                    "T_c of the output's drag -(T_c tanh(w/w_s) + b w)"),
      number_key<P>("output_drag_viscous_Nms_per_rad", &P::output_drag_viscous_Nms_per_rad, 1, "N m s/rad",
                    at_least(0), "b of the output's drag"),
      number_key<P>("drag_smoothing_rad_per_s", &P::drag_smoothing_rad_per_s, 1, "rad/s", above(0),
                    "w_s: the Coulomb drag's step smoothed over this speed"),
      number_key<P>("circular_spline_outer_radius_mm", &P::circular_spline_outer_radius_m, 1e-3, "mm",
                    at_least(0, "0 = default"), "for the inertia: 0 = pitch radius + 2.25 m + 0.15 pitch radius"),
      number_key<P>("circular_spline_width_mm", &P::circular_spline_width_m, 1e-3, "mm", at_least(0, "0 = default"),
                    "for the inertia: 0 = flexspline.rim_width_mm"),
      number_key<P>("base_clearance_mm", &P::base_clearance_m, 1e-3, "mm", any_value(),
                    "pairs = \"frozen\": the clearance of the approximate clearance model"),
      number_key<P>("duration_s", &P::duration_s, 1, "s", above(0), "simulated time"),
      number_key<P>("output_step_s", &P::output_step_s, 1, "s", above(0),
                    "sampling of dynamics.csv, at most duration_s/16"),
      number_key<P>("steady_from_s", &P::steady_from_s, 1, "s", at_least(0),
                    "start of the steady window (means, balances, spectra); 8 samples at least before duration_s"),
      number_key<P>("relative_tolerance", &P::relative_tolerance, 1, "", within(0, 1e-2, true, true),
                    "the integrator's (CVODE BDF) local error control"),
      number_key<P>("absolute_tolerance_rad", &P::absolute_tolerance_rad, 1, "rad", above(0),
                    "on the angles' deviation from the kinematic motion"),
  };
  return keys;
}

}  // namespace sw
