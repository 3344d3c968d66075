#pragma once
// The case file's [dynamics] table, SI units. Header-only and dependent on the standard library alone, so that
// io/case.hpp can hold it without depending on the dynamics module. Millimetre keys of the file are converted once by
// the case parser; every key has the default written here.
#include <optional>
#include <sstream>
#include <string>

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
/// 0 stay where they are (the passing of teeth only through the optional k(t)); kept for comparison.
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

/// The resolved [dynamics] table in the case file's own keys and units (millimetres where the key says _mm).
inline std::string describe(const DynamicsParams& p) {
  std::ostringstream o;
  o.precision(10);
  o << "[dynamics]\n"
    << "configuration = \"" << to_string(p.configuration) << "\"\n"
    << "ramp = \"" << to_string(p.ramp_shape) << "\"\n"
    << "pairs = \"" << to_string(p.pair_motion) << "\"\n"
    << "pair_stiffness = \"" << to_string(p.pair_stiffness) << "\"\n"
    << "rim = \"" << to_string(p.rim) << "\"\n"
    << "compliance_phases = " << p.compliance_phases << "\n"
    << "oversampling = " << p.oversampling << "\n"
    << "drive_speed_rpm = " << p.drive_speed_rpm << "\n"
    << "drive_ramp_start_s = " << p.drive_ramp_start_s << "\n"
    << "drive_ramp_end_s = " << p.drive_ramp_end_s << "\n"
    << "load_torque_Nm = " << p.load_torque_Nm << "\n"
    << "load_ramp_start_s = " << p.load_ramp_start_s << "\n"
    << "load_ramp_end_s = " << p.load_ramp_end_s << "\n"
    << "stiffness_N_per_m = " << p.stiffness_N_per_m << "\n"
    << "stiffness_variation_N_per_m = " << p.stiffness_variation_N_per_m << "\n"
    << "stiffness_phase_deg = " << p.stiffness_phase_deg << "\n"
    << "damping_Ns_per_m = " << p.damping_Ns_per_m << "\n"
    << "exponent_stiffness = " << p.exponent_stiffness << "\n"
    << "exponent_damping = " << p.exponent_damping << "\n"
    << "exponent_indentation = " << p.exponent_indentation << "\n"
    << "flexspline_compliance_rad_per_Nm = " << p.flexspline_compliance_rad_per_Nm << "\n"
    << "flexspline_torsion_damping_Nms_per_rad = " << p.flexspline_torsion_damping_Nms_per_rad << "\n"
    << "circular_spline_drag_Nms_per_rad = " << p.circular_spline_drag_Nms_per_rad << "\n"
    << "load_inertia_kgm2 = " << p.load_inertia_kgm2 << "\n"
    << "output_drag_coulomb_Nm = " << p.output_drag_coulomb_Nm << "\n"
    << "output_drag_viscous_Nms_per_rad = " << p.output_drag_viscous_Nms_per_rad << "\n"
    << "drag_smoothing_rad_per_s = " << p.drag_smoothing_rad_per_s << "\n"
    << "circular_spline_outer_radius_mm = " << p.circular_spline_outer_radius_m * 1e3 << "\n"
    << "circular_spline_width_mm = " << p.circular_spline_width_m * 1e3 << "\n"
    << "base_clearance_mm = " << p.base_clearance_m * 1e3 << "\n"
    << "duration_s = " << p.duration_s << "\n"
    << "output_step_s = " << p.output_step_s << "\n"
    << "steady_from_s = " << p.steady_from_s << "\n"
    << "relative_tolerance = " << p.relative_tolerance << "\n"
    << "absolute_tolerance_rad = " << p.absolute_tolerance_rad << "\n";
  return o.str();
}

}  // namespace sw
