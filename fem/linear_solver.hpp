#pragma once
// "Factorise this K once; solve with these right-hand sides": all the load cases, the generator contact and the
// loaded tooth contact need of the flexspline's equations. Two backends satisfy it: CholmodFactor (one process,
// fem/cholmod_factor.hpp) and PetscSolver (MPI ranks, MUMPS or a Krylov method, fem/petsc_solver.hpp).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace sw {

struct FactorStats {
  std::int64_t equations = 0;
  std::int64_t matrix_nnz = 0;   ///< stored upper triangle (PETSc: both triangles, as it stores them)
  double factor_nnz = 0;         ///< nnz(L) (0 for an iterative solver)
  double factor_gflop = 0;       ///< floating-point work of the numeric factorisation (GF)
  double analyse_s = 0, factor_s = 0;
  std::string ordering;          ///< ordering the factorisation selected
  bool supernodal = true;
  std::string backend = "cholmod";         ///< "cholmod" | "petsc"
  std::string algorithm;                   ///< e.g. "supernodal Cholesky", "preonly + cholesky (mumps)", "cg + gamg"
  int ranks = 1;                           ///< MPI ranks the solver runs on
  std::vector<long> peak_rss_bytes_per_rank;  ///< PETSc: each rank's peak resident memory so far
  std::int64_t iterations = 0;             ///< Krylov iterations over all right-hand sides (0: a direct solve)
  std::int64_t right_hand_sides = 0;       ///< PETSc: solved so far
};

class LinearSolver {
public:
  virtual ~LinearSolver() = default;

  /// Solves K·X = B for all columns of B (n_equations x k). Can be called any number of times with different
  /// right-hand sides on the one factorisation.
  virtual Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const = 0;

  /// Y = L⁻¹·P·B for a sparse B (n x k), half of a solve, for K = Pᵀ·L·Lᵀ·P: Bᵀ·K⁻¹·B = Yᵀ·Y (influence matrices at
  /// half the cost). Empty where the backend has none; callers then take full solves.
  virtual std::optional<Eigen::MatrixXd> forward_solve(const Eigen::SparseMatrix<double>&) const {
    return std::nullopt;
  }
  /// Bᵀ·K⁻¹·B (k x k, symmetric) from the half solve: Yᵀ·Y. Empty where the backend has no half solve.
  virtual std::optional<Eigen::MatrixXd> influence_matrix(const Eigen::SparseMatrix<double>&) const {
    return std::nullopt;
  }

  virtual const FactorStats& stats() const = 0;
};

}  // namespace sw
