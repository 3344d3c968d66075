#pragma once
// Writes what `strainwave fem` produces: result.json (keys in SPEC.md), neutral_curve.csv (for the kinematics module),
// flexspline.pvd with one .vtu per load case.
#include <filesystem>
#include <optional>
#include <string>

#include "io/case.hpp"
#include "common/resources.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/flexspline_analysis.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

struct RunInfo {
  double mesh_s = 0, output_s = 0, total_s = 0;
  long peak_rss_bytes = 0;
  BlasInfo blas;
};

/// result.json text for the solution.
std::string fem_result_json(const Case& c, const TetMesh& mesh, const FlexsplineSolution& s, const RunInfo& run);

/// The keys of result.json the later stages read (backlash, dynamics, reconcile): the one reader of the file.
struct FemCompensation {
  double phi0_rad = 0;                          ///< φ₀ at the FEM case's torque
  std::optional<double> compliance_rad_per_Nm;  ///< C_τ, when present
};

/// Reads phi0_rad (required) and compliance_rad_per_Nm (optional) from result.json. Throws InputError naming the
/// file and key when the file is missing, not JSON, or phi0_rad is absent or not a number.
FemCompensation read_fem_compensation(const std::filesystem::path& result_json);

/// C_τ from result.json, required and > 0 (dynamics, reconcile). Throws InputError naming the file and the key.
double read_fem_compliance(const std::filesystem::path& result_json);

/// What the tooth contact takes from an earlier FEM run instead of solving the load cases again: the model's size (to
/// check it is the same model), C_τ, the generator model and the generator-deformed neutral curve (neutral_curve.csv
/// beside result.json).
struct FemRunForContact {
  std::int64_t equations = 0;
  double compliance_rad_per_Nm = 0;
  std::string generator_model;  ///< "cam", "rollers", "four_force", ...
  NeutralCurveSamples neutral_curve;
};

/// Reads them; InputError naming the file and key for anything missing (a fourier result has no TET10 equations).
FemRunForContact read_fem_run_for_contact(const std::filesystem::path& result_json);

/// neutral_curve.csv text: phi_rad,w_wg_m,v_wg_m,mu_wg_rad,w_comb_m,v_comb_m,mu_comb_rad (one row per degree).
std::string neutral_curve_csv(const NeutralCurveSamples& nc);

/// Reads neutral_curve.csv back (the inverse of neutral_curve_csv; radius_m and z_m from its comment line when
/// present, else 0). Throws InputError naming the file and line for a missing/unknown column, a non-numeric value or
/// a wrong number of values.
NeutralCurveSamples read_neutral_curve_csv(const std::filesystem::path& csv);

/// Writes flexspline.pvd and flexspline_<case>.vtu (displacement, stress, von Mises, cylindrical components).
void write_fem_vtk(const std::filesystem::path& dir, const Case& c, const TetMesh& mesh, const FlexsplineSolution& s);

}  // namespace sw
