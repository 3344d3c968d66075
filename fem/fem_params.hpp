#pragma once
// The FEM's loads and solver (the case file's [load] and [solver] tables), SI units, and their schemas.
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "common/case_keys.hpp"

namespace sw {

enum class TorqueLoading { EngagementZones, Uniform };

struct LoadParams {
  double torque_Nm = 0.0;
  TorqueLoading torque_loading = TorqueLoading::EngagementZones;
  double engagement_half_angle_rad = 0.3490658503988659;  ///< ± around each end of the major axis (20°)
  /// The torque the contact stage loads to, both ways (N·m): the case's key, else the catalog's rated torque of
  /// [catalog] size; absent when neither gives one.
  std::optional<double> rated_torque_Nm;
  std::string rated_torque_from;  ///< "the case file" or "catalog size N" (empty when absent)
};

enum class SolverMethod { Tet10, Fourier };
/// Where the TET10 equations are factorised: CHOLMOD in this process, or PETSc on the MPI ranks of an mpirun launch.
enum class SolverBackend { Cholmod, Petsc };

/// How the flexspline is solved: 3-D quadratic tetrahedra (any shape), or, for a body of revolution (teeth "ring",
/// "layer" or "none"), the meridian section with circumferential harmonics 0..harmonics (exact in θ up to that order).
struct SolverParams {
  SolverMethod method = SolverMethod::Tet10;
  int harmonics = 64;  ///< fourier only: highest circumferential harmonic kept
  SolverBackend backend = SolverBackend::Cholmod;  ///< tet10 only
};

/// The [load] table's schema (common/case_keys.hpp).
inline const std::vector<CaseKey<LoadParams>>& load_keys() {
  using L = LoadParams;
  static const std::vector<CaseKey<L>> keys = {
      number_key<L>("torque_Nm", &L::torque_Nm, 1, "N m", any_value(), "the FEM's output torque on the flexspline"),
      choice_key<L>("torque_loading", &L::torque_loading,
                    {{"engagement_zones", TorqueLoading::EngagementZones}, {"uniform", TorqueLoading::Uniform}},
                    "the FEM's torque as tangential load on the teeth's zones about the major axis, or all round"),
      number_key<L>("engagement_half_angle_deg", &L::engagement_half_angle_rad, std::numbers::pi / 180, "deg",
                    within(0, 90, true, false), "half width of each engagement zone of torque_loading"),
      optional_number_key<L>("rated_torque_Nm", &L::rated_torque_Nm, 1, "N m",
                             above(0, "the torque the drive is loaded to, both ways"),
                             "the contact's torque-twist curve runs from -rated to +rated")
          .with_default("the rated torque of [catalog] size, else none"),
  };
  return keys;
}

/// [solver] method: the file's "auto" is resolved when the case is read (io/case.cpp), so the resolved case holds
/// "tet10" or "fourier".
inline CaseKey<SolverParams> method_key() {
  auto k = choice_key<SolverParams>(
      "method", &SolverParams::method, {{"tet10", SolverMethod::Tet10}, {"fourier", SolverMethod::Fourier}},
      "the flexspline's FEM: 3-D quadratic tetrahedra, or the meridian section with harmonics");
  k.choices.insert(k.choices.begin(), "auto");
  return std::move(k).with_default(
      "\"auto\": fourier for a body of revolution, tet10 for explicit teeth or backend \"petsc\"");
}

/// The [solver] table's schema (common/case_keys.hpp). The file's method "auto" is resolved when the case is read.
inline const std::vector<CaseKey<SolverParams>>& solver_keys() {
  using S = SolverParams;
  static const std::vector<CaseKey<S>> keys = {
      method_key(),
      integer_key<S>("harmonics", &S::harmonics, within(0, 4096), "fourier: highest circumferential harmonic kept")
          .with_default("the case's need (fem/flexspline_model.hpp default_harmonics)"),
      choice_key<S>("backend", &S::backend, {{"cholmod", SolverBackend::Cholmod}, {"petsc", SolverBackend::Petsc}},
                    "tet10: factorise with CHOLMOD here, or with PETSc on the ranks of an mpirun launch"),
  };
  return keys;
}

}  // namespace sw
