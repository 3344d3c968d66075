#include "fem/tet10_buckling.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/Sparse>
#include <Spectra/SymGEigsSolver.h>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/elasticity.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/loads.hpp"

namespace sw {
namespace {

// The stiffness's 4-point degree-2 rule for the unit tetrahedron (fem/elasticity.cpp): a = (5 + 3√5)/20,
// b = (5 − √5)/20, weights 1/24 (a quarter of the unit tet's volume 1/6). CalculiX's C3D10 integrates with the same
// 4 points (its manual's element C3D10; tests/fem/test_tet10_buckling.cpp agrees with ccx *BUCKLE to 7e-8). On K_σ
// the integrand (linear σ⁰ × two linear gradients) is cubic, so the rule is not exact there; it is the one both codes
// use, which makes their discrete problems the same.
constexpr double kGaussA = 0.5854101966249685;
constexpr double kGaussB = 0.1381966011250105;
constexpr double kGaussWeight = 1.0 / 24.0;
const std::array<Eigen::Vector3d, 4> kGaussPoints = {
    Eigen::Vector3d(kGaussB, kGaussB, kGaussB), Eigen::Vector3d(kGaussA, kGaussB, kGaussB),
    Eigen::Vector3d(kGaussB, kGaussA, kGaussB), Eigen::Vector3d(kGaussB, kGaussB, kGaussA)};
// Lanczos basis: Spectra advises ncv ≥ 2·nev; torsion's ± pairs are nearly degenerate in |μ|, so a wider basis (at
// least 24 vectors) keeps the restarts few, for 24 vectors of memory.
constexpr int kMinLanczosVectors = 24;
constexpr int kLanczosMaxRestarts = 1000;  // Spectra's default maxit
constexpr int kSolveChunk = 24;             // right-hand sides per solve for W = K⁻¹·L (memory: n_eq × 24 doubles)

using SparseMatrix = Eigen::SparseMatrix<double>;
using UpperMap = Eigen::Map<const Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>>;
UpperMap upper_map(const SymmetricCsc& K) {
  return UpperMap(K.n, K.n, static_cast<std::int64_t>(K.nnz()), K.column_start.data(), K.row.data(), K.value.data());
}

/// Gradients of the shape functions in physical coordinates (10 × 3) and det J at a natural point.
Eigen::Matrix<double, 10, 3> shape_gradients(const ElementCoords& X, const Eigen::Vector3d& xi, double& det) {
  const Eigen::Matrix<double, 10, 3> dN = tet10_shape_gradient(xi);
  const Eigen::Matrix3d J = X.transpose() * dN;  // J(i, j) = ∂x_i/∂ξ_j
  det = J.determinant();
  return dN * J.inverse();
}

/// Cauchy stress tensor (Pa) from a Voigt vector (xx, yy, zz, yz, xz, xy).
Eigen::Matrix3d stress_tensor(const Eigen::Matrix<double, 6, 1>& s) {
  Eigen::Matrix3d S;
  S << s[0], s[5], s[4], s[5], s[1], s[3], s[4], s[3], s[2];
  return S;
}

/// The element's scalar geometric block H (10 × 10): K_σ,e = H ⊗ I₃ (node a, b: H_ab on the diagonal of the 3 × 3).
Eigen::Matrix<double, 10, 10> element_geometric(const ElementCoords& X, const Matrix6d& D,
                                                const Eigen::Matrix<double, 30, 1>& ue) {
  Eigen::Matrix<double, 10, 10> H = Eigen::Matrix<double, 10, 10>::Zero();
  for (const auto& xi : kGaussPoints) {
    double det = 0;
    const Eigen::Matrix<double, 10, 3> G = shape_gradients(X, xi, det);
    if (!(det > 0)) throw InputError("geometric stiffness: an element is inverted at a Gauss point (det J = " +
                                     std::to_string(det) + "); check the mesh");
    const Eigen::Matrix3d S = stress_tensor(D * (tet10_strain_matrix(X, xi) * ue));
    H.noalias() += (kGaussWeight * det) * (G * S * G.transpose());
  }
  return H;
}

/// Spectra's B operation for the regular-inverse mode: B·x = K·x and B⁻¹·x by the factor of K, with the constraints
/// Lᵀ·x = 0 when W = K⁻¹·L is given (B⁻¹ = K_c⁻¹, the header's constrained inverse).
class StiffnessOp {
public:
  using Scalar = double;
  StiffnessOp(const SymmetricCsc& K, const LinearSolver& factor, const SparseMatrix& L, const Eigen::MatrixXd& W)
      : K_(upper_map(K)), factor_(factor), L_(L), W_(W) {
    if (W_.cols() > 0) C_.compute(Eigen::MatrixXd(L_.transpose() * W_));
  }
  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, rows()) =
        K_.selfadjointView<Eigen::Upper>() * Eigen::Map<const Eigen::VectorXd>(x, rows());
  }
  void solve(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, rows()) = inverse(Eigen::Map<const Eigen::VectorXd>(x, rows()));
  }
  /// K_c⁻¹·b.
  Eigen::VectorXd inverse(const Eigen::VectorXd& b) const {
    Eigen::VectorXd y = factor_.solve(b);
    if (W_.cols() > 0) y -= W_ * C_.solve(Eigen::VectorXd(L_.transpose() * y));
    return y;
  }
  Eigen::VectorXd times(const Eigen::VectorXd& x) const { return K_.selfadjointView<Eigen::Upper>() * x; }

private:
  UpperMap K_;
  const LinearSolver& factor_;
  const SparseMatrix& L_;
  const Eigen::MatrixXd& W_;
  Eigen::LDLT<Eigen::MatrixXd> C_;
};

/// Spectra's A operation: K_σ / scale.
class GeometricOp {
public:
  using Scalar = double;
  explicit GeometricOp(const SparseMatrix& Ks) : Ks_(Ks) {}
  Eigen::Index rows() const { return Ks_.rows(); }
  Eigen::Index cols() const { return Ks_.cols(); }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, rows()) = Ks_ * Eigen::Map<const Eigen::VectorXd>(x, rows());
  }

private:
  const SparseMatrix& Ks_;
};

/// A deterministic start in the constrained subspace: K_c⁻¹ of a smooth pseudo-random vector.
Eigen::VectorXd start_vector(const StiffnessOp& B) {
  Eigen::VectorXd r(B.rows());
  for (Eigen::Index i = 0; i < r.size(); ++i) r[i] = std::sin(1.0 + static_cast<double>(i));
  return B.inverse(r);
}

/// |μ| of the Rayleigh quotient after three power steps of K_c⁻¹·K_σ: the size the problem is scaled by (a unit
/// torque's μ can lie near Spectra's absolute floor ε^(2/3) ≈ 4e-11).
double mu_scale(const StiffnessOp& B, const SparseMatrix& Ks, Eigen::VectorXd x) {
  for (int step = 0; step < 3; ++step) {
    const Eigen::VectorXd y = B.inverse(Ks * x);
    if (!(y.norm() > 0)) return 0.0;
    x = y / y.norm();
  }
  return std::abs(x.dot(Ks * x) / x.dot(B.times(x)));
}

/// Free-dof restriction of the held patterns (n_eq × m).
SparseMatrix restrict_columns(const DofMap& dofs, const SparseMatrix& held) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(held.nonZeros()));
  for (Eigen::Index j = 0; j < held.cols(); ++j)
    for (SparseMatrix::InnerIterator it(held, j); it; ++it)
      if (const std::int64_t q = dofs.equation[static_cast<std::size_t>(it.row())]; q >= 0)
        entries.emplace_back(static_cast<Eigen::Index>(q), j, it.value());
  SparseMatrix L(dofs.n_equations, held.cols());
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

/// W = K⁻¹·L in chunks of right-hand sides.
Eigen::MatrixXd solve_columns(const LinearSolver& factor, const SparseMatrix& L) {
  Eigen::MatrixXd W(L.rows(), L.cols());
  for (Eigen::Index j0 = 0; j0 < L.cols(); j0 += kSolveChunk) {
    const Eigen::Index k = std::min<Eigen::Index>(kSolveChunk, L.cols() - j0);
    W.middleCols(j0, k) = factor.solve(Eigen::MatrixXd(L.middleCols(j0, k)));
  }
  return W;
}

void check_options(const Tet10BucklingOptions& o) {
  if (o.modes < 1) throw InputError("buckling.modes = " + std::to_string(o.modes) + "; must be >= 1");
  if (!(o.tolerance > 0.0 && o.tolerance < 1e-2))
    throw InputError("buckling.tolerance = " + std::to_string(o.tolerance) + "; must be in (0, 0.01)");
}

}  // namespace

SparseMatrix geometric_stiffness(const TetMesh& mesh, const Material& material, const DofMap& dofs,
                                 const Eigen::VectorXd& prestress_u) {
  const std::size_t nn = mesh.n_nodes();
  if (dofs.equation.size() != 3 * nn)
    throw InputError("geometric stiffness: the dof map has " + std::to_string(dofs.equation.size()) +
                     " dofs; must be 3 x " + std::to_string(nn) + " (the mesh's nodes)");
  if (static_cast<std::size_t>(prestress_u.size()) != 3 * nn)
    throw InputError("geometric stiffness: the prestress displacement has " + std::to_string(prestress_u.size()) +
                     " entries; must be 3 x " + std::to_string(nn) + " (the mesh's nodes)");
  const Matrix6d D = elasticity_matrix(material);
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(mesh.tets.size() * 300);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const auto& t = mesh.tets[e];
    Eigen::Matrix<double, 30, 1> ue;
    for (int a = 0; a < 10; ++a) ue.segment<3>(3 * a) = prestress_u.segment<3>(3 * static_cast<Eigen::Index>(t[a]));
    const Eigen::Matrix<double, 10, 10> H = element_geometric(element_coordinates(mesh, e), D, ue);
    for (int a = 0; a < 10; ++a)
      for (int b = 0; b < 10; ++b)
        for (int k = 0; k < 3; ++k) {
          const std::int64_t p = dofs.equation[3 * static_cast<std::size_t>(t[a]) + k];
          const std::int64_t q = dofs.equation[3 * static_cast<std::size_t>(t[b]) + k];
          if (p >= 0 && q >= 0) entries.emplace_back(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(q), H(a, b));
        }
  }
  SparseMatrix Ks(dofs.n_equations, dofs.n_equations);
  Ks.setFromTriplets(entries.begin(), entries.end());
  return Ks;
}

namespace {

/// The pencil on the operator B (K, and K_c⁻¹ when constrained): the body of buckling_tet10.
BucklingResultTet10 solve_pencil(const TetMesh& mesh, const Material& material, const DofMap& dofs,
                                 StiffnessOp& B, const Eigen::VectorXd& prestress_u,
                                 const Tet10BucklingOptions& o) {
  const Eigen::Index n = dofs.n_equations;
  const int nev = std::min<int>(o.modes, static_cast<int>(n) - 1);
  const SparseMatrix Ks = geometric_stiffness(mesh, material, dofs, prestress_u);
  const Eigen::VectorXd start = start_vector(B);
  const double scale = mu_scale(B, Ks, start);
  if (!(scale > 0))
    throw InputError("tet10 buckling: the prestress's geometric stiffness is zero (no stress); pass the displacement "
                     "of a load case");
  const SparseMatrix Ks_scaled = Ks / scale;
  GeometricOp A(Ks_scaled);
  const Eigen::Index ncv = std::min<Eigen::Index>(std::max(kMinLanczosVectors, 4 * nev + 1), n);
  Spectra::SymGEigsSolver<GeometricOp, StiffnessOp, Spectra::GEigsMode::RegularInverse> eig(A, B, nev, ncv);
  eig.init(start.data());
  eig.compute(Spectra::SortRule::LargestMagn, kLanczosMaxRestarts, o.tolerance);
  if (eig.info() != Spectra::CompInfo::Successful)
    throw InputError("tet10 buckling: the Lanczos iteration did not converge in " +
                     std::to_string(kLanczosMaxRestarts) + " restarts at tolerance " + std::to_string(o.tolerance) +
                     "; raise buckling.tolerance or ask fewer modes");
  const Eigen::VectorXd mu = eig.eigenvalues() * scale;
  const Eigen::MatrixXd X = eig.eigenvectors();
  std::vector<int> order(static_cast<std::size_t>(mu.size()));
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return std::abs(mu[a]) > std::abs(mu[b]); });
  BucklingResultTet10 r;
  const Eigen::VectorXd zeros = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * mesh.n_nodes()));
  for (const int i : order) {
    const double lambda = -1.0 / mu[i];
    const Eigen::VectorXd x = X.col(i);
    // The residual in the energy norm of the constrained problem: e = x + λ·K_c⁻¹·K_σ·x (the held patterns'
    // reactions drop out), ‖e‖_K / ‖x‖_K.
    const Eigen::VectorXd e = x + lambda * B.inverse(Ks * x);
    r.load_factors.push_back(lambda);
    r.residuals.push_back(std::sqrt(std::abs(e.dot(B.times(e))) / x.dot(B.times(x))));
    const Eigen::VectorXd mode = expand_to_full(dofs, x, zeros);
    r.modes.push_back(mode / mode.cwiseAbs().maxCoeff());
    if (lambda > 0 && (r.smallest_positive == 0 || lambda < r.smallest_positive)) r.smallest_positive = lambda;
  }
  return r;
}

}  // namespace

BucklingResultTet10 buckling_tet10(const TetMesh& mesh, const Material& material, const DofMap& dofs,
                                   const SymmetricCsc& K, const LinearSolver& K_factor,
                                   const Eigen::VectorXd& prestress_u, const Tet10BucklingOptions& o,
                                   const SparseMatrix& held) {
  check_options(o);
  if (K.n != dofs.n_equations)
    throw InputError("tet10 buckling: K has " + std::to_string(K.n) + " equations; the dof map " +
                     std::to_string(dofs.n_equations));
  if (held.cols() > 0 && static_cast<std::size_t>(held.rows()) != 3 * mesh.n_nodes())
    throw InputError("tet10 buckling: the held patterns have " + std::to_string(held.rows()) + " rows; must be 3 x " +
                     std::to_string(mesh.n_nodes()) + " (the mesh's nodes)");
  const SparseMatrix L = held.cols() > 0 ? restrict_columns(dofs, held) : SparseMatrix(dofs.n_equations, 0);
  const Eigen::MatrixXd W = L.cols() > 0 ? solve_columns(K_factor, L) : Eigen::MatrixXd(dofs.n_equations, 0);
  StiffnessOp B(K, K_factor, L, W);
  return solve_pencil(mesh, material, dofs, B, prestress_u, o);
}

SparseMatrix generator_radial_holds(const FlexsplineModel& c, const TetMesh& mesh) {
  if (!c.wave_generator)
    throw InputError("tet10 buckling: the generator's stations are held, but the model has no [wave_generator]");
  const auto& w = *c.wave_generator;
  const double z_wg = c.flexspline.length_m - w.axial_position_m;
  const auto faces = select_faces(mesh, kSurfaceInner, [&](const Eigen::Vector3d& x) {
    return std::abs(x[2] - z_wg) <= 0.5 * w.band_width_m;
  });
  if (faces.empty())
    throw InputError("tet10 buckling: no bore faces in the generator's band at z = " + std::to_string(z_wg * 1e3) +
                     " mm; check wave_generator.axial_position_mm / band_width_mm");
  const AngularHats hats(mesh, faces);
  const double spacing = station_spacing(c);
  const int stations = static_cast<int>(std::lround(2 * kPi / spacing));
  std::vector<Eigen::Triplet<double>> entries;
  int column = 0;
  for (int k = 0; k < stations; ++k) {
    const Eigen::VectorXd f =
        hats.load(k * spacing, spacing, [](double t) { return Eigen::Vector3d(std::cos(t), std::sin(t), 0.0); });
    if (f.size() == 0) continue;
    for (Eigen::Index i = 0; i < f.size(); ++i)
      if (f[i] != 0.0) entries.emplace_back(i, column, f[i]);
    ++column;
  }
  SparseMatrix L(static_cast<Eigen::Index>(3 * mesh.n_nodes()), column);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

SymmetricCsc stiffness_with_prestress(const TetMesh& mesh, const Material& material, const DofMap& dofs,
                                      const SymmetricCsc& K, const Eigen::VectorXd& base_u) {
  const SparseMatrix Ks = geometric_stiffness(mesh, material, dofs, base_u);
  using Upper64 = Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>;
  std::vector<Eigen::Triplet<double, std::int64_t>> entries;
  entries.reserve(K.nnz() + static_cast<std::size_t>(Ks.nonZeros() / 2 + K.n));
  for (std::int64_t j = 0; j < K.n; ++j)
    for (std::int64_t k = K.column_start[j]; k < K.column_start[j + 1]; ++k) entries.emplace_back(K.row[k], j, K.value[k]);
  for (Eigen::Index j = 0; j < Ks.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(Ks, j); it; ++it)
      if (it.row() <= it.col()) entries.emplace_back(it.row(), it.col(), it.value());
  Upper64 sum(K.n, K.n);
  sum.setFromTriplets(entries.begin(), entries.end());
  sum.makeCompressed();
  SymmetricCsc out;
  out.n = K.n;
  out.column_start.assign(sum.outerIndexPtr(), sum.outerIndexPtr() + K.n + 1);
  out.row.assign(sum.innerIndexPtr(), sum.innerIndexPtr() + sum.nonZeros());
  out.value.assign(sum.valuePtr(), sum.valuePtr() + sum.nonZeros());
  return out;
}

BucklingResultTet10 torsion_buckling_tet10(const FlexsplineModel& c, const TetMesh& mesh,
                                           const FlexsplineSystem& system, bool generator_held,
                                           const Tet10BucklingOptions& o, const Eigen::VectorXd& base_u) {
  check_options(o);
  const double T = c.load.torque_Nm != 0.0 ? c.load.torque_Nm : 1.0;
  const SparseMatrix held = generator_held ? generator_radial_holds(c, mesh) : SparseMatrix();
  progress("buckling: assemble K again and K_sigma of the torque case (" + std::to_string(T) + " N m)" +
           (generator_held ? ", " + std::to_string(held.cols()) + " generator stations held radially" : "") +
           (base_u.size() ? "; K + K_sigma of the base state factorised for the eigenproblem" : ""));
  const SymmetricCsc K = assemble_stiffness(mesh, c.material, system.dofs);
  // The torque's prestress, linear on K: K_c⁻¹·F of its loads on the free dofs (the held stations included).
  const SparseMatrix L = held.cols() > 0 ? restrict_columns(system.dofs, held) : SparseMatrix(K.n, 0);
  const Eigen::MatrixXd W = L.cols() > 0 ? solve_columns(*system.factor, L) : Eigen::MatrixXd(K.n, 0);
  StiffnessOp B(K, *system.factor, L, W);
  const Eigen::VectorXd f = restrict_to_free(system.dofs, torque_load_vector(c, mesh, T));
  const Eigen::VectorXd u =
      expand_to_full(system.dofs, B.inverse(f), Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(mesh.n_nodes())));
  if (!base_u.size()) return solve_pencil(mesh, c.material, system.dofs, B, u, o);
  // About the base state: (K + K_σ(base) + λ·K_σ(torque))·x = 0, the pencil on the base's tangent.
  const SymmetricCsc Kb = stiffness_with_prestress(mesh, c.material, system.dofs, K, base_u);
  const CholmodFactor tangent(Kb, equation_nodes(system.dofs));
  const Eigen::MatrixXd Wb = L.cols() > 0 ? solve_columns(tangent, L) : Eigen::MatrixXd(K.n, 0);
  StiffnessOp Bb(Kb, tangent, L, Wb);
  return solve_pencil(mesh, c.material, system.dofs, Bb, u, o);
}

}  // namespace sw
