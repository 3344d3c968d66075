#include "fem/fourier_buckling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/LU>
#include <Eigen/Sparse>
#include <Spectra/SymGEigsSolver.h>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/fourier_analysis.hpp"

namespace sw {
namespace {

using namespace fourier;

// Lanczos basis size: Spectra's advice is ncv ≥ 2·nev (nev = 1 here); 20 vectors keep restarts few when the largest
// ν are close (neighbouring axial wave patterns of one harmonic), for 20 vectors of memory.
constexpr int kLanczosVectors = 20;
constexpr int kLanczosMaxRestarts = 1000;  // Spectra's default maxit
// A harmonic whose largest ν is below this fraction of the largest so far is not coupled by the prestress (ν is
// round-off): its load factor is infinite.
constexpr double kNoCoupling = 1e-14;

using SparseMatrix = Eigen::SparseMatrix<double>;
using Mat9x18 = Eigen::Matrix<double, 9, 18>;

/// Displacement-gradient amplitudes of harmonic n at a point: row 3k + i is ∂u_k/∂x_i in the local frame (k, i in
/// r, θ, z; the header's table), columns node-major (a, b, c). Both families have these amplitudes; the rows marked
/// in kSineRow go with sin nθ in the symmetric family (−cos nθ in the antisymmetric one), the others with cos nθ
/// (sin nθ).
struct GradientPoint {
  Mat9x18 G;
  double r = 0, det = 0;
};
constexpr bool kSineRow[9] = {false, true, false, true, false, true, false, true, false};

GradientPoint gradient_matrix(const Mat6x2& X, double xi, double eta, int n) {
  const ShapePoint sp = shape_point(X, xi, eta);
  const auto& N = sp.N;
  const auto& D = sp.dN;  // rows d/dr, d/dz
  GradientPoint p;
  p.det = sp.det;
  p.r = sp.r;
  const double ir = 1.0 / p.r;
  p.G.setZero();
  for (int j = 0; j < 6; ++j) {
    const double Nr = D(0, j), Nz = D(1, j), Nj = N[j] * ir;
    const int a = 3 * j, b = a + 1, c = a + 2;
    // Symmetric family u_r = a cos, u_θ = b sin, u_z = c cos (the antisymmetric one: the same amplitudes).
    p.G(0, a) = Nr;                          // u_r,r
    p.G(1, a) = -n * Nj, p.G(1, b) = -Nj;    // (u_r,θ − u_θ)/r = −(n·a + b)/r · sin
    p.G(2, a) = Nz;                          // u_r,z
    p.G(3, b) = Nr;                          // u_θ,r
    p.G(4, a) = Nj, p.G(4, b) = n * Nj;      // (u_θ,θ + u_r)/r = (n·b + a)/r · cos
    p.G(5, b) = Nz;                          // u_θ,z
    p.G(6, c) = Nr;                          // u_z,r
    p.G(7, c) = -n * Nj;                     // u_z,θ/r = −n·c/r · sin
    p.G(8, c) = Nz;                          // u_z,z
  }
  return p;
}

/// θ integral of (row p's trig function, symmetric family) × (row q's, antisymmetric family) for harmonic n: a cos-type
/// row against a sine-type row gives ∫cos nθ·(−cos nθ) = −C_n, a sine-type against a cos-type ∫sin² = S_n, equal
/// types 0 (C_0 = 2π, S_0 = 0; C_n = S_n = π).
double family_weight(bool p_sine, bool q_sine, int n) {
  if (!p_sine && q_sine) return n == 0 ? -2 * kPi : -kPi;
  if (p_sine && !q_sine) return n == 0 ? 0.0 : kPi;
  return 0.0;
}

/// The torsion shears (τ_rθ, τ_θz) of the prestress at a point of element e: harmonic 0, antisymmetric family, whose
/// stress amplitudes multiply −cos 0 = −1 (fem/fourier_element.hpp's strain_matrix rows 4, 5).
Eigen::Vector2d torsion_shears(const Mat6x2& X, const Eigen::Matrix<double, 18, 1>& b0, double xi, double eta,
                               double shear_modulus) {
  const StrainPoint p = strain_matrix(X, xi, eta, 0);
  const Eigen::Matrix<double, 6, 1> strain = p.B * b0;
  return {-shear_modulus * strain[4], -shear_modulus * strain[5]};
}

/// Element block C_e (18 × 18, rows symmetric family, columns antisymmetric): xᵀ·C_e·y is the cross term of
/// ∫ σ⁰_ij u_k,i u_k,j dV between the families, shears only (the header's argument).
Mat18 element_coupling(const Mat6x2& X, const Eigen::Matrix<double, 18, 1>& b0, double shear_modulus, int n) {
  Mat18 C = Mat18::Zero();
  // (i, j) pairs carrying a shear: (r, θ) and (θ, z), both orders.
  constexpr int kPairs[4][2] = {{0, 1}, {1, 0}, {1, 2}, {2, 1}};
  for (int q = 0; q < 7; ++q) {
    const GradientPoint g = gradient_matrix(X, kRule.xi[q], kRule.eta[q], n);
    const Eigen::Vector2d tau = torsion_shears(X, b0, kRule.xi[q], kRule.eta[q], shear_modulus);
    const double w = kRule.w[q] * std::abs(g.det) * g.r;
    for (int k = 0; k < 3; ++k)
      for (const auto& pair : kPairs) {
        const int i = pair[0], j = pair[1];
        const double sigma = (i == 1 && j == 1) ? 0.0 : (i == 2 || j == 2) ? tau[1] : tau[0];
        const int p = 3 * k + i, r = 3 * k + j;
        const double f = family_weight(kSineRow[p], kSineRow[r], n);
        if (f == 0.0) continue;
        C.noalias() += (w * sigma * f) * g.G.row(p).transpose() * g.G.row(r);
      }
  }
  return C;
}

/// Σ_e of the element couplings on the equations of a numbering (both families share it): n_eq × n_eq, full.
SparseMatrix assemble_coupling(const SectionMesh& s, const HarmonicDofs& d, const Eigen::MatrixXd& b0, double G,
                               int n) {
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(s.triangles.size() * 18 * 18);
  for (std::size_t e = 0; e < s.triangles.size(); ++e) {
    const auto& t = s.triangles[e];
    Eigen::Matrix<double, 18, 1> be;
    for (int a = 0; a < 6; ++a) be.segment<3>(3 * a) = b0.row(t[a]).transpose();
    const Mat18 Ce = element_coupling(coords(s, e), be, G, n);
    for (int p = 0; p < 18; ++p) {
      const std::int64_t ip = d.eq[3 * t[p / 3] + p % 3];
      if (ip < 0) continue;
      const double sp = d.sign[3 * t[p / 3] + p % 3];
      for (int q = 0; q < 18; ++q) {
        const std::int64_t iq = d.eq[3 * t[q / 3] + q % 3];
        if (iq < 0 || Ce(p, q) == 0.0) continue;
        trip.emplace_back(static_cast<int>(ip), static_cast<int>(iq), sp * d.sign[3 * t[q / 3] + q % 3] * Ce(p, q));
      }
    }
  }
  SparseMatrix C(d.n_eq, d.n_eq);
  C.setFromTriplets(trip.begin(), trip.end());
  return C;
}

/// The prestress's torsion amplitudes: anti[0] with only its b column (a, c of the antisymmetric family at n = 0 are
/// no displacement).
Eigen::MatrixXd torsion_amplitudes(const SectionMesh& s, const HarmonicField& prestress) {
  const Eigen::Index nn = static_cast<Eigen::Index>(s.n_nodes());
  if (prestress.anti.empty() || prestress.anti[0].rows() != nn || prestress.anti[0].cols() != 3)
    throw InputError("torsion buckling: the prestress field has no harmonic-0 antisymmetric amplitudes of " +
                     std::to_string(nn) + " x 3 (the section's nodes); pass the torque case of this section");
  Eigen::MatrixXd b0 = Eigen::MatrixXd::Zero(nn, 3);
  b0.col(1) = prestress.anti[0].col(1);
  if (!(b0.cwiseAbs().maxCoeff() > 0.0))
    throw InputError("torsion buckling: the prestress field has no torsion (its harmonic-0 b amplitudes are all 0); "
                     "pass the torque case (T = 1 N·m)");
  return b0;
}

/// K_n as Eigen's view of the factor's upper triangle.
using UpperMap = Eigen::Map<const Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>>;
UpperMap upper_map(const SymmetricCsc& K) {
  return UpperMap(K.n, K.n, static_cast<std::int64_t>(K.nnz()), K.column_start.data(), K.row.data(), K.value.data());
}

/// Spectra's B operation for the regular-inverse mode: B·x = K_n·x and B⁻¹·x by the CHOLMOD factor of K_n.
/// The factor is CholmodFactor's, which offers whole solves (and half solves L⁻¹·P·B for sparse B only, no L⁻ᵀ), so
/// Spectra's Cholesky mode (L⁻¹·A·L⁻ᵀ) is not available; the regular-inverse mode runs Lanczos on K⁻¹·A in the
/// K-inner product instead (self-adjoint there), one more solve per step, and gives the same eigenvalues.
class StiffnessOp {
public:
  using Scalar = double;
  StiffnessOp(const SymmetricCsc& K, const CholmodFactor& factor) : K_(upper_map(K)), factor_(factor) {}
  Eigen::Index rows() const { return K_.rows(); }
  Eigen::Index cols() const { return K_.cols(); }
  void perform_op(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, rows()) =
        K_.selfadjointView<Eigen::Upper>() * Eigen::Map<const Eigen::VectorXd>(x, rows());
  }
  void solve(const double* x, double* y) const {
    Eigen::Map<Eigen::VectorXd>(y, rows()) = factor_.solve(Eigen::Map<const Eigen::VectorXd>(x, rows()));
  }

private:
  UpperMap K_;
  const CholmodFactor& factor_;
};

/// Spectra's A operation: A·x = C·K⁻¹·Cᵀ·x (symmetric, positive semidefinite).
class EliminatedCouplingOp {
public:
  using Scalar = double;
  EliminatedCouplingOp(const SparseMatrix& C, const CholmodFactor& factor) : C_(C), factor_(factor) {}
  Eigen::Index rows() const { return C_.rows(); }
  Eigen::Index cols() const { return C_.cols(); }
  void perform_op(const double* x, double* y) const {
    const Eigen::VectorXd t = C_.transpose() * Eigen::Map<const Eigen::VectorXd>(x, rows());
    Eigen::Map<Eigen::VectorXd>(y, rows()) = C_ * factor_.solve(t);
  }

private:
  const SparseMatrix& C_;
  const CholmodFactor& factor_;
};

/// A rough size of the largest ν (the Rayleigh quotient after three power steps from a fixed start), to scale the
/// problem: Spectra's convergence test is relative to max(|ν|, ε^(2/3) ≈ 4e-11), and the ν of a unit torque are as
/// small as 1e-12 (λ = 1e6). 0 when C does not couple.
double nu_scale(const SymmetricCsc& K, const CholmodFactor& factor, const SparseMatrix& C) {
  Eigen::VectorXd x(C.rows());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = std::sin(1.0 + static_cast<double>(i));
  auto apply = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return C * factor.solve(C.transpose() * v); };
  for (int step = 0; step < 3; ++step) {
    const Eigen::VectorXd y = factor.solve(apply(x));
    if (!(y.norm() > 0)) return 0.0;
    x = y / y.norm();
  }
  const double kx = x.dot(upper_map(K).selfadjointView<Eigen::Upper>() * x);
  return std::max(0.0, x.dot(apply(x)) / kx);
}

/// The largest ν of C·K⁻¹·Cᵀ·x = ν·K·x and its vector (K-normalised); ν = 0 when C does not couple.
std::pair<double, Eigen::VectorXd> largest_eigenpair(const SymmetricCsc& K, const CholmodFactor& factor,
                                                     const SparseMatrix& C, double tolerance, int n) {
  const Eigen::Index size = C.rows();
  const double scale = size < 2 ? 0.0 : nu_scale(K, factor, C);
  if (!(scale > 0)) return {0.0, Eigen::VectorXd::Zero(size)};
  const SparseMatrix Cs = C / std::sqrt(scale);  // A/scale: its largest ν of order 1
  StiffnessOp B(K, factor);
  EliminatedCouplingOp A(Cs, factor);
  const Eigen::Index ncv = std::min<Eigen::Index>(kLanczosVectors, size);
  Spectra::SymGEigsSolver<EliminatedCouplingOp, StiffnessOp, Spectra::GEigsMode::RegularInverse> eig(A, B, 1, ncv);
  eig.init();
  eig.compute(Spectra::SortRule::LargestAlge, kLanczosMaxRestarts, tolerance);
  if (eig.info() != Spectra::CompInfo::Successful)
    throw InputError("torsion buckling: the Lanczos iteration of harmonic " + std::to_string(n) +
                     " did not converge in " + std::to_string(kLanczosMaxRestarts) +
                     " restarts; raise buckling tolerance (now " + std::to_string(tolerance) + ")");
  return {eig.eigenvalues()[0] * scale, eig.eigenvectors().col(0)};
}

/// One numbering's stiffness polynomial and factor (n = 0, 1, ≥ 2 differ by the axis conditions), reused across
/// harmonics: the factor is analysed once and refactorised on the same pattern.
struct Numbering {
  std::optional<GlobalPolynomial> poly;
  std::unique_ptr<CholmodFactor> factor;
};

/// Harmonic n's system: its numbering, K_n, its factor and the coupling C_n (at n = 0 the symmetric K_σ,0 = C + Cᵀ).
struct HarmonicSystem {
  const HarmonicDofs* dofs = nullptr;
  SymmetricCsc K;
  const CholmodFactor* factor = nullptr;
  SparseMatrix C;
};

class BucklingScan {
public:
  BucklingScan(const SectionMesh& s, const Material& m, const std::vector<bool>& fixed, const Eigen::MatrixXd& b0)
      : s_(s), m_(m), fixed_(fixed), b0_(b0), axis_(axis_nodes(s)), poly_(element_polynomials(s, m)) {}

  HarmonicSystem system(int n) {
    Numbering& k = numbering_[std::min(n, 2)];
    if (!k.poly) k.poly = assemble_polynomial(s_, poly_, number_dofs(s_.n_nodes(), n, fixed_, axis_));
    HarmonicSystem h;
    h.dofs = &k.poly->dofs;
    h.K = k.poly->at(n);
    if (k.factor) k.factor->refactorise(h.K);
    else k.factor = std::make_unique<CholmodFactor>(h.K, k.poly->dofs.node_of_eq);
    h.factor = k.factor.get();
    h.C = assemble_coupling(s_, *h.dofs, b0_, m_.shear_modulus_Pa(), n);
    if (n == 0) h.C = SparseMatrix(h.C + SparseMatrix(h.C.transpose()));
    return h;
  }

private:
  const SectionMesh& s_;
  const Material& m_;
  const std::vector<bool>& fixed_;
  Eigen::MatrixXd b0_;
  std::vector<bool> axis_;
  std::vector<ElementPolynomial> poly_;
  Numbering numbering_[3];
};

/// Which field component each equation carries (0 a, 1 b, 2 c).
std::vector<int> component_of_equation(const HarmonicDofs& d) {
  std::vector<int> comp(static_cast<std::size_t>(d.n_eq), 0);
  for (std::size_t i = 0; i < d.eq.size(); ++i)
    if (d.eq[i] >= 0 && d.sign[i] > 0) comp[static_cast<std::size_t>(d.eq[i])] = static_cast<int>(i % 3);
  return comp;
}

/// The mode for +λ from a vector w of ν's eigenspace, z = s − λ·K⁻¹·Cᵀ·s with s a part of w on one side of the
/// coupling (n ≥ 1: w is the symmetric family and the result's second half the antisymmetric one; n = 0: s is the
/// larger of w's (a, c) and b parts, and z one field). Fills result.mode and result.mode_residual.
void set_mode(const HarmonicSystem& h, int n, double lambda, const Eigen::VectorXd& w, std::size_t n_nodes,
              BucklingResult& result) {
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n_nodes), 3);
  const UpperMap Kmap = upper_map(h.K);
  const auto K = Kmap.selfadjointView<Eigen::Upper>();
  Eigen::MatrixXd sym, anti;
  double residual = 0;
  if (n >= 1) {
    const Eigen::VectorXd x = w, y = -lambda * h.factor->solve(Eigen::VectorXd(h.C.transpose() * x));
    const Eigen::VectorXd rx = K * x + lambda * (h.C * y), ry = K * y + lambda * (h.C.transpose() * x);
    residual = std::sqrt((rx.squaredNorm() + ry.squaredNorm()) /
                         (Eigen::VectorXd(K * x).squaredNorm() + Eigen::VectorXd(K * y).squaredNorm()));
    sym = to_nodes(*h.dofs, x, zero);
    anti = to_nodes(*h.dofs, y, zero);
  } else {
    const std::vector<int> comp = component_of_equation(*h.dofs);
    Eigen::VectorXd ac = w, b = w;
    for (Eigen::Index i = 0; i < w.size(); ++i) (comp[static_cast<std::size_t>(i)] == 1 ? ac : b)[i] = 0;
    const Eigen::VectorXd s = ac.norm() >= b.norm() ? ac : b;
    const Eigen::VectorXd z = s - lambda * h.factor->solve(Eigen::VectorXd(h.C * s));
    const Eigen::VectorXd Kz = K * z;
    residual = (Kz + lambda * (h.C * z)).norm() / Kz.norm();
    const Eigen::MatrixXd field = to_nodes(*h.dofs, z, zero);
    sym = field;
    sym.col(1).setZero();
    anti = zero;
    anti.col(1) = field.col(1);
  }
  const double scale = std::max(sym.cwiseAbs().maxCoeff(), anti.cwiseAbs().maxCoeff());
  result.mode.sym.assign(static_cast<std::size_t>(n) + 1, Eigen::MatrixXd());
  result.mode.anti.assign(static_cast<std::size_t>(n) + 1, Eigen::MatrixXd());
  result.mode.sym[static_cast<std::size_t>(n)] = sym / scale;
  result.mode.anti[static_cast<std::size_t>(n)] = anti / scale;
  result.mode_residual = residual;
}

void check_options(const BucklingOptions& o) {
  if (o.max_harmonic < 0)
    throw InputError("buckling.max_harmonic = " + std::to_string(o.max_harmonic) + "; must be >= 0 (0: default " +
                     std::to_string(kDefaultBucklingHarmonics) + ")");
  if (o.rises_to_stop < 0)
    throw InputError("buckling.rises_to_stop = " + std::to_string(o.rises_to_stop) + "; must be >= 0 (0: scan all)");
  if (!(o.tolerance > 0.0 && o.tolerance < 1e-2))
    throw InputError("buckling.tolerance = " + std::to_string(o.tolerance) + "; must be in (0, 0.01)");
}

}  // namespace

BucklingResult torsion_buckling_fourier(const SectionMesh& s, const Material& m, const std::vector<bool>& fixed,
                                        const HarmonicField& prestress_unit_torque, const BucklingOptions& o) {
  check_options(o);
  if (fixed.size() != 3 * s.n_nodes())
    throw InputError("torsion buckling: fixed has " + std::to_string(fixed.size()) + " entries; must be 3 x " +
                     std::to_string(s.n_nodes()) + " (the section's nodes)");
  const Eigen::MatrixXd b0 = torsion_amplitudes(s, prestress_unit_torque);
  const int N = o.max_harmonic > 0 ? o.max_harmonic : kDefaultBucklingHarmonics;
  BucklingScan scan(s, m, fixed, b0);
  BucklingResult result;
  result.load_factor = std::numeric_limits<double>::infinity();
  double largest_nu = 0;
  int rises = 0;
  for (int n = 0; n <= N; ++n) {
    HarmonicSystem h = scan.system(n);
    const auto [nu, w] = largest_eigenpair(h.K, *h.factor, h.C, o.tolerance, n);
    largest_nu = std::max(largest_nu, nu);
    const double lambda = nu > kNoCoupling * largest_nu && nu > 0 ? 1.0 / std::sqrt(nu)
                                                                  : std::numeric_limits<double>::infinity();
    const double previous = result.per_harmonic.empty() ? lambda : result.per_harmonic.back().load_factor;
    result.per_harmonic.push_back({n, lambda});
    if (lambda < result.load_factor) {
      result.load_factor = lambda;
      result.n = n;
      set_mode(h, n, lambda, w, s.n_nodes(), result);
      rises = 0;
    } else {
      rises = lambda > previous ? rises + 1 : 0;
      if (o.rises_to_stop > 0 && rises >= o.rises_to_stop) break;
    }
  }
  if (!std::isfinite(result.load_factor))
    throw InputError("torsion buckling: no harmonic 0.." + std::to_string(N) +
                     " is coupled by the prestress; check that it is the torque case of this section");
  return result;
}

BucklingResult torsion_buckling_fourier(const FlexsplineModel& c, const FourierSolution& solution,
                                        const BucklingOptions& o) {
  const std::size_t nn = solution.section.n_nodes();
  if (solution.clamped.size() != nn)
    throw InputError("torsion buckling: the solution's clamp marks " + std::to_string(solution.clamped.size()) +
                     " nodes; must be " + std::to_string(nn) + " (the solution of analyse_flexspline_fourier)");
  std::vector<bool> fixed(3 * nn);
  for (std::size_t i = 0; i < nn; ++i) fixed[3 * i] = fixed[3 * i + 1] = fixed[3 * i + 2] = solution.clamped[i];
  return torsion_buckling_fourier(solution.section, c.material, fixed, solution.torque_unit, o);
}

double geometric_stiffness_energy(const SectionMesh& s, const Material& m, const HarmonicField& prestress, int n,
                                  const Eigen::MatrixXd& sym, const Eigen::MatrixXd& anti) {
  const Eigen::Index nn = static_cast<Eigen::Index>(s.n_nodes());
  if (n < 0) throw InputError("geometric_stiffness_energy: n = " + std::to_string(n) + "; must be >= 0");
  if (sym.rows() != nn || sym.cols() != 3 || anti.rows() != nn || anti.cols() != 3)
    throw InputError("geometric_stiffness_energy: amplitudes must be " + std::to_string(nn) + " x 3 (the section's "
                     "nodes, a, b, c)");
  const Eigen::MatrixXd b0 = torsion_amplitudes(s, prestress);
  const HarmonicDofs d = number_dofs(s.n_nodes(), n, std::vector<bool>(3 * s.n_nodes(), false), axis_nodes(s));
  const SparseMatrix C = assemble_coupling(s, d, b0, m.shear_modulus_Pa(), n);
  // Amplitudes onto the equations (a tied dof carries its equation's value times its sign).
  auto gather = [&](const Eigen::MatrixXd& U) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(d.n_eq);
    for (Eigen::Index i = 0; i < nn; ++i)
      for (int k = 0; k < 3; ++k)
        if (d.eq[3 * i + k] >= 0 && d.sign[3 * i + k] > 0) x[d.eq[3 * i + k]] = U(i, k);
    return x;
  };
  if (n >= 1) return 2.0 * gather(sym).dot(C * gather(anti));
  Eigen::MatrixXd field = sym;
  field.col(1) = anti.col(1);
  const Eigen::VectorXd z = gather(field);
  return 2.0 * z.dot(C * z);  // zᵀ·(C + Cᵀ)·z
}

}  // namespace sw
