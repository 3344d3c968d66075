#pragma once
// The FEM's loads and solver (the case file's [load] and [solver] tables), SI units.
#include <optional>
#include <string>

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

/// How the flexspline is solved: 3-D quadratic tetrahedra (any shape), or, for a body of revolution (teeth "ring" or
/// "none"), the meridian section with circumferential harmonics 0..harmonics (exact in θ up to that order).
struct SolverParams {
  SolverMethod method = SolverMethod::Tet10;
  int harmonics = 64;  ///< fourier only: highest circumferential harmonic kept
  SolverBackend backend = SolverBackend::Cholmod;  ///< tet10 only
};

}  // namespace sw
