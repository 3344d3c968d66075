#pragma once
// What `strainwave backlash` writes: backlash.json (its schema is BacklashResult below, writer and reader side by side;
// beside the figures the case it ran and the tool's version, io/provenance.hpp), backlash.csv (per tooth-pair
// position), backlash.svg (basic vs compensated), profiles.vtp (flanks).
#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/provenance.hpp"
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
  Provenance provenance;                        ///< the case and the tool that made the report
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

/// backlash.json, key by key in the file's own units (each member is named as its key).
struct BacklashResult {
  /// One flank of a pair: its clearance, moment arm and the parts nearest each other ("flank / tip corner").
  struct Side {
    double clearance_um = 0, lever_arm_mm = 0;
    std::string nearest;
  };
  struct Pair {
    double phi_deg = 0;
    bool in_mesh = false;
    double depth_mm = 0, j_t1_mm = 0, j_t2_mm = 0, total_play_um = 0;
    Side t1, t2;
  };
  struct Radii {
    double tip_radius_mm = 0, root_radius_mm = 0, form_radius_mm = 0;
  };
  /// What removes an interference at rest (0: none found).
  struct Remedy {
    double addendum_scale_free_of_interference = 0, addendum_coefficient_flexspline_max = 0;
    double addendum_coefficient_circular_max = 0;
    std::array<double, 2> w0_scale_free_of_interference{};
    std::string definition;
  };
  struct Geometry {
    Radii flexspline, circular_spline;
    double w_major_axis_mm = 0, w_minor_axis_mm = 0, working_depth_mm = 0, two_w0_mm = 0;
    double minor_axis_tip_clearance_mm = 0, major_axis_tip_to_root_mm = 0, major_axis_root_to_tip_mm = 0;
    Pair major_axis_pair;
    double major_axis_play_arcmin = 0;
    bool interference_at_rest = false;
    double smallest_clearance_um = 0;
    Pair smallest_clearance_at;
    std::optional<Remedy> remedy;  ///< when interfering at rest
  };
  /// A row of the paper's table; out of the mesh zone there is no backlash (null in the file).
  struct Row {
    double position_deg = 0;
    bool in_mesh = false;
    std::optional<double> basic_over_m, compensated_over_m;
    std::optional<double> change_percent;  ///< in the mesh zone
    std::string compensated_state;
    Pair basic, compensated;
  };
  struct AngularPlay {
    double min = 0, max = 0;
    std::array<double, 2> with_phi0{};
    std::string definition;
  };
  /// The mesh at one generator position of the period.
  struct MeshAt {
    double wg_deg = 0;
    int pairs_in_mesh = 0;
    double min_backlash_um = 0, angular_play_arcmin = 0, closing_t1_arcmin = 0, closing_t2_arcmin = 0;
    std::array<int, 3> pairs_within_1_5_10_um_t1{}, pairs_within_1_5_10_um_t2{};
  };
  struct Revolution {
    std::size_t steps = 0;
    int distinct_positions = 0;
    double min_basic_at_wg_deg = 0, min_compensated_at_wg_deg = 0;
    std::array<int, 2> engaged_pairs{};  ///< min, max
    std::string definition;
    std::vector<MeshAt> period_basic;
  };
  struct Location {
    double phi_deg = 0, position_deg = 0;
    std::string where;
    double depth_um = 0, x_mm = 0, y_mm = 0;
  };

  std::string case_path;  ///< key "case_file": the case file the run read
  Provenance provenance;  ///< keys "case" (the resolved case) and "version"
  std::string neutral_curve;
  double module_mm = 0, phi0_rad = 0;
  std::string phi0_source;
  double torque_Nm = 0;
  std::optional<double> compliance_rad_per_Nm;
  Geometry geometry_check;
  std::string table_model;
  std::vector<Row> table;
  double min_backlash_basic_mm = 0, min_backlash_compensated_mm = 0;
  double max_backlash_basic_mm = 0, max_backlash_compensated_mm = 0;
  AngularPlay angular_play_arcmin;
  Revolution revolution;
  bool interference = false;
  std::vector<Location> interference_locations;
};

/// The file's figures of a backlash report.
BacklashResult backlash_result(const BacklashReport& r);

/// backlash.json text.
std::string backlash_json(const BacklashResult& r);

/// Reads backlash.json back. Throws InputError, one line naming the file, the key and the value, when the file is
/// missing, not JSON, or a key the writer always writes is missing or of another kind.
BacklashResult read_backlash_result(const std::filesystem::path& backlash_json);

/// backlash.csv text: one row per tooth-pair position.
std::string backlash_csv(const BacklashReport& r);

/// backlash.svg text: j/m of the pair vs its position, basic and compensated, with the table's points.
std::string backlash_svg(const BacklashReport& r);

/// profiles.vtp: every flexspline tooth outline on the deformed curve at generator angle 0 (basic and compensated)
/// and the circular spline's flanks; cell data "part" = 0 flexspline basic, 1 flexspline compensated, 2 circular
/// spline. Coordinates in millimetres. Written atomically.
void write_profiles_vtp(const std::filesystem::path& path, const BacklashModel& model, double phi0_rad);

}  // namespace sw
