#pragma once
// The flexspline's equations, kept for every stage that needs "solve with this right-hand side": the clamp's
// supports, the stiffness factorised once (by CHOLMOD, or on MPI ranks by PETSc: [solver] backend), and the wave
// generator's contact stations on the bore. The FEM load cases (fem/flexspline_analysis.hpp) and the loaded tooth
// contact (contact/) both work on one such system.
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "fem/flexspline_model.hpp"
#include "fem/assembly.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/linear_solver.hpp"
#include "fem/generator_contact.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

struct FlexsplineSystem {
  std::vector<bool> clamped;  ///< per node: on a kSurfaceClamped face
  DofMap dofs;
  std::unique_ptr<LinearSolver> factor;  ///< CholmodFactor or PetscSolver, by c.solver.backend
  double assemble_s = 0;

  /// K⁻¹·F for full-dof loads (3·n_nodes × k), as full-dof displacements (zero on the clamp).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& loads) const;
  /// Influence matrix Lᵀ·K⁻¹·L of load patterns L (3·n_nodes × m): the work-conjugate displacement of each pattern
  /// under a unit amount of each other (m × m, symmetric positive definite), solved in chunks of right-hand sides.
  Eigen::MatrixXd influence(const Eigen::SparseMatrix<double>& loads) const;
};

/// Nodes fixed by the supports: every node on a kSurfaceClamped face (size n_nodes).
std::vector<bool> clamped_nodes(const TetMesh& mesh);

/// Supports (every node on a kSurfaceClamped face), assembly and the one factorisation (progress on stderr), on the
/// model's solver.backend: CHOLMOD in this process, or PETSc on the MPI ranks (each assembles its share).
FlexsplineSystem assemble_and_factorise(const FlexsplineModel& c, const TetMesh& mesh);

/// The wave generator as the solver sees it: contact stations on the bore over the generator's band and what they
/// push against (a cam's or the rollers' standoff), or, for the force idealisation, the unit forces and stations that
/// hold the band radially under torque.
struct GeneratorStations {
  bool unilateral = false;     ///< cam, rollers: contact that pushes and never pulls
  BandStations stations;
  Eigen::VectorXd obstacle_m;  ///< per pair: the generator surface's standoff from the bore, summed over the pair (m;
                               ///< rollers: per metre of set-out, scaled to w0 by the analysis)
  Eigen::VectorXd force_load;  ///< force models: the unit generator forces (3·n_nodes)
};
GeneratorStations generator_stations(const FlexsplineModel& c, const TetMesh& mesh);

/// Half-width of each of the force idealisation's patches on the bore (rad).
inline constexpr double kGeneratorPatchHalfAngle_rad = 3.0 * 3.141592653589793 / 180;

/// The rollers' set-out per metre of standoff: all four touch (symmetric), so the generator case is linear in the
/// standoff, and `w_unit_m` (the major axis's w for a unit standoff) scales it to the case's w0. InputError when the
/// rollers do not push the major axis outward.
double rollers_setout(const WaveGeneratorParams& w, double w_unit_m);

}  // namespace sw
