#pragma once
// The three outputs of `strainwave dynamics` (the app writes them with write_file_atomic):
//   dynamics.csv  one row per output sample: time, speed of every body [rpm], every pair's force [N] (signed, drive
//                 flank positive), total meshing force [N], mesh torque on the flexspline rim [N·m], drive and load torque
//   dynamics.json a DynamicsResult: the keys of SPEC.md ("Dynamics result") plus the parameters, inertias, energies and
//                 solver statistics (written and read by io/dynamics_output.hpp)
//   dynamics.svg  speeds over time, pair forces and total force over time, force spectrum with f_m marked
#include <optional>
#include <string>
#include <vector>

#include "dynamics/analysis.hpp"

namespace sw {

/// Extra facts for the reports that the model does not hold.
struct DynamicsReportInfo {
  std::string case_path;
  std::string clearance_source;   ///< e.g. "kinematics (basic, φ₀ = 0)" or "approximate (dynamics stand-in)"
  std::string bearing_source;     ///< the generator bearing's friction moment: how it was found, or why none
  double total_time_s = 0.0;      ///< wall clock of the whole command
  double simulate_time_s = 0.0;   ///< wall clock of the integration
};

/// A spectral line in orders of the mesh frequency f_m and of the generator frequency f_g (0 where that is 0).
struct OrderLine {
  double frequency_Hz = 0.0;
  double amplitude = 0.0;        ///< N for the total force, rad for the transmission error
  double mesh_order = 0.0;       ///< frequency / f_m
  double generator_order = 0.0;  ///< frequency / f_g
};


/// Everything dynamics.json holds: the summary of the run over its steady window, with the facts of the model, the
/// integration and the command that it reports beside it.
struct DynamicsResult {
  std::string case_path;
  DynamicsConfiguration configuration = DynamicsConfiguration::CsFixed;
  int teeth_flexspline = 0, teeth_circular = 0;
  PairMotion pairs = PairMotion::Frozen;
  std::string clearance_source;
  std::string bearing_source;  ///< the generator bearing's friction moment: how it was found, or why none
  std::vector<SpeedCheck> speeds;
  double max_speed_error_rel = 0.0;
  std::vector<PairForceCheck> pair_forces;                ///< frozen pairs
  std::optional<double> max_pair_force_error_rel;         ///< frozen pairs only (moving: a test against loaded contact)
  int pairs_in_interference = 0;                          ///< negative clearance at rest: carried as contact preload
  double total_force_at_rest_N = 0.0;
  double mesh_torque_Nm = 0.0, mesh_torque_theory_Nm = 0.0, load_torque_Nm = 0.0;
  double torque_balance_error_rel = 0.0, energy_error_rel = 0.0;
  EnergyBalance energy;
  /// The steady window's powers and efficiency (with energy.friction_J: absent in files written before the flanks had
  /// friction).
  std::optional<SteadyPower> steady_power;
  double mesh_frequency_Hz = 0.0, generator_frequency_Hz = 0.0;
  double mean_total_force_N = 0.0, force_fluctuation_N = 0.0;
  double spectrum_resolution_Hz = 0.0;
  std::vector<SpectralLine> spectral_lines;               ///< of the total force, strongest first
  double force_noise_floor_N = 0.0, transmission_error_noise_floor_rad = 0.0;
  std::vector<OrderLine> force_lines_in_orders, transmission_error_lines_in_orders;
  double steady_window_start_s = 0.0, steady_window_end_s = 0.0;
  double mesh_deflection_min_rad = 0.0, mesh_deflection_max_rad = 0.0;
  double max_pair_force_N = 0.0;
  double flanks_in_contact_min = 0.0, flanks_in_contact_max = 0.0;
  double transmission_error_peak_to_peak_rad = 0.0;
  int oversampling = 1;
  std::string output_filter;                              ///< the output low-pass, in words
  BodyInertias inertia;
  /// The run's [dynamics] table (dynamics.json repeats the ramps, the contact law and the integrator's settings).
  DynamicsParams parameters;
  std::string solver_method;
  SolverStats solver;
  double simulate_time_s = 0.0, total_time_s = 0.0;       ///< wall clock
  double real_time_factor = 0.0;                          ///< duration_s / simulate_time_s
};

/// The run's dynamics.json value: the summary `r` of series `s` of model `m`, and the command's facts `info`.
DynamicsResult dynamics_result(const DynamicsModel& m, const DynamicsSeries& s, const DynamicsSummary& r,
                               const DynamicsReportInfo& info);

/// dynamics.csv text.
std::string dynamics_csv(const DynamicsModel& m, const DynamicsSeries& s);

/// The run as a SPEC.md recording of kind `dynamics` (input of `strainwave reconcile`): metadata lines, then
/// time_s,wg_speed_rpm,output_speed_rpm,mesh_force_N (output = the configuration's output body, mesh force = Σ|F_i|).
/// `extra_metadata` lines are written as given ("key: value", without the leading "# ").
std::string dynamics_recording(const DynamicsModel& m, const DynamicsSeries& s,
                               const std::vector<std::string>& extra_metadata = {});

/// dynamics.svg text: speeds, pair (or tooth) forces, for moving pairs the transmission error and the flanks in
/// contact, the total force and its spectrum, under a header of the case, the drive, the load and the checks.
std::string dynamics_svg(const DynamicsModel& m, const DynamicsSeries& s, const DynamicsSummary& r,
                         const DynamicsReportInfo& info);

}  // namespace sw
