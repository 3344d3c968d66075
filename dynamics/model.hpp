#pragma once
// The multibody model of a strain wave gear: three rigid bodies (wave generator, flexspline, circular spline),
// the flexspline optionally split into its toothed rim and its output flange joined by a torsional spring 1/C_τ, and one
// contact per tooth pair of the engagement zones. Everything here is a small value type or a free function; the time
// integration is in dynamics/simulate.hpp.
//
// Kinematics. In the frame turning with the wave generator the flexspline and the circular spline mesh like an internal
// gear pair of equal module, so the pitch-line velocities at the mesh agree: r_f·(ω_f − ω_w) = r_c·(ω_c − ω_w) with
// r = m·z/2, i.e.
//     z_f·(ω_f − ω_w) = z_c·(ω_c − ω_w)                                  (the only kinematic relation)
// from which each configuration follows (ω_d the driven speed):
//     cs_fixed (ω_c = 0):  ω_f = −(z_c − z_f)/z_f · ω_w     (reduction z_f/(z_c − z_f), output reversed)
//     fs_fixed (ω_f = 0):  ω_c = +(z_c − z_f)/z_c · ω_w     (reduction z_c/(z_c − z_f), same sense)
//     wg_fixed (ω_w = 0):  ω_c = +(z_f/z_c) · ω_f           (an internal gear pair)
//     all_free (wave generator driven, load T on the flexspline, brake b on the circular spline):
//              ω_c = (z_c/z_f)·T/b,  ω_f = (1 − z_c/z_f)·ω_w + (z_c/z_f)·ω_c
//              (with output drag D(ω_f), T is T + D(ω_f) and ω_f solves the resulting monotone equation)
// The seed paper's printed relations (ω_g = (Z_f − Z_c)/Z_f·ω_w, ω_c = Z_f/Z_c·ω_g) mix two configurations and its speed
// table matches neither, so they are not used.
//
// Mesh deflection. e = (θ_f − θ_w) − (z_c/z_f)(θ_c − θ_w) [rad] is zero for kinematic motion; it is the flexspline
// rim's rotation relative to where the circular spline and the wave generator put it. A pair at lever arm ρ with flank
// normal projection n sees the penetration δ = n·ρ·e − j on its drive flank and δ = −n·ρ·e − j' on its coast flank.
// The generalized torques follow from virtual work (M = Σ F_i n_i ρ_i, F_i signed, drive flank positive):
//     Q_f = −M,   Q_c = (z_c/z_f)·M,   Q_w = (1 − z_c/z_f)·M          (they sum to zero: no torque on the housing)
//
// Mesh frequency. A flexspline tooth passes a point fixed to the wave generator at the rate z_f·|ω_f − ω_w|/2π
// (= z_c·|ω_c − ω_w|/2π by the relation above); both engagement zones are in phase when z_f is even:
//     f_m = z_f·|n_f − n_w|/60 Hz (speeds in rpm): cs_fixed z_c·n_w/60, fs_fixed z_f·n_w/60, wg_fixed z_f·n_f/60.
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "common/material.hpp"
#include "mesh/flexspline_params.hpp"
#include "dynamics/dynamics_params.hpp"
#include "dynamics/moving_mesh.hpp"
#include "gear/gear.hpp"

namespace sw {

/// One engaged tooth pair, at a fixed position in the wave generator's frame (the pattern of clearances is stationary
/// there; the passing of individual teeth is represented by the stiffness variation k(t) at f_m).
/// Penetrations: drive flank δ = arm_m()·e − clearance_drive_m, coast flank δ = −coast_arm()·e − clearance_coast_m.
struct ToothPair {
  double angle_rad = 0.0;           ///< position from the major axis in the wave-generator frame (reports only)
  double clearance_drive_m = 0.0;   ///< clearance of the loaded flank along its normal (may be < 0: preload)
  double clearance_coast_m = 0.0;   ///< clearance of the opposite flank along its normal
  double lever_arm_m = 0.0;         ///< radius at which the pair acts on the flexspline rim, > 0
  double normal_projection = 1.0;   ///< projection of the circumferential direction on the flank normal (cos α), (0,1]
  double coast_arm_m = 0.0;         ///< effective arm of the coast flank when it differs (0 = same as the drive flank)
  /// Effective arm n·ρ [m] of the drive flank: pair force × arm = torque on the flexspline.
  double arm_m() const { return lever_arm_m * normal_projection; }
  /// Effective arm of the coast flank [m].
  double coast_arm() const { return coast_arm_m > 0.0 ? coast_arm_m : arm_m(); }
};

enum class BodyId { WaveGenerator = 0, FlexsplineRim = 1, FlexsplineFlange = 2, CircularSpline = 3 };
inline constexpr int kBodyCount = 4;
const char* body_name(BodyId b);

/// Polar moments of inertia [kg·m²]. Rim and flange are the two halves of the flexspline (their sum is the whole).
struct BodyInertias {
  std::array<double, kBodyCount> kgm2{};  ///< indexed by BodyId
  double& operator[](BodyId b) { return kgm2[static_cast<int>(b)]; }
  double operator[](BodyId b) const { return kgm2[static_cast<int>(b)]; }
};

/// Everything the integrator needs; built from a case by make_model() or by hand in tests.
struct DynamicsModel {
  DynamicsParams params;
  int teeth_flexspline = 190;   ///< z_f
  int teeth_circular = 192;     ///< z_c > z_f
  BodyInertias inertia;
  std::vector<ToothPair> pairs;    ///< frozen pairs (pairs = "frozen")
  /// Moving pairs (pairs = "moving"): the teeth travel through the mesh; `pairs` is then not used.
  std::shared_ptr<const MovingMesh> moving;
  /// Coulomb's μ on the moving pairs' flanks ([contact] friction_coefficient), in [0, 1]; 0: frictionless.
  double friction_coefficient = 0.0;
  /// The friction force μ·F·tanh(v/v_s) is smoothed over this sliding speed v_s (m/s), > 0: far below the flanks'
  /// sliding, whose sign changes where a tooth turns back out of the circular spline's space (dynamics/README.md).
  double friction_smoothing_m_per_s = 1.0e-3;
  /// The generator's running friction moment on the rim (N·m, ≥ 0: its bearing's, and what else turns with the wave
  /// against the flexspline) at the speed of the two relative to each other (rad/s, ≥ 0): between the generator and
  /// the flexspline's rim, against their relative turn, the Coulomb step smoothed over
  /// params.drag_smoothing_rad_per_s. Empty: a frictionless generator.
  std::function<double(double relative_speed_rad_s)> generator_moment_Nm;
};

enum class BodyRole { Fixed, Driven, Free, MergedIntoFlange };

/// Steady state predicted by kinematics and statics.
struct SteadyState {
  std::array<BodyRole, kBodyCount> role{};
  std::array<double, kBodyCount> speed_rad_s{};  ///< steady speed of each body (rim = flange)
  BodyId driven = BodyId::WaveGenerator;
  BodyId output = BodyId::FlexsplineFlange;
  double load_torque_Nm = 0.0;     ///< signed torque applied to the output body at full load (opposes its motion)
  double drag_torque_Nm = 0.0;     ///< output drag at the steady speed (signed, opposes the motion)
  double mesh_torque_Nm = 0.0;     ///< M = Σ F_i n_i ρ_i at steady state (torque the mesh takes off the flexspline rim)
  double mesh_frequency_Hz = 0.0;  ///< f_m = z_f·|ω_f − ω_w|/2π
};

/// Checks every [dynamics] value against its documented range; throws InputError naming `where` (the case file; empty:
/// none), the key, the value and the constraint ("cases/x.toml: dynamics.damping_Ns_per_m = -1; must be >= 0").
void validate(const DynamicsParams& p, const std::string& where);

/// The moving pairs' own constraints (rim = "fem": no separate C_τ, m1 = 1; pair_stiffness = "teeth": m1 = 1).
void validate_moving(const DynamicsParams& p, const std::string& where);

/// A model from case values: inertias from the geometry, the given tooth pairs. Throws InputError (via validate()).
DynamicsModel make_model(const GearParams& gear, const FlexsplineParams& fs, bool cup, const Material& mat,
                         const DynamicsParams& p, std::vector<ToothPair> pairs, const std::string& where);

/// Drag torque on the output body at speed ω [rad/s]: −(T_c·tanh(ω/ω_s) + b·ω) [N·m].
double output_drag_Nm(const DynamicsParams& p, double omega_rad_s);

/// Body roles, steady speeds, output load and mesh torque for the model's configuration at full speed and load.
/// Precondition: 0 < z_f < z_c; drive speed > 0; throws InputError for all_free when the
/// circular spline's brake is too weak for the load to resist (see DynamicsParams).
SteadyState steady_state(const DynamicsModel& m);

/// Ramp 0 → 1 between t0 and t1 (t1 > t0) with the chosen shape; value, time derivative [1/s] and time integral [s].
double ramp(RampShape shape, double t, double t0, double t1);
double ramp_rate(RampShape shape, double t, double t0, double t1);
double ramp_integral(RampShape shape, double t, double t0, double t1);

/// Contact law of one flank: penetration δ [m] and its rate [m/s] → normal force [N] (≥ 0) and its elastic part k·δ^m1.
struct FlankForce {
  double force_N = 0.0;
  double elastic_N = 0.0;
};
FlankForce flank_force(const DynamicsParams& p, double stiffness, double delta_m, double delta_rate_m_s);

/// Quasi-static load sharing of the same contact law (δ̇ = 0, k = k0): the deflection e [rad] at which
/// Σ F_i(e)·arm_i = mesh_torque_Nm, and each pair's signed force [N]. Throws InputError if no pair can carry it.
struct LoadSharing {
  double deflection_rad = 0.0;
  std::vector<double> force_N;
};
LoadSharing quasi_static_load_sharing(const std::vector<ToothPair>& pairs, const DynamicsParams& p,
                                      double mesh_torque_Nm);

/// Inertias from the case geometry (steel-like density from Material): flexspline wall + rim + teeth (a half-filled
/// ring 2.25·m deep) + diaphragm (cup: a full disc of the inner radius and diaphragm thickness, boss included); circular
/// spline a ring from its tooth tips (half-filled teeth) to its outer radius; wave generator a full disc of the
/// flexspline's inner radius and the rim width (cam plus bearing as solid steel: an upper bound).
/// Rim = rim + teeth + half the body wall; flange = diaphragm + the other half (lumped two-mass torsion model).
BodyInertias body_inertias(const GearParams& gear, const FlexsplineParams& fs, bool cup, const Material& mat,
                           const DynamicsParams& p);

/// Stand-in for the backlash module's clearances (kinematics/): pairs at φ_i = 2πi/z_f within ±half_angle of both ends
/// of the major axis; the rim's radial deformation w(φ) = w0·cos 2φ opens a radial gap w0·(1 − cos 2φ) to the circular
/// spline's tooth spaces, seen on each involute flank as w0·(1 − cos 2φ)·sin α (+ base clearance); lever arm = deformed
/// pitch radius m·z_f/2 + w0·cos 2φ; normal projection cos α.
std::vector<ToothPair> approximate_tooth_pairs(const GearParams& gear, double radial_deformation_m,
                                               double half_angle_rad, double base_clearance_m);

}  // namespace sw
