#pragma once
// Time integration of the model in dynamics/model.hpp with CVODE (SUNDIALS, Debian libsundials-dev): variable-order
// BDF with Newton iterations on a dense difference-quotient Jacobian and local error control (relative_tolerance,
// absolute_tolerance_rad). The mesh is stiff (contact modes at tens of kHz against a 0.1 s run), hence BDF.
//
// State: every free body's angle and speed as deviations from the kinematic reference motion θ_ref = R_b·Θ(t)
// (R_b = steady speed ratio, Θ the driven body's prescribed angle). The mesh deflection, a few µrad against angles of
// tens of rad, is then a difference of small numbers and the error control acts on it directly. Four quadratures
// ride along (input work, output work, dissipation, parametric work of k(t)) for the energy balance, and a fifth, the
// flanks' friction work, when the model has friction (without it the integrated state is the frictionless one's).
#include <array>
#include <vector>

#include "dynamics/model.hpp"

namespace sw {

/// Energy terms from the start of the run [J]. Balance:
/// input + parametric = output + dissipated + friction + Δkinetic + Δpotential.
struct EnergyBalance {
  double input_J = 0.0;        ///< work of the drive torque on the driven body
  double output_J = 0.0;       ///< work done by the bodies on the load and the drags
  double dissipated_J = 0.0;   ///< contact damping + torsion-spring damping
  double friction_J = 0.0;     ///< the flanks' friction: ∫ Σ |F_t·v_slide| dt
  double bearing_J = 0.0;      ///< the generator bearing's friction: ∫ M·|ω_w − ω_rim| dt
  double parametric_J = 0.0;   ///< ∫ ∂U/∂t dt of the time-varying mesh stiffness (0 for constant k)
  double kinetic_J = 0.0;      ///< at the end (starts from rest)
  double potential_J = 0.0;    ///< contact + torsion spring, at the end minus at the start
  double error_rel() const;    ///< |input + parametric − (output + dissipated + friction + bearing + kinetic + potential)| / |input|
};

struct SolverStats {
  long steps = 0, rhs_evals = 0, jac_evals = 0, error_test_fails = 0, newton_fails = 0;
};

/// Samples every output_step_s from 0 to duration_s (inclusive). The solution is sampled `oversampling` times per
/// output step (CVODE's interpolant, every force evaluated there) and the force-like signals (pair forces, total force,
/// mesh torque, drive torque, mesh deflection, transmission error) pass a linear-phase low-pass FIR (Blackman-windowed
/// sinc, unit DC gain, flat within 2e-4 to 0.4/output_step_s, at least 74 dB down from the output's Nyquist frequency
/// 0.5/output_step_s) before they are decimated: contact forces have kinks, whose content above the output's Nyquist
/// frequency would otherwise fold into the spectra. Content above the fine sampling's own Nyquist frequency
/// (oversampling·0.5/output_step_s) is not filtered; the kinks' spectrum falls as 1/f² there.
/// Angles, speeds, the number of flanks in contact and k(t) are plain samples.
struct DynamicsSeries {
  std::vector<double> time_s;
  std::array<std::vector<double>, kBodyCount> angle_rad;   ///< per BodyId (rim = flange when rigid)
  std::array<std::vector<double>, kBodyCount> speed_rad_s;
  std::vector<std::vector<double>> pair_force_N;           ///< [pair][sample], signed (drive flank positive)
  /// M = Σ F_i·arm_i (+ M_σ and the flanks' friction, moving pairs), the torque the mesh takes off the flexspline rim
  std::vector<double> mesh_torque_Nm;
  /// Moving pairs: M_σ = ∂U/∂(θ_w − θ_f) side of the mesh torque, the torque of the teeth's travel (in mesh_torque_Nm).
  std::vector<double> travel_torque_Nm;
  std::vector<double> total_force_N;      ///< Σ |F_i|, the total meshing force
  std::vector<double> drive_torque_Nm;    ///< torque the drive applies to the driven body
  std::vector<double> load_torque_Nm;     ///< applied load on the output body (signed)
  std::vector<double> stiffness_N_per_m;  ///< k(t)
  std::vector<double> deflection_rad;     ///< mesh deflection e
  /// Transmission error: the output body's angle minus the ideal (kinematic) one, rad.
  std::vector<double> transmission_error_rad;
  std::vector<double> flanks_in_contact;  ///< moving pairs: tooth flanks carrying force
  std::vector<double> max_pair_force_N;   ///< largest flank force
  /// Moving pairs: pair_force_N is per flexspline tooth ([tooth mod teeth per unknown][sample], ccw flank positive).
  bool per_tooth = false;
  /// The energy terms from the start to each sample (plain samples of the integrated works): the difference of two
  /// is the work over the time between them.
  std::vector<EnergyBalance> energy_to_sample;
  EnergyBalance energy;
  SolverStats stats;
};

/// Integrates the model from rest over [0, duration_s]; the flanks' friction (friction_coefficient) acts on moving
/// pairs. Throws InputError when CVODE fails (message names the time and the CVODE flag, and suggests loosening
/// relative_tolerance or checking the contact parameters).
DynamicsSeries simulate(const DynamicsModel& m);

}  // namespace sw
