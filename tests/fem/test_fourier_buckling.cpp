// Torsion buckling on the harmonic solver (fem/fourier_buckling.hpp): a thin tube against the moderate-length closed
// form of shell theory, the load factor's symmetry in the torque's sign and its 1/T scaling, the geometric stiffness
// against a direct 3-D integral of σ⁰_ij u_k,i u_k,j, and the error paths.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

#include "common/error.hpp"
#include "fem/fourier_analysis.hpp"
#include "fem/fourier_buckling.hpp"
#include "fem/fourier_section.hpp"
#include "fem/fourier_solver.hpp"
#include "tests/input_error.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;

/// A plain tube of mid-surface radius R, wall t, length L, solved for its torque case (T = 1 N·m at z = L, clamp
/// at z = 0) on the given section: the prestress.
FlexsplineModel tube_model(double R, double t, double L) {
  FlexsplineModel c;
  c.flexspline.shape = FlexsplineShape::Tube;
  c.flexspline.teeth = TeethModel::None;
  c.flexspline.inner_radius_m = R - t / 2;
  c.flexspline.wall_thickness_m = t;
  c.flexspline.length_m = L;
  c.load.torque_Nm = 1.0;
  c.solver.method = SolverMethod::Fourier;
  c.solver.harmonics = 0;
  return c;
}

struct Tube {
  double R, t, L;
  FlexsplineModel model;
  FourierSolution solution;  // its torque case on the section
};
Tube solve_tube(double R, double t, double L, int layers, int cells_along) {
  Tube tube{R, t, L, tube_model(R, t, L), {}};
  tube.solution = analyse_section_fourier(tube.model, mesh_annulus_section(R - t / 2, R + t / 2, L, layers, cells_along));
  return tube;
}

enum class Ends { Clamped, SimplySupported };

/// Supports of the buckling problem (every harmonic). Clamped: every dof of the end z = 0, and the loaded end z = L
/// held radially and axially but free to turn (u_θ free). Simply supported (the classical shell's: w = v = 0 on the
/// mid-surface circle of each end, free to rotate about it, axial displacement free at the loaded end): a and b of the
/// mid-surface node at both ends, c there only at z = 0 (the axial rigid mode).
std::vector<bool> tube_supports(const Tube& tube, Ends ends) {
  const SectionMesh& s = tube.solution.section;
  std::vector<bool> fixed(3 * s.n_nodes(), false);
  const double tol = 1e-9 * tube.L;
  for (std::size_t i = 0; i < s.n_nodes(); ++i) {
    const double r = s.nodes(static_cast<Eigen::Index>(i), 0), z = s.nodes(static_cast<Eigen::Index>(i), 1);
    const bool start = z < tol, end = z > tube.L - tol, mid = std::abs(r - tube.R) < tol;
    if (ends == Ends::Clamped) {
      if (start) fixed[3 * i] = fixed[3 * i + 1] = fixed[3 * i + 2] = true;
      if (end) fixed[3 * i] = fixed[3 * i + 2] = true;
    } else if (mid && (start || end)) {
      fixed[3 * i] = fixed[3 * i + 1] = true;
      fixed[3 * i + 2] = start;
    }
  }
  return fixed;
}

/// Mean shear τ = T/(2π R² t) of the thin wall at the buckling torque.
double critical_shear(const Tube& tube, const BucklingResult& b) {
  return b.load_factor / (2 * kPi * tube.R * tube.R * tube.t);
}

// The moderate-length closed form for a thin cylinder in torsion (NASA SP-8007, 1968 revision, §4.3 "torsion",
// with its correlation factor γ = 1, i.e. the theory): τ_cr = 0.747·E·(t/R)^(5/4)·(R/L)^(1/2), ν = 0.3 folded in;
// it is Batdorf's simply-supported asymptote k_s = 0.85·Z^(3/4) of τ_cr = k_s·π²·E·t²/(12(1−ν²)L²) (NACA Report
// 874, 1947): 0.85·π²/12/(1 − 0.09)^(5/8) = 0.742. EN 1993-1-6:2007 Annex D.1.4 gives the same with 0.75 (C_τ = 1)
// for ω = L/√(R·t) from 10 to 8.7·R/t. Valid for Z = L²/(R·t)·√(1−ν²) from about 50 to 78·(R/t)²·(1−ν²).
// Tube: R/t = 100 (R = 50 mm, t = 0.5 mm), L = 2R = 100 mm: Z = 382, ω = 20 (mid-range; the short-cylinder term of
// EN's C_τ = √(1 + 42/ω³) adds 0.3 %). Steel E = 210 GPa, ν = 0.3.
//
// 5 %: the closed form is an asymptote of Donnell's shallow-shell theory (errors of order 1/n², 1.5 % at the n = 8
// found here), with n continuous (the integer minimum lies above it) and the chart's rounding (0.747 against
// 0.742); the 3-D wall adds O(t/R) = 1 %. Measured: simply supported τ_cr +1.7 % above the closed form at n = 8
// (2 layers × 80 cells; 40 cells: +0.08 %, 160: −0.06 %, 4 layers: −0.01 %: the mesh is converged to 0.1 %).
// Clamped as asked (the loaded end turning freely) lies +5.2 % above the same form (edge restraint raises it: Batdorf's
// clamped curve lies above the simply supported one, by less as Z grows; measured clamped/simply supported 1.034),
// so it is held within 5 % of the simply supported FE value's band: 1 < clamped/simply supported < 1.10.
constexpr double kClosedFormCoefficient = 0.747;
constexpr double kClosedFormTolerance = 0.05;
constexpr double kMeshConvergence = 2e-3;  // 40 → 80 cells along: measured 8e-4 (simply supported)
constexpr double kClampRaisesAtMost = 1.10;  // Batdorf's clamped/simply supported asymptotes 0.93/0.85 = 1.094

TEST(TorsionBuckling, ThinTubeMatchesTheModerateLengthClosedForm) {
  const double R = 50e-3, t = 0.5e-3, L = 100e-3;
  const Tube tube = solve_tube(R, t, L, 2, 80);
  const Material& m = tube.model.material;
  const double nu = m.poisson_ratio, E = m.youngs_modulus_Pa;
  const double Z = L * L / (R * t) * std::sqrt(1 - nu * nu);
  ASSERT_GT(Z, 50.0);
  ASSERT_LT(Z, 78 * (R / t) * (R / t) * (1 - nu * nu));
  const double closed_form = kClosedFormCoefficient * E * std::pow(t / R, 1.25) * std::sqrt(R / L);

  const BucklingResult ss =
      torsion_buckling_fourier(tube.solution.section, m, tube_supports(tube, Ends::SimplySupported),
                               tube.solution.torque_unit);
  const BucklingResult clamped =
      torsion_buckling_fourier(tube.solution.section, m, tube_supports(tube, Ends::Clamped), tube.solution.torque_unit);
  const double tau_ss = critical_shear(tube, ss), tau_clamped = critical_shear(tube, clamped);
  std::printf("tube R/t %.0f, L/R %.1f, Z %.0f: closed form %.1f MPa; simply supported %.1f MPa (n = %d, %+.2f %%), "
              "clamped %.1f MPa (n = %d, %+.2f %%), T_cr %.0f / %.0f N m\n",
              R / t, L / R, Z, closed_form / 1e6, tau_ss / 1e6, ss.n, 100 * (tau_ss / closed_form - 1),
              tau_clamped / 1e6, clamped.n, 100 * (tau_clamped / closed_form - 1), ss.load_factor,
              clamped.load_factor);
  EXPECT_NEAR(tau_ss / closed_form, 1.0, kClosedFormTolerance);
  EXPECT_GT(tau_clamped / tau_ss, 1.0);
  EXPECT_LT(tau_clamped / tau_ss, kClampRaisesAtMost);
  // The minimum is interior to the scan: the harmonics on both sides of it lie higher.
  ASSERT_GT(ss.n, 0);
  ASSERT_LT(static_cast<std::size_t>(ss.n) + 1, ss.per_harmonic.size());
  EXPECT_GT(ss.per_harmonic[static_cast<std::size_t>(ss.n) - 1].load_factor, ss.load_factor);
  EXPECT_GT(ss.per_harmonic[static_cast<std::size_t>(ss.n) + 1].load_factor, ss.load_factor);
  EXPECT_LT(ss.mode_residual, 1e-6);

  const Tube coarse = solve_tube(R, t, L, 2, 40);
  const BucklingResult ss_coarse =
      torsion_buckling_fourier(coarse.solution.section, m, tube_supports(coarse, Ends::SimplySupported),
                               coarse.solution.torque_unit);
  std::printf("  mesh: 2 x 40 cells %.2f N m, 2 x 80 cells %.2f N m (%.2e)\n", ss_coarse.load_factor, ss.load_factor,
              ss_coarse.load_factor / ss.load_factor - 1);
  EXPECT_EQ(ss_coarse.n, ss.n);
  EXPECT_NEAR(ss_coarse.load_factor / ss.load_factor, 1.0, kMeshConvergence);
}

// Torsion buckling is sign-symmetric (the mirror image of a mode buckles under the reversed torque), and the prestress
// is linear in the torque: λ(−σ⁰) = λ(σ⁰), λ(2σ⁰) = λ(σ⁰)/2, harmonic by harmonic. Tolerance: the Lanczos tolerance
// 1e-10 on ν = 1/λ², with room for the factor's round-off.
constexpr double kSameEigenvalue = 1e-8;

TEST(TorsionBuckling, LoadFactorIsEvenInTheTorqueAndScalesAsItsInverse) {
  const Tube tube = solve_tube(50e-3, 0.5e-3, 50e-3, 2, 24);
  const std::vector<bool> fixed = tube_supports(tube, Ends::Clamped);
  const SectionMesh& s = tube.solution.section;
  const Material& m = tube.model.material;
  BucklingOptions o;
  o.max_harmonic = 14;
  o.rises_to_stop = 0;
  const BucklingResult base = torsion_buckling_fourier(s, m, fixed, tube.solution.torque_unit, o);
  const BucklingResult reversed = torsion_buckling_fourier(s, m, fixed, tube.solution.torque_unit * -1.0, o);
  const BucklingResult doubled = torsion_buckling_fourier(s, m, fixed, tube.solution.torque_unit * 2.0, o);
  ASSERT_EQ(base.per_harmonic.size(), 15u);
  ASSERT_EQ(reversed.per_harmonic.size(), 15u);
  ASSERT_EQ(doubled.per_harmonic.size(), 15u);
  for (std::size_t k = 0; k < base.per_harmonic.size(); ++k) {
    const double l = base.per_harmonic[k].load_factor;
    EXPECT_NEAR(reversed.per_harmonic[k].load_factor / l, 1.0, kSameEigenvalue) << "n = " << k;
    EXPECT_NEAR(doubled.per_harmonic[k].load_factor / l, 0.5, kSameEigenvalue) << "n = " << k;
  }
  EXPECT_EQ(reversed.n, base.n);
  EXPECT_LT(base.mode_residual, 1e-6);
  EXPECT_LT(reversed.mode_residual, 1e-6);
  // The mode is normalised and lives in its harmonic only; under the reversed torque it is its mirror image (the
  // helix of the other hand): the same symmetric family, the antisymmetric one negated (y = −λ·K⁻¹·Cᵀ·x, C → −C).
  const auto n = static_cast<std::size_t>(base.n);
  EXPECT_LT((reversed.mode.sym[n] - base.mode.sym[n]).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((reversed.mode.anti[n] + base.mode.anti[n]).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT(base.mode.anti[n].cwiseAbs().maxCoeff(), 0.1);  // a helix: both families carry the mode
  ASSERT_EQ(base.mode.sym.size(), n + 1);
  EXPECT_NEAR(std::max(base.mode.sym[n].cwiseAbs().maxCoeff(), base.mode.anti[n].cwiseAbs().maxCoeff()), 1.0, 1e-15);
  for (std::size_t k = 0; k < n; ++k) EXPECT_EQ(base.mode.sym[k].size(), 0);
}

// ∫ σ⁰_ij u_k,i u_k,j dV by a route that shares nothing with the element: the displacement written in Cartesian
// components, its Cartesian gradient by 4th-order central differences, σ⁰ rotated to Cartesian, and the volume
// integral by Gauss–Legendre in r and z (5 points: the integrand is a polynomial of degree ≤ 4 in each) times the
// trapezoidal rule in θ (32 points: exact for the trigonometric degree ≤ 2n + 2 here). Prestress: u_θ = α·z·r + β·r²,
// whose shears are by hand γ_θz = ∂u_θ/∂z = α·r, γ_rθ = ∂u_θ/∂r − u_θ/r = β·r (both present, so both terms of K_σ are
// exercised); the field of harmonic n has quadratic amplitudes in (r, z) in both families. Everything is quadratic,
// so the 6-node section reproduces it exactly and the element's degree-5 rule integrates it exactly: the two agree to
// round-off (1e-9: the differences' h⁴ truncation and ε/h rounding are below 1e-11 at h = 1e-4·R).
constexpr double kDirectIntegral = 1e-9;

using Amplitude = std::function<double(double, double)>;  // of (r, z)
struct TestField {
  int n;
  std::array<Amplitude, 3> sym, anti;  // (a, b, c)
};

Eigen::Vector3d cylindrical_displacement(const TestField& f, double r, double theta, double z) {
  const double c = std::cos(f.n * theta), s = std::sin(f.n * theta);
  if (f.n == 0) return {f.sym[0](r, z), -f.anti[1](r, z), f.sym[2](r, z)};
  return {f.sym[0](r, z) * c + f.anti[0](r, z) * s, f.sym[1](r, z) * s - f.anti[1](r, z) * c,
          f.sym[2](r, z) * c + f.anti[2](r, z) * s};
}

Eigen::Vector3d cartesian_displacement(const TestField& f, const Eigen::Vector3d& x) {
  const double r = std::hypot(x[0], x[1]), theta = std::atan2(x[1], x[0]);
  const Eigen::Vector3d u = cylindrical_displacement(f, r, theta, x[2]);
  return {u[0] * std::cos(theta) - u[1] * std::sin(theta), u[0] * std::sin(theta) + u[1] * std::cos(theta), u[2]};
}

double direct_energy(const TestField& f, double ri, double ro, double L, double G, double alpha, double beta) {
  const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                        0.2369268850561891};
  constexpr int kAngles = 32;
  const double h = 1e-4 * ro;
  double W = 0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < kAngles; ++k) {
        const double r = 0.5 * (ri + ro) + 0.5 * (ro - ri) * gx[i], z = 0.5 * L + 0.5 * L * gx[j];
        const double theta = 2 * kPi * k / kAngles;
        const Eigen::Vector3d x(r * std::cos(theta), r * std::sin(theta), z);
        Eigen::Matrix3d grad;  // grad(k, i) = ∂u_k/∂x_i
        for (int d = 0; d < 3; ++d) {
          const Eigen::Vector3d e = Eigen::Vector3d::Unit(d) * h;
          grad.col(d) = (8 * (cartesian_displacement(f, x + e) - cartesian_displacement(f, x - e)) -
                         (cartesian_displacement(f, x + 2 * e) - cartesian_displacement(f, x - 2 * e))) /
                        (12 * h);
        }
        Eigen::Matrix3d S = Eigen::Matrix3d::Zero();  // cylindrical (r, θ, z)
        S(0, 1) = S(1, 0) = G * beta * r;
        S(1, 2) = S(2, 1) = G * alpha * r;
        Eigen::Matrix3d Q;  // columns e_r, e_θ, e_z
        Q << std::cos(theta), -std::sin(theta), 0, std::sin(theta), std::cos(theta), 0, 0, 0, 1;
        const Eigen::Matrix3d sigma = Q * S * Q.transpose();
        const double weight = 0.25 * (ro - ri) * L * gw[i] * gw[j] * (2 * kPi / kAngles) * r;
        W += weight * (grad * sigma * grad.transpose()).trace();
      }
  return W;
}

Eigen::MatrixXd nodal(const SectionMesh& s, const std::array<Amplitude, 3>& f) {
  Eigen::MatrixXd U(static_cast<Eigen::Index>(s.n_nodes()), 3);
  for (Eigen::Index i = 0; i < U.rows(); ++i)
    for (int k = 0; k < 3; ++k) U(i, k) = f[k](s.nodes(i, 0), s.nodes(i, 1));
  return U;
}

TEST(TorsionBuckling, GeometricStiffnessEqualsTheDirectVolumeIntegral) {
  const double ri = 10e-3, ro = 12e-3, L = 8e-3, alpha = 3.0, beta = -2e2;
  const SectionMesh s = mesh_annulus_section(ri, ro, L, 2, 4);
  Material m;
  const double G = m.shear_modulus_Pa();
  HarmonicField prestress;
  prestress.sym.assign(1, Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(s.n_nodes()), 3));
  prestress.anti = prestress.sym;
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(s.n_nodes()); ++i) {
    const double r = s.nodes(i, 0), z = s.nodes(i, 1);
    prestress.anti[0](i, 1) = -(alpha * z * r + beta * r * r);  // b = −u_θ
  }
  const double k = 1e-3;  // m: amplitude scale
  const std::array<Amplitude, 3> sym = {
      [&](double r, double z) { return k * (1 + 30 * z + 2e3 * r * z - 4e3 * z * z); },
      [&](double r, double z) { return k * (0.5 - 40 * r + 3e3 * r * r + 20 * z); },
      [&](double r, double z) { return k * (-0.3 + 10 * r - 25 * z + 1e3 * r * z); }};
  const std::array<Amplitude, 3> anti = {
      [&](double r, double z) { return k * (0.7 - 15 * r + 5e3 * z * z); },
      [&](double r, double z) { return k * (-0.2 + 2e3 * r * z + 60 * z); },
      [&](double r, double z) { return k * (0.4 + 3e3 * r * r - 1e3 * z * z); }};
  for (int n : {0, 1, 3}) {
    const TestField f{n, sym, anti};
    const double direct = direct_energy(f, ri, ro, L, G, alpha, beta);
    const double fe = geometric_stiffness_energy(s, m, prestress, n, nodal(s, sym), nodal(s, anti));
    std::printf("n = %d: u'K_sigma u = %.12e J, direct %.12e J (%.1e)\n", n, fe, direct, fe / direct - 1);
    EXPECT_NEAR(fe / direct, 1.0, kDirectIntegral) << "n = " << n;
  }
  // Rigid motions strain nothing, and a pure shear prestress does no second-order work on a rigid rotation either:
  // Σ_k Ω_ki Ω_kj = ω²(δ_ij − e_i e_j) for a rotation about e, so the work is ω²∫(tr σ⁰ − σ⁰_ee) dV = 0 (tr σ⁰ = 0,
  // σ⁰_xx ∝ sin 2θ for e = x). n = 0: rotation about z (b = −r); n = 1: rotation about y (a = z, b = −z, c = −r).
  const double scale = std::abs(geometric_stiffness_energy(s, m, prestress, 1, nodal(s, sym), nodal(s, anti)));
  const Eigen::MatrixXd none = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(s.n_nodes()), 3);
  Eigen::MatrixXd rz = none, ry = none;
  for (Eigen::Index i = 0; i < rz.rows(); ++i) {
    rz(i, 1) = -k * s.nodes(i, 0) / ri;
    ry.row(i) << k * s.nodes(i, 1) / ri, -k * s.nodes(i, 1) / ri, -k * s.nodes(i, 0) / ri;
  }
  EXPECT_LT(std::abs(geometric_stiffness_energy(s, m, prestress, 0, none, rz)), 1e-12 * scale);
  EXPECT_LT(std::abs(geometric_stiffness_energy(s, m, prestress, 1, ry, none)), 1e-12 * scale);
  EXPECT_LT(std::abs(geometric_stiffness_energy(s, m, prestress, 1, none, ry)), 1e-12 * scale);
}

// The case-level call reads the solution's section, torque case and clamp: the same as the explicit call with the
// clamped nodes' dofs held (a cantilever tube, free end).
TEST(TorsionBuckling, CaseCallUsesTheSolutionsClampAndTorqueCase) {
  const Tube tube = solve_tube(50e-3, 0.5e-3, 50e-3, 2, 16);
  BucklingOptions o;
  o.max_harmonic = 12;
  const BucklingResult viaCase = torsion_buckling_fourier(tube.model, tube.solution, o);
  const SectionMesh& s = tube.solution.section;
  std::vector<bool> fixed(3 * s.n_nodes(), false);
  for (std::size_t i = 0; i < s.n_nodes(); ++i)
    if (s.nodes(static_cast<Eigen::Index>(i), 1) < 1e-12) fixed[3 * i] = fixed[3 * i + 1] = fixed[3 * i + 2] = true;
  const BucklingResult explicit_call =
      torsion_buckling_fourier(s, tube.model.material, fixed, tube.solution.torque_unit, o);
  EXPECT_EQ(viaCase.n, explicit_call.n);
  EXPECT_NEAR(viaCase.load_factor / explicit_call.load_factor, 1.0, kSameEigenvalue);
  // A free end buckles lower than the end held radially and axially.
  const Tube held = tube;
  const BucklingResult clamped = torsion_buckling_fourier(s, tube.model.material, tube_supports(held, Ends::Clamped),
                                                          tube.solution.torque_unit, o);
  EXPECT_LT(viaCase.load_factor, clamped.load_factor);
}

// A cup's boss reaches the axis: the numberings of n = 0, 1 (b = −a tied) and n ≥ 2 (axis held) each give a
// converged eigenpair of the unreduced problem, the minimum lies inside the scan, and the scan stops after the rises.
constexpr double kEigenpairResidual = 1e-6;  // of ‖(K ⊕ K)z + λK_σz‖/‖(K ⊕ K)z‖; measured ~1e-9

TEST(TorsionBuckling, CupWithItsBossOnTheAxisBucklesInAConvergedMode) {
  FlexsplineModel c;
  c.flexspline.shape = FlexsplineShape::Cup;
  c.flexspline.teeth = TeethModel::None;
  c.flexspline.length_m = 14.7e-3;
  c.flexspline.diaphragm_thickness_m = 1.5e-3;
  c.flexspline.boss_radius_m = 10e-3;
  c.mesh.size_m = 1e-3;
  c.mesh.wall_layers = 1;
  c.load.torque_Nm = 1;
  c.load.torque_loading = TorqueLoading::Uniform;
  c.solver.method = SolverMethod::Fourier;
  c.solver.harmonics = 0;
  const FourierSolution s = analyse_flexspline_fourier(c);
  BucklingOptions o;
  o.rises_to_stop = 3;
  const BucklingResult r = torsion_buckling_fourier(c, s, o);
  std::printf("cup: T_cr %.0f N m at n = %d of %zu scanned, residual %.1e\n", r.load_factor, r.n, r.per_harmonic.size(),
              r.mode_residual);
  EXPECT_GE(r.n, 2);
  EXPECT_EQ(r.per_harmonic.size(), static_cast<std::size_t>(r.n) + 1 + 3);
  EXPECT_LT(r.mode_residual, kEigenpairResidual);
  o.max_harmonic = 1;  // harmonics 0, 1: the minimum is n = 1, whose mode has the tied axis dofs
  const BucklingResult low = torsion_buckling_fourier(c, s, o);
  EXPECT_EQ(low.n, 1);
  EXPECT_LT(low.mode_residual, kEigenpairResidual);
  EXPECT_DOUBLE_EQ(low.per_harmonic[1].load_factor, r.per_harmonic[1].load_factor);
}

using sw::testing::message_of;

TEST(TorsionBuckling, RejectsBadInputWithAMessage) {
  const Tube tube = solve_tube(50e-3, 0.5e-3, 20e-3, 2, 8);
  const SectionMesh& s = tube.solution.section;
  const Material& m = tube.model.material;
  const std::vector<bool> fixed = tube_supports(tube, Ends::Clamped);
  EXPECT_NE(message_of([&] { torsion_buckling_fourier(s, m, std::vector<bool>(5), tube.solution.torque_unit); })
                .find("fixed has 5 entries"),
            std::string::npos);
  EXPECT_NE(message_of([&] { torsion_buckling_fourier(s, m, fixed, tube.solution.torque_unit * 0.0); })
                .find("no torsion"),
            std::string::npos);
  EXPECT_NE(message_of([&] { torsion_buckling_fourier(s, m, fixed, HarmonicField{}); }).find("harmonic-0"),
            std::string::npos);
  BucklingOptions o;
  o.max_harmonic = -1;
  EXPECT_NE(message_of([&] { torsion_buckling_fourier(s, m, fixed, tube.solution.torque_unit, o); })
                .find("buckling.max_harmonic = -1"),
            std::string::npos);
  o = {};
  o.tolerance = 0.0;
  EXPECT_NE(message_of([&] { torsion_buckling_fourier(s, m, fixed, tube.solution.torque_unit, o); })
                .find("buckling.tolerance"),
            std::string::npos);
  // No supports: the rigid modes make K singular, which the factor reports.
  EXPECT_THROW(torsion_buckling_fourier(s, m, std::vector<bool>(3 * s.n_nodes(), false), tube.solution.torque_unit),
               InputError);
}

}  // namespace
}  // namespace sw
