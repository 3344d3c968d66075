#pragma once
// Linear (bifurcation) buckling of the TET10 flexspline under the prestress of a load case (the torque), on the same
// mesh, supports and stiffness factor as the static solve (fem/flexspline_system.hpp).
//
// Physics. With σ⁰ the Cauchy stress of the prestress displacement u⁰ (linear prebuckling: σ⁰ grows in proportion to
// the load, the geometry does not change before bifurcation), the critical load factors λ solve
//   (K + λ·K_σ)·x = 0,   xᵀ·K_σ·x = ∫ σ⁰_ij (∂x_k/∂X_i)(∂x_k/∂X_j) dV,
// K_σ the initial-stress (geometric) stiffness of the Green–Lagrange strain's quadratic part (Bathe, Finite Element
// Procedures, 2nd ed., 2014, §6.8.2, eq. 6.246 and the linearised buckling problem of §6.8.2; Cook, Malkus, Plesha &
// Witt, Concepts and Applications of FEA, 4th ed., 2002, §18.2–18.3, K_σ = ∫ Gᵀ·S·G dV with S = σ⁰ ⊗ I₃). Element
// by element with G_e the 9 × 30 matrix of ∂N_a/∂X_i, the block of nodes a, b is (∇N_aᵀ·σ⁰·∇N_b)·I₃, integrated
// with the stiffness's own 4-point rule, σ⁰ evaluated at each Gauss point from the element's own displacements
// (not nodal-averaged), as CalculiX's C3D10 does in *BUCKLE. K_σ is indefinite; the pencil is solved as
//   K_σ·x = μ·K·x,   μ = −1/λ,
// whose largest |μ| are the smallest |λ|: Lanczos in the K-inner product (Spectra's SymGEigsSolver, regular-inverse
// mode) on the CHOLMOD factor of K, K_σ scaled to a largest |μ| of order 1 first (Spectra's convergence test is
// relative to max(|μ|, ε^(2/3))).
//
// Supports: the system's (the clamp's dofs eliminated) and, optionally, linear constraints Lᵀ·x = 0 (held patterns:
// the wave generator's stations held radially). Those are exact: the constrained inverse
//   K_c⁻¹ = K⁻¹ − W·(Lᵀ·W)⁻¹·Wᵀ,  W = K⁻¹·L
// (the Lagrange-multiplier elimination, Bathe §3.4.1 / Cook §9.2) replaces K⁻¹ in the Lanczos iteration, which then
// stays in the subspace Lᵀ·x = 0 where K_c is K; the prestress of the case-level function is solved the same way.
// Torsion buckling of a body of revolution is nearly sign-symmetric (λ and −λ): both signs are returned.
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "common/material.hpp"
#include "fem/assembly.hpp"
#include "fem/flexspline_model.hpp"
#include "fem/flexspline_system.hpp"
#include "fem/linear_solver.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// How many load factors and how tightly: `modes` of the smallest |λ| (either sign), Lanczos relative tolerance on μ.
struct Tet10BucklingOptions {
  int modes = 2;
  double tolerance = 1e-9;
};

struct BucklingResultTet10 {
  std::vector<double> load_factors;   ///< λ (signed), by increasing |λ|: the buckling load is λ × the prestress's load
  std::vector<Eigen::VectorXd> modes; ///< per λ: 3·n_nodes, zero on the clamp, scaled so max |component| = 1
  std::vector<double> residuals;      ///< per λ: ‖x + λ·K_c⁻¹·K_σ·x‖_K / ‖x‖_K on the free equations (K_c⁻¹ = K⁻¹
                                      ///< without held patterns): the eigenpair's relative error in energy
  double smallest_positive = 0;       ///< the smallest λ > 0 among those found (0 if none)
};

/// K_σ (n_equations × n_equations, both triangles, N/m) of the prestress displacement `prestress_u` (3·n_nodes, m),
/// on the free dofs of `dofs` (global x, y, z components; no node frames). Throws InputError on size mismatch.
Eigen::SparseMatrix<double> geometric_stiffness(const TetMesh& mesh, const Material& material, const DofMap& dofs,
                                                const Eigen::VectorXd& prestress_u);

/// The smallest |λ| of (K + λ·K_σ(prestress_u))·x = 0 with Lᵀ·x = 0 for the columns of `held` (3·n_nodes × m, full
/// dofs; empty: no constraint). `K` (upper triangle, the dofs' equations) and `K_factor` (its factorisation) must be
/// the same matrix. Throws InputError on sizes that do not match, options out of range, a prestress that strains
/// nothing, or a Lanczos iteration that does not converge.
BucklingResultTet10 buckling_tet10(const TetMesh& mesh, const Material& material, const DofMap& dofs,
                                   const SymmetricCsc& K, const LinearSolver& K_factor,
                                   const Eigen::VectorXd& prestress_u, const Tet10BucklingOptions& o = {},
                                   const Eigen::SparseMatrix<double>& held = {});

/// Unit radial patterns of the wave generator's stations, one per station all round (not paired: θ and θ + π held
/// separately), on the bore over the generator's band, at the analysis's spacing (station_spacing): 3·n_nodes × m,
/// each 1 N outward spread by the stations' linear hat (fem/loads.hpp AngularHats), so Lᵀ·u is the hat-weighted mean
/// radial displacement. Throws InputError when the model has no wave generator or no bore face lies in its band.
Eigen::SparseMatrix<double> generator_radial_holds(const FlexsplineModel& c, const TetMesh& mesh);

/// K + K_σ(base_u) as an upper triangle on the same equations: the tangent stiffness about a base state (the
/// generator's deformation) whose stress stiffens (tension) or softens (compression) the body, linear in that stress.
SymmetricCsc stiffness_with_prestress(const TetMesh& mesh, const Material& material, const DofMap& dofs,
                                      const SymmetricCsc& K, const Eigen::VectorXd& base_u);

/// The case's torsion buckling: prestress = the torque case's loads (torque_load_vector at load.torque_Nm, 1 N·m when
/// it is 0) on the system's clamp, with the generator's stations held radially in the prestress and the buckling
/// problem when `generator_held` (the generator as a bilateral support; needs a wave generator). K is assembled again
/// (the system keeps only its factor). λ multiplies the case's torque.
///
/// `base_u` (3·n_nodes; empty: none) is a state the torque is added to, the generator's deformation: the eigenproblem
/// is (K + K_σ(base) + λ·K_σ(torque))·x = 0, on the base's tangent (stiffness_with_prestress, factorised again), the
/// torque's prestress linear on K as without a base; λ multiplies the torque alone (the base stays as it is). Linear
/// in the base's stress: its displacements do not change the geometry. A base that is a times the torque case's
/// displacement gives λ − a exactly (K + (a + λ)·K_σ(torque)).
BucklingResultTet10 torsion_buckling_tet10(const FlexsplineModel& c, const TetMesh& mesh,
                                           const FlexsplineSystem& system, bool generator_held = false,
                                           const Tet10BucklingOptions& o = {}, const Eigen::VectorXd& base_u = {});

}  // namespace sw
