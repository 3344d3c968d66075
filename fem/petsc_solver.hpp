#pragma once
// The flexspline's equations on PETSc under MPI ([solver] backend = "petsc"; `mpirun -np N strainwave fem CASE.toml
// --backend petsc`). Rank 0 runs the whole analysis as one process would (meshing, load cases, contact,
// post-processing, output); the stiffness, its factorisation and every solve are distributed: rank 0 broadcasts the
// mesh, the ranks partition the free nodes (PT-Scotch through PETSc's MatPartitioning; the Debian PETSc has no
// ParMETIS), each rank assembles its elements into a preallocated MATAIJ with block size 3 (rows of a node together,
// contiguous per rank) and the solves run on the ranks' rows; right-hand sides are scattered from rank 0 and
// solutions gathered back to it. The other ranks serve rank 0 from `parallel::serve()` and sleep between requests.
//
// The solver is PETSc's KSP, set from the PETSc options on the command line (a single dash: -ksp_type cg -pc_type
// gamg, -mat_mumps_icntl_14 50, -ksp_monitor; also the PETSC_OPTIONS environment variable). Default: MUMPS
// Cholesky (-ksp_type preonly -pc_type cholesky -pc_factor_mat_solver_type mumps). The matrix carries the six
// rigid-body modes as its near-null space (MatNullSpaceCreateRigidBody) for algebraic multigrid (-pc_type gamg), and
// Krylov methods run to a relative residual of 1e-10 unless -ksp_rtol says otherwise.
//
// Without PETSc at build time (cmake -DSW_WITH_PETSC=OFF, or libpetsc-real-dev missing) the backend is refused with
// one line.
#include <memory>
#include <string>
#include <vector>

#include "fem/flexspline_model.hpp"
#include "fem/assembly.hpp"
#include "fem/linear_solver.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

namespace parallel {

/// True when this build has the PETSc backend.
bool petsc_available();

/// Takes PETSc's options out of a command line: every argument of a single dash and a name of two or more
/// characters (-ksp_type, -pc_type, -log_view), with the argument after it when that is not itself an option (a
/// negative number is a value). Returns them in order; `args` keeps strainwave's own arguments.
std::vector<std::string> take_petsc_options(std::vector<std::string>& args);

/// Starts MPI and PETSc now when an MPI launcher (mpirun, srun) started this process, so the ranks ≥ 1 can serve;
/// otherwise PETSc starts on one rank when the petsc backend is first used. InputError when PETSc options are given
/// to a build without PETSc, or when MPI or PETSc fail to start.
void start(const std::vector<std::string>& petsc_options);

/// This process's rank and the number of ranks (0 and 1 without an MPI launch).
int rank();
int ranks();
/// Machines (shared-memory nodes) the ranks run on (1 without an MPI launch).
int nodes();

/// Ranks ≥ 1: take part in every setup and solve rank 0 asks for, until it stops; returns the exit code.
int serve();

/// Rank 0: releases the serving ranks and finalises PETSc. Idempotent; main calls it on every way out. After a run
/// that `succeeded`, warns (one line) when PETSc options were given but the petsc backend was never used.
void stop(bool succeeded);

}  // namespace parallel

class PetscSolver final : public LinearSolver {
public:
  /// Rank 0 (the other ranks join from parallel::serve()): distributes the mesh, partitions, assembles K over the
  /// free dofs of `dofs` (whole nodes fixed, as clamped_nodes gives them) and sets up the solver (MUMPS: the
  /// numeric factorisation). InputError with PETSc's own sentence for a bad option, a failed factorisation (rigid-body
  /// modes unconstrained?) or a rank that ran out of memory.
  PetscSolver(const TetMesh& mesh, const Material& material, const DofMap& dofs);
  ~PetscSolver() override;
  PetscSolver(const PetscSolver&) = delete;
  PetscSolver& operator=(const PetscSolver&) = delete;

  /// Solves K·X = B (n_equations x k) on the ranks; B and X live on rank 0. Direct solvers take the columns in
  /// blocks (MatMatSolve), Krylov methods one by one from a zero initial guess; InputError when one does not converge.
  /// The first solve also refuses PETSc options that nothing used (a misspelt option).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const override;

  const FactorStats& stats() const override;
  double assemble_s() const;  ///< wall time of the distributed assembly (s)

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sw
