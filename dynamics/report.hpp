#pragma once
// The three outputs of `strainwave dynamics` as strings (the app writes them with write_file_atomic):
//   dynamics.csv  one row per output sample: time, speed of every body [rpm], every pair's force [N] (signed, drive
//                 flank positive), total meshing force [N], mesh torque on the flexspline rim [N·m], drive and load torque
//   dynamics.json the keys of SPEC.md ("Dynamics result") plus the parameters, inertias, energies and solver statistics
//   dynamics.svg  speeds over time, pair forces and total force over time, force spectrum with f_m marked
#include <string>
#include <vector>

#include "dynamics/analysis.hpp"

namespace sw {

/// Extra facts for the reports that the model does not hold.
struct DynamicsReportInfo {
  std::string case_path;
  std::string clearance_source;   ///< e.g. "kinematics (basic, φ₀ = 0)" or "approximate (dynamics stand-in)"
  double total_time_s = 0.0;      ///< wall clock of the whole command
  double simulate_time_s = 0.0;   ///< wall clock of the integration
};

std::string dynamics_csv(const DynamicsModel& m, const DynamicsSeries& s);

/// The run as a SPEC.md recording of kind `dynamics` (input of `strainwave reconcile`): metadata lines, then
/// time_s,wg_speed_rpm,output_speed_rpm,mesh_force_N (output = the configuration's output body, mesh force = Σ|F_i|).
/// `extra_metadata` lines are written as given ("key: value", without the leading "# ").
std::string dynamics_recording(const DynamicsModel& m, const DynamicsSeries& s,
                               const std::vector<std::string>& extra_metadata = {});
std::string dynamics_json(const DynamicsModel& m, const DynamicsSeries& s, const DynamicsSummary& r,
                          const DynamicsReportInfo& info);
std::string dynamics_svg(const DynamicsModel& m, const DynamicsSeries& s, const DynamicsSummary& r,
                         const DynamicsReportInfo& info);

}  // namespace sw
