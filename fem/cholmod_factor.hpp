#pragma once
// Sparse Cholesky by CHOLMOD (supernodal, ordering as CHOLMOD chooses: AMD or METIS), factorised once and reused for
// every right-hand side. CHOLMOD stays out of this header (pimpl).
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "fem/assembly.hpp"
#include "fem/linear_solver.hpp"

namespace sw {

/// Which BLAS the process runs CHOLMOD's dense kernels on, and whether it is the slow reference one.
struct BlasInfo {
  std::string description;  ///< e.g. "OpenBLAS 0.3.21 (pthreads, 2 threads) from /usr/lib/.../libblas.so.3"
  bool is_reference = false;
};

/// Inspects the loaded BLAS (OpenBLAS is recognised by its openblas_get_config symbol).
BlasInfo detect_blas();

class CholmodFactor final : public LinearSolver {
public:
  /// Analyses and factorises K (upper triangle). Throws InputError with a sentence for CHOLMOD's failures; a matrix
  /// that is not positive definite means the supports leave rigid-body motion free.
  ///
  /// `block_of_equation` (optional, size n): the node each equation belongs to. When given, the fill-reducing
  /// ordering is computed by METIS on the node graph (a third of the size, a ninth of the edges of the dof graph) and
  /// expanded to the node's equations, which keeps each node's dofs together and makes the analysis several times
  /// cheaper for the same fill.
  explicit CholmodFactor(const SymmetricCsc& K, const std::vector<std::int64_t>& block_of_equation = {});
  ~CholmodFactor();
  CholmodFactor(const CholmodFactor&) = delete;
  CholmodFactor& operator=(const CholmodFactor&) = delete;

  /// Factorises K again on this factor's analysis (ordering and supernodes): K must have the pattern the factor was
  /// analysed for (the harmonic solver's n ≥ 2 matrices share one). Only the numeric factorisation is timed.
  void refactorise(const SymmetricCsc& K);

  /// Solves K·X = B for all columns of B at once (n x k).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const override;

  /// Y = L⁻¹·P·B for a sparse B (n x k), half of a solve: for K = Pᵀ·L·Lᵀ·P, Bᵀ·K⁻¹·B = Yᵀ·Y (influence matrices
  /// at half the cost). Only the supernodes on the paths from B's nonzero rows up the elimination tree are touched,
  /// each with only the columns whose path passes through it; Y's rows are in the factor's (permuted) order and zero
  /// off those paths. Empty when the factor is not a supernodal LLᵀ.
  std::optional<Eigen::MatrixXd> forward_solve(const Eigen::SparseMatrix<double>& B) const override;
  /// Bᵀ·K⁻¹·B = Yᵀ·Y summed supernode by supernode as the half solve finishes each one's rows (a BLAS rank-k update
  /// of its block, with only its columns), never reading Y again. On the seed cup (541k × 138) this took the contact's
  /// influence coefficients from 2.6–4.5 s to 0.7 s: a separate pass over the dense Y cost 2.3 s, most of it the
  /// first read of pages the solve had only zero-filled (the same pass repeated: 0.1 s).
  std::optional<Eigen::MatrixXd> influence_matrix(const Eigen::SparseMatrix<double>& B) const override;

  const FactorStats& stats() const override;

private:
  /// The half solve; with `gram`, also Yᵀ·Y accumulated into it (k x k, lower triangle then mirrored).
  std::optional<Eigen::MatrixXd> forward(const Eigen::SparseMatrix<double>& B, Eigen::MatrixXd* gram) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace sw
