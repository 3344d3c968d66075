// The half solve on the patterns' paths (CholmodFactor::forward_solve) against full solves: Bᵀ·K⁻¹·B = Yᵀ·Y for
// local load patterns scattered over a clamped tube, with both orderings (METIS on the node graph, CHOLMOD's own).
#include <gtest/gtest.h>

#include <random>

#include "fem/assembly.hpp"
#include "common/error.hpp"
#include "fem/cholmod_factor.hpp"
#include "mesh/shapes.hpp"

namespace sw {
namespace {

const Material kSteel{210e9, 0.3, 7850};

struct Tube {
  TetMesh mesh;
  DofMap dofs;
  SymmetricCsc K;
};

Tube clamped_tube() {
  MeshParams mp;
  mp.size_m = 1.5e-3;
  mp.wall_layers = 2;
  Tube t;
  t.mesh = mesh_tube(9e-3, 10e-3, 12e-3, mp);
  std::vector<bool> fixed(3 * t.mesh.n_nodes(), false);
  for (std::size_t i = 0; i < t.mesh.n_nodes(); ++i)
    if (t.mesh.nodes(i, 2) < 1e-9) fixed[3 * i] = fixed[3 * i + 1] = fixed[3 * i + 2] = true;
  t.dofs = make_dof_map(fixed);
  t.K = assemble_stiffness(t.mesh, kSteel, t.dofs);
  return t;
}

/// Columns of a few nonzeros each around a random equation (a local pattern), plus one dense column (every path).
Eigen::SparseMatrix<double> local_patterns(std::int64_t n, int m) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<std::int64_t> at(0, n - 12);
  std::uniform_real_distribution<double> value(-1, 1);
  std::vector<Eigen::Triplet<double>> e;
  for (int j = 0; j + 1 < m; ++j) {
    const std::int64_t k0 = at(rng);
    for (int i = 0; i < 12; i += 2) e.emplace_back(k0 + i, j, value(rng));
  }
  for (std::int64_t k = 0; k < n; ++k) e.emplace_back(k, m - 1, value(rng));
  Eigen::SparseMatrix<double> B(n, m);
  B.setFromTriplets(e.begin(), e.end());
  return B;
}

TEST(ForwardSolve, HalfSolveOnThePathsGivesTheInfluenceMatrixOfFullSolves) {
  const Tube t = clamped_tube();
  const Eigen::SparseMatrix<double> B = local_patterns(t.dofs.n_equations, 40);
  const Eigen::MatrixXd Bd(B);
  for (const bool node_ordering : {true, false}) {
    const CholmodFactor factor(t.K, node_ordering ? equation_nodes(t.dofs) : std::vector<std::int64_t>{});
    const auto Y = factor.forward_solve(B);
    ASSERT_TRUE(Y.has_value());
    const Eigen::MatrixXd half = Y->transpose() * *Y;
    const Eigen::MatrixXd full = Bd.transpose() * factor.solve(Bd);
    // The influence matrix summed supernode by supernode during the half solve: Yᵀ·Y, symmetric to the bit.
    const Eigen::MatrixXd g = *factor.influence_matrix(B);
    EXPECT_LT((g - half).cwiseAbs().maxCoeff(), 1e-13 * half.cwiseAbs().maxCoeff()) << node_ordering;
    EXPECT_EQ((g - g.transpose()).cwiseAbs().maxCoeff(), 0.0);
    // Round-off of two different substitution orders on a system of condition ~1e8: 1e-10 of the largest entry.
    EXPECT_LT((half - full).cwiseAbs().maxCoeff(), 1e-10 * full.cwiseAbs().maxCoeff()) << node_ordering;
    // A local pattern's forward substitution stays on its paths: most of Y is never touched.
    const double touched = static_cast<double>((Y->leftCols(39).array() != 0).count()) / (Y->rows() * 39.0);
    EXPECT_LT(touched, 0.5) << node_ordering;
  }
}

// A second matrix of the same pattern factorised on the first one's analysis solves like a factor of its own.
TEST(Refactorise, SamePatternOnTheFirstAnalysisSolvesLikeAFreshFactor) {
  const Tube t = clamped_tube();
  SymmetricCsc K2 = t.K;
  for (double& v : K2.value) v *= 3.0;  // same pattern, other values: a stiffer material
  for (std::int64_t j = 0; j < K2.n; ++j) K2.value[K2.column_start[j + 1] - 1] *= 1.5;  // and a heavier diagonal
  CholmodFactor reused(t.K, equation_nodes(t.dofs));
  reused.refactorise(K2);
  const CholmodFactor fresh(K2, equation_nodes(t.dofs));
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(t.dofs.n_equations, 3);
  const Eigen::MatrixXd x1 = reused.solve(B), x2 = fresh.solve(B);
  EXPECT_LT((x1 - x2).cwiseAbs().maxCoeff(), 1e-10 * x2.cwiseAbs().maxCoeff());
  EXPECT_THROW(reused.refactorise(SymmetricCsc{}), std::logic_error);
}

TEST(ForwardSolve, RefusesARightHandSideOfTheWrongSize) {
  const Tube t = clamped_tube();
  const CholmodFactor factor(t.K);
  EXPECT_THROW(factor.forward_solve(Eigen::SparseMatrix<double>(t.dofs.n_equations + 1, 2)), std::logic_error);
}

}  // namespace
}  // namespace sw

namespace sw {
namespace {

/// diag(1, ratio): its pivots' ratio is `ratio`.
SymmetricCsc two_pivots(double ratio) { return SymmetricCsc{2, {0, 1, 2}, {0, 1}, {1.0, ratio}}; }

// The pivot ratio a fine but constrained model reaches (3.2e-7 on size 17's section at 0.05 mm, measured) factorises;
// one at round-off (a rigid mode left a positive pivot) is refused with its ratio in the sentence.
TEST(CholmodFactor, OnlyAPivotAtRoundOffIsCalledSingular) {
  EXPECT_NO_THROW(CholmodFactor{two_pivots(1e-9)});
  try {
    CholmodFactor f{two_pivots(1e-15)};
    FAIL() << "a pivot at round-off must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pivot ratio 1e-15"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sw
