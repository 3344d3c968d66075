// TET10 element and assembly: rigid-body null space, symmetry, and the patch tests (linear and quadratic fields
// reproduced exactly on a distorted multi-element mesh).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "common/error.hpp"
#include "fem/assembly.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/elasticity.hpp"
#include "tests/fem/box_mesh.hpp"

namespace sw {
namespace {

const Material kSteel{210e9, 0.3, 7850};

ElementCoords distorted_element() {
  Eigen::Matrix<double, 4, 3> c;
  c << 0.1, -0.05, 0.02, 1.2, 0.1, -0.1, 0.3, 0.9, 0.15, 0.2, 0.25, 1.1;
  ElementCoords x;
  x.topRows<4>() = c;
  const int e[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
  for (int k = 0; k < 6; ++k) x.row(4 + k) = 0.5 * (c.row(e[k][0]) + c.row(e[k][1]));
  return x * 1e-3;
}

TEST(Tet10Stiffness, IsSymmetricPositiveSemidefiniteWithSixRigidBodyModes) {
  const Matrix30d K = tet10_stiffness(distorted_element(), elasticity_matrix(kSteel));
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
  Eigen::SelfAdjointEigenSolver<Matrix30d> eig(K);
  const auto& ev = eig.eigenvalues();
  const double largest = ev.maxCoeff();
  // Round-off level for the zero eigenvalues: well below 1e-10 of the largest.
  constexpr double kZero = 1e-10;
  int zeros = 0;
  for (int i = 0; i < 30; ++i) {
    EXPECT_GT(ev[i], -kZero * largest);
    if (std::abs(ev[i]) < kZero * largest) ++zeros;
  }
  EXPECT_EQ(zeros, 6);
  EXPECT_GT(ev[6], 1e-6 * largest);  // the seventh is a real deformation mode
}

TEST(Tet10Shape, PartitionOfUnityAndNodalInterpolation) {
  const auto& X = tet10_node_coordinates();
  for (int a = 0; a < 10; ++a) {
    const auto N = tet10_shape(X.row(a).transpose());
    for (int b = 0; b < 10; ++b) EXPECT_NEAR(N[b], a == b ? 1.0 : 0.0, 1e-15);
  }
  const auto G = tet10_shape_gradient(Eigen::Vector3d(0.2, 0.3, 0.1));
  EXPECT_LT(G.colwise().sum().norm(), 1e-14);
}

/// Solves a pure-Dirichlet problem: every boundary node takes the exact field, interior nodes are solved for.
double patch_error(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& exact) {
  constexpr double kSize = 0.01;
  const TetMesh m = test::distorted_box(3, kSize, 0.25);
  const auto boundary = test::box_boundary_nodes(m, kSize);
  std::vector<bool> fixed(3 * m.n_nodes());
  Eigen::VectorXd prescribed = Eigen::VectorXd::Zero(3 * m.n_nodes());
  for (std::size_t i = 0; i < m.n_nodes(); ++i) {
    const Eigen::Vector3d ue = exact(m.nodes.row(i).transpose());
    for (int c = 0; c < 3; ++c) {
      fixed[3 * i + c] = boundary[i];
      prescribed[3 * i + c] = ue[c];
    }
  }
  const DofMap dofs = make_dof_map(fixed);
  const CholmodFactor factor(assemble_stiffness(m, kSteel, dofs));
  const Eigen::VectorXd free = factor.solve(dirichlet_lift(m, kSteel, dofs, prescribed));
  const Eigen::VectorXd u = expand_to_full(dofs, free, prescribed);
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < m.n_nodes(); ++i) {
    const Eigen::Vector3d ue = exact(m.nodes.row(i).transpose());
    err = std::max(err, (u.segment<3>(3 * i) - ue).norm());
    scale = std::max(scale, ue.norm());
  }
  return err / scale;
}

// Exact up to round-off of a condition-number-sized amplification: 1e-10 relative.
constexpr double kPatchTol = 1e-10;

TEST(PatchTest, LinearDisplacementFieldIsExactOnADistortedMesh) {
  const auto linear = [](const Eigen::Vector3d& x) {
    return Eigen::Vector3d(1e-4 + 2e-3 * x[0] - 1e-3 * x[1] + 5e-4 * x[2], -2e-4 + 1e-3 * x[0] + 3e-3 * x[2],
                           3e-4 - 2e-3 * x[1] + 1e-3 * x[2]);
  };
  EXPECT_LT(patch_error(linear), kPatchTol);
}

TEST(PatchTest, QuadraticEquilibriumFieldIsExactForTet10) {
  // u = a·(x² − y², −2xy, xy): harmonic components and zero divergence, so it satisfies Navier's equations without
  // body force and TET10 must reproduce it exactly.
  const auto quadratic = [](const Eigen::Vector3d& p) {
    const double a = 0.1, x = p[0], y = p[1];
    return Eigen::Vector3d(a * (x * x - y * y), -2 * a * x * y, a * x * y);
  };
  EXPECT_LT(patch_error(quadratic), kPatchTol);
}

TEST(CholmodFactor, UnconstrainedModelIsRejectedWithAClearSentence) {
  const TetMesh m = test::distorted_box(2, 0.01, 0.1);
  const DofMap dofs = make_dof_map(std::vector<bool>(3 * m.n_nodes(), false));
  try {
    CholmodFactor factor(assemble_stiffness(m, kSteel, dofs));
    FAIL() << "a free-floating body must not factorise";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("rigid-body modes unconstrained? check the boundary conditions"),
              std::string::npos) << e.what();
  }
}

TEST(CholmodFactor, RunsOnTheOptimisedBlasTheSetupInstalls) {
  // scripts/setup.sh installs OpenBLAS behind libblas.so.3; CHOLMOD on the reference BLAS is ~10x slower. This fails
  // when the process resolves to the reference BLAS (or to none that says what it is).
  const BlasInfo blas = detect_blas();
  EXPECT_FALSE(blas.is_reference) << blas.description;
  EXPECT_NE(blas.description.find("OpenBLAS"), std::string::npos) << blas.description;
}

}  // namespace
}  // namespace sw
