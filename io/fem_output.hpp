#pragma once
// What `strainwave fem` writes: result.json (its schema is FemResult below, writer and reader side by side; beside
// the figures the case it ran and the tool's version, io/provenance.hpp), neutral_curve.csv (for the kinematics
// module), flexspline.pvd with one .vtu per load case.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "io/case.hpp"
#include "io/provenance.hpp"
#include "common/resources.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/fourier_solver.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

struct RunInfo {
  double mesh_s = 0, output_s = 0, total_s = 0;
  long peak_rss_bytes = 0;
  BlasInfo blas;
};

/// result.json's `mesh` of a TET10 run: the mesh solved.
struct TetMeshFigures {
  std::size_t nodes = 0, elements = 0;
  double min_dihedral_deg = 0, max_dihedral_deg = 0, max_radius_edge_ratio = 0;
};

/// result.json's `mesh` of a harmonic (fourier) run: the meridian section, and the TET10 grid it is revolved into for
/// viewing.
struct SectionMeshFigures {
  std::string kind;
  std::size_t nodes = 0, elements = 0, grid_nodes = 0, grid_elements = 0;
  std::optional<double> tooth_layer_shear_factor;  ///< teeth = "layer": κ of the ribs' shear along the face
};

/// result.json, key by key in the file's own units (each member is named as its key): what `strainwave fem` writes
/// and what the report, sweeps and later stages read back. Optional parts are left out of the file when empty.
struct FemResult {
  struct CupTheoryTerms {
    double diaphragm_rad = 0, body_wall_rad = 0, rim_rad = 0;
    std::array<double, 2> diaphragm_radii_mm{};  ///< inner, outer
    double body_length_mm = 0, rim_length_mm = 0, rim_outer_radius_mm = 0;
  };
  struct Reading {
    double radius_mm = 0, z_mm = 0;
  };
  struct Place {
    double angle_deg = 0, z_mm = 0;
  };
  /// Hoop stress figures, MPa (but the angle and z).
  struct HoopStressMPa {
    double nominal_bending = 0, nominal_membrane = 0, nominal_angle_deg = 0, nominal_z_mm = 0;
    double ring_theory_bending = 0;
    double local_peak_tensile = 0;
    Place local_peak_tensile_at;
    double local_peak_compressive = 0;
    Place local_peak_compressive_at;
  };
  struct HoopStressProfile {
    double z_mm = 0, inner_radius_mm = 0, outer_radius_mm = 0;
    std::vector<int> angle_deg;
    std::vector<double> inner_Pa, outer_Pa;  ///< at angle_deg
  };
  struct WaveGenerator {
    double force_per_point_N = 0, w0_reached_mm = 0;
    std::array<double, 3> net_force_N{}, net_moment_Nm{};
    double rim_rotation_rad = 0;
  };
  struct SweepPoint {
    double torque_Nm = 0, compliance_rad_per_Nm = 0;
  };
  /// The generator's bearing (its keys stand in `generator`).
  struct Bearing {
    double bearing_max_ball_load_N = 0, bearing_max_approach_um = 0;
  };
  /// A station pair of the generator (each force acts at angle and at angle + 180°).
  struct Station {
    double angle_deg = 0;
    std::optional<double> force_N;  ///< the generator case (unilateral generators only)
    double force_with_torque_N = 0;
  };
  struct Generator {
    std::string model, idealisation;
    double total_radial_force_N = 0;
    std::vector<std::array<double, 2>> contact_zones_deg, contact_zones_with_torque_deg;  ///< [from, to]
    double min_contact_force_N = 0, reaction_torque_Nm = 0, w_major_axis_mm = 0, w_minor_axis_mm = 0;
    std::optional<Bearing> bearing;  ///< a cam with a bearing
    std::vector<Station> stations;  ///< left out when empty
  };
  struct FatiguePoint {
    std::string place;
    double r_mm = 0, z_mm = 0;
    double hoop_alternating_MPa = 0, hoop_mean_MPa = 0, meridional_alternating_MPa = 0, meridional_mean_MPa = 0;
    std::optional<double> goodman_safety_factor;  ///< with [material] fatigue data
  };
  struct Fatigue {
    std::string case_name;  ///< key "case": the load case turned over a revolution
    std::string criterion;
    FatiguePoint rim;
    std::optional<FatiguePoint> diaphragm;
  };
  struct LoadCase {
    std::string name;
    double rim_rotation_rad = 0;
  };
  struct PetscFigures {
    std::vector<long> peak_rss_bytes_per_rank;
    std::int64_t iterations = 0, right_hand_sides = 0;
  };
  struct HarmonicSolved {
    int n = 0;
    std::int64_t equations = 0;
    double factor_nnz = 0, factor_s = 0;
  };
  struct Harmonics {
    int harmonics = 0;  ///< N: harmonics 0..N kept
    std::vector<HarmonicSolved> harmonics_solved;
  };
  struct Solver {
    std::string method;  ///< "tet10" | "fourier"
    std::size_t dofs = 0;
    std::int64_t equations = 0, matrix_nnz = 0;
    double factor_nnz = 0, factor_gflop = 0, factor_gflop_per_s = 0;
    std::string ordering;
    bool supernodal = true;
    std::string blas, backend, algorithm;
    int ranks = 1;
    std::optional<PetscFigures> petsc;   ///< backend "petsc" (its keys stand in `solver`)
    std::optional<Harmonics> harmonics;  ///< method "fourier" (its keys stand in `solver`)
  };
  struct Timings {
    double mesh = 0, assemble = 0, analyse = 0, factor = 0, solve = 0, output = 0, total = 0;
  };

  std::string case_path;  ///< key "case_file": the case file the run read (an output, when it ran a stored case)
  Provenance provenance;  ///< keys "case" (the resolved case) and "version"
  double torque_Nm = 0, phi0_rad = 0, compliance_rad_per_Nm = 0;
  double phi0_theory_rad = 0, phi0_theory_cup_rad = 0;
  CupTheoryTerms phi0_theory_cup_terms;
  double phi0_engaged_rad = 0;
  Reading phi0_reading;
  double applied_torque_Nm = 0, reaction_torque_Nm = 0, torque_balance_error_rel = 0;
  double max_hoop_stress_Pa = 0, max_hoop_stress_angle_deg = 0, min_hoop_stress_Pa = 0, min_hoop_stress_angle_deg = 0;
  std::string hoop_stress_case;
  HoopStressMPa hoop_stress_MPa;
  HoopStressProfile hoop_stress_profile;
  std::optional<WaveGenerator> wave_generator;          ///< with a [wave_generator]
  std::optional<std::vector<SweepPoint>> torque_sweep;  ///< with a [wave_generator]
  std::optional<Generator> generator;
  std::optional<Fatigue> fatigue;
  std::vector<LoadCase> load_cases;
  std::variant<TetMeshFigures, SectionMeshFigures> mesh;  ///< by solver.method
  Solver solver;
  Timings timings_s;
  long peak_rss_bytes = 0;
};

/// The result of the case's solution on the TET10 mesh, with what the run cost.
FemResult fem_result(const Case& c, const TetMesh& mesh, const FlexsplineSolution& s, const RunInfo& run);

/// The result of the harmonic solver's solution: its figures as on TET10, the meridian section as the mesh, the
/// equations and degrees of freedom of all harmonics kept, and each harmonic solved.
FemResult fem_result(const Case& c, const FourierSolution& f, const RunInfo& run);

/// result.json text.
std::string fem_result_json(const FemResult& r);

/// Reads result.json back. Throws InputError, one line naming the file, the key and the value, when the file is
/// missing, not JSON, or a key the writer always writes is missing or of another kind.
FemResult read_fem_result(const std::filesystem::path& result_json);

/// The keys of result.json that backlash reads.
struct FemCompensation {
  double phi0_rad = 0;                          ///< φ₀ at the FEM case's torque
  std::optional<double> compliance_rad_per_Nm;  ///< C_τ, when present
};

/// Reads phi0_rad (required) and compliance_rad_per_Nm (optional) alone from result.json, so a file holding only
/// them serves too. Throws InputError naming the file and key when the file is missing, not JSON, or phi0_rad is
/// absent or not a finite number.
FemCompensation read_fem_compensation(const std::filesystem::path& result_json);

/// C_τ from result.json, required and > 0 (dynamics, reconcile); read alone, so a file holding only it serves too.
/// Throws InputError naming the file and the key.
double read_fem_compliance(const std::filesystem::path& result_json);

/// What the tooth contact takes from an earlier FEM run instead of solving the load cases again: the model's size (to
/// check it is the same model), C_τ, the generator model and the generator-deformed neutral curve (neutral_curve.csv
/// beside result.json).
struct FemRunForContact {
  std::string method;  ///< solver.method: "tet10" | "fourier"
  std::int64_t equations = 0;
  double compliance_rad_per_Nm = 0;
  std::string generator_model;  ///< "cam", "rollers", "four_force", ...
  NeutralCurveSamples neutral_curve;
};

/// Reads them; InputError naming the file and key for anything missing.
FemRunForContact read_fem_run_for_contact(const std::filesystem::path& result_json);

/// neutral_curve.csv text: phi_rad,w_wg_m,v_wg_m,mu_wg_rad,w_comb_m,v_comb_m,mu_comb_rad (one row per degree).
std::string neutral_curve_csv(const NeutralCurveSamples& nc);

/// Reads neutral_curve.csv back (the inverse of neutral_curve_csv; radius_m and z_m from its comment line when
/// present, else 0). Throws InputError naming the file and line for a missing/unknown column, a non-numeric value or
/// a wrong number of values.
NeutralCurveSamples read_neutral_curve_csv(const std::filesystem::path& csv);

/// Writes flexspline.pvd and flexspline_<case>.vtu (displacement, stress, von Mises, cylindrical components) of each
/// load case on `mesh`.
void write_fem_vtk(const std::filesystem::path& dir, const TetMesh& mesh, const std::vector<LoadCaseSolution>& cases);

}  // namespace sw
