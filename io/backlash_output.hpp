#pragma once
// What `strainwave backlash` reads and writes besides the case: φ₀ from the FEM's result.json; backlash.json (keys in
// SPEC.md), backlash.csv (per tooth-pair position), backlash.svg (basic vs compensated), profiles.vtp (flanks).
// Target sw::backlash_io (the only place the backlash outputs touch VTK or JSON).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "kinematics/backlash.hpp"

namespace sw {

/// One row of the paper's table.
struct BacklashTableRow {
  double position_deg = 0;  ///< from the minor axis (tooth at φ = 90° − position)
  PairClearance basic, compensated;
};

/// Everything `strainwave backlash` reports.
struct BacklashReport {
  std::string case_path;
  std::string curve_source;
  double module_m = 0;
  double phi0_rad = 0;
  std::string phi0_source;                      ///< "--phi0", "fem result.json", "C_tau x torque", "none"
  std::optional<double> compliance_rad_per_Nm;
  double torque_Nm = 0;
  std::vector<BacklashTableRow> table;
  std::vector<PairClearance> positions_basic, positions_compensated;  ///< pair at φ over (−180°, 180°]
  RevolutionSweep revolution_basic, revolution_compensated;
  GeometryCheck geometry;                       ///< the check made before the sweep (basic model)
};

/// The geometry check as printed text (several lines, each labelled), for the command's summary.
std::string geometry_check_text(const GeometryCheck& g, double module_m);

/// backlash.json text.
std::string backlash_json(const BacklashReport& r);

/// backlash.csv text: one row per tooth-pair position.
std::string backlash_csv(const BacklashReport& r);

/// backlash.svg text: j/m of the pair vs its position, basic and compensated, with the table's points.
std::string backlash_svg(const BacklashReport& r);

/// profiles.vtp: every flexspline tooth outline on the deformed curve at generator angle 0 (basic and compensated)
/// and the circular spline's flanks; cell data "part" = 0 flexspline basic, 1 flexspline compensated, 2 circular
/// spline. Coordinates in millimetres. Written atomically.
void write_profiles_vtp(const std::filesystem::path& path, const BacklashModel& model, double phi0_rad);

}  // namespace sw
