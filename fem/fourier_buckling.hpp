#pragma once
// Linear (bifurcation) buckling of a body of revolution under the prestress of a torque, on the harmonic solver's
// section (fem/fourier_solver.hpp, fem/fourier_element.hpp: 6-node triangles, families, axis conditions).
//
// Physics. With σ⁰ the stress of the unit torque (T = 1 N·m) the critical load factor λ solves
//   (K + λ·K_σ)·u = 0,   uᵀ·K_σ·u = ∫ σ⁰_ij (∂u_k/∂x_i)(∂u_k/∂x_j) dV
// (the second-order work of the prestress on the displacement gradient: the initial-stress stiffness of the
// Green–Lagrange strain's quadratic part; Bathe, Finite Element Procedures, 2nd ed., 2014, §6.8.2, linearised
// buckling; Cook, Malkus, Plesha & Witt, Concepts and Applications of FEA, 4th ed., 2002, ch. 18). ∇u is taken in the
// local cylindrical orthonormal frame, rows k = (u_r, u_θ, u_z), columns i = (r, θ, z):
//   u_r,r  (u_r,θ − u_θ)/r  u_r,z;   u_θ,r  (u_θ,θ + u_r)/r  u_θ,z;   u_z,r  u_z,θ/r  u_z,z.
// The torsion prestress is harmonic 0, antisymmetric family (b alone: u_θ = −b); its stresses are exactly the two
// shears τ_rθ, τ_θz (b strains nothing else). Since σ⁰ does not depend on θ, harmonics stay uncoupled; within one
// harmonic each ∇u entry goes as cos nθ or sin nθ, and the shears multiply an r- or z-column entry with a θ-column
// entry of the same row, which is always a cos·sin product inside one family. So K_σ has no block inside a family:
// it couples the symmetric family x with the antisymmetric family y of the same n through one matrix C_n,
//   K_σ = [0 C; Cᵀ 0],   C = −Cᵀ for n ≥ 1 (skew),   C + Cᵀ = K_σ,0 at n = 0 (one field: (a, c) and b).
// The eigenproblem per harmonic is (K_n ⊕ K_n)·z = −λ·K_σ·z; eliminating y = −λ·K_n⁻¹·Cᵀ·x leaves
//   C·K_n⁻¹·Cᵀ·x = ν·K_n·x,   ν = 1/λ² ≥ 0
// (the same size as one family, positive semidefinite, ±λ as one ν: torsion buckling is sign-symmetric). The largest
// ν, found by Lanczos in the K-inner product (Spectra's SymGEigsSolver, regular-inverse mode) on the CHOLMOD factor of
// K_n, gives the smallest |λ| of the harmonic; the buckling torque is min over n of |λ|·1 N·m.
//
// Idealisations: linear prebuckling (σ⁰ proportional to the torque, no change of geometry before bifurcation); only
// the torque case's harmonic 0 is used as prestress (a torque spread over the engagement zones has higher harmonics,
// local to the rim; they would couple harmonics n and n ± 2k and are left out); supports are the caller's, the same
// for every harmonic, with the axis conditions of fem/fourier_solver.hpp. Each load factor is doubly degenerate
// (the mode turned by a quarter wave, (x, y) → (−y, x)); one mode per harmonic is returned.
#include <vector>

#include <Eigen/Core>

#include "common/material.hpp"
#include "fem/flexspline_model.hpp"
#include "fem/fourier_analysis.hpp"
#include "fem/fourier_element.hpp"
#include "fem/fourier_section.hpp"
#include "fem/fourier_solver.hpp"

namespace sw {

/// What the harmonic scan does: harmonics 0..max_harmonic (0: kDefaultBucklingHarmonics), stopping early once the
/// load factor has risen `rises_to_stop` harmonics in a row past the lowest so far (0: scan them all); the Lanczos
/// iteration's relative tolerance on each load factor.
struct BucklingOptions {
  int max_harmonic = 0;
  int rises_to_stop = 6;
  double tolerance = 1e-10;
};

/// The highest harmonic scanned by default: in Donnell's theory a tube in torsion buckles in n ∝ (R/t)^(1/4)·(R/L)^(1/2)
/// waves (Batdorf, NACA Report 874, 1947: k_s ∝ Z^(3/4) at n·L/(πR) ∝ Z^(1/4)), about 10 for R/t = 100, L = R;
/// 60 leaves room for thinner and shorter walls.
inline constexpr int kDefaultBucklingHarmonics = 60;

/// The lowest load factor of one harmonic (|λ|; infinity when the prestress does not couple the harmonic).
struct HarmonicBuckling {
  int n = 0;
  double load_factor = 0;
};

struct BucklingResult {
  std::vector<HarmonicBuckling> per_harmonic;  ///< the harmonics scanned, in order
  double load_factor = 0;  ///< min over n of |λ|: the buckling torque is load_factor × the prestress's torque
  int n = 0;               ///< its harmonic
  /// The critical mode for +load_factor: amplitudes of harmonic n only (sym[n], anti[n], n_nodes × 3; the other
  /// harmonics empty), scaled so the largest |amplitude| is 1 (a shape). At n = 0: sym[0] holds (a, 0, c), anti[0]
  /// holds (0, b, 0), as the solver's fields.
  HarmonicField mode;
  /// ‖(K ⊕ K)·z + λ·K_σ·z‖ / ‖(K ⊕ K)·z‖ of that mode on the equations (a check of the eigenpair).
  double mode_residual = 0;
};

/// Buckling of the section `s` (metres) of material `m` under the prestress of `prestress_unit_torque` (a field of
/// fem/fourier_solver.hpp whose anti[0] is the torsion, n_nodes × 3; the other parts are not read), with the dofs
/// where `fixed` (size 3·n_nodes, node-major a, b, c) is true held at 0 in every harmonic, and the axis conditions.
/// The supports must hold every rigid-body mode of every harmonic scanned (CholmodFactor's InputError otherwise).
/// Throws InputError for sizes that do not match the section, options out of range, or a prestress without torsion.
BucklingResult torsion_buckling_fourier(const SectionMesh& s, const Material& m, const std::vector<bool>& fixed,
                                        const HarmonicField& prestress_unit_torque, const BucklingOptions& o = {});

/// The same for a case solved by analyse_flexspline_fourier: its section, its torque case (T = 1 N·m) and its clamp
/// (every dof of the clamped nodes held; the rest of the flexspline free, as the torque case).
BucklingResult torsion_buckling_fourier(const FlexsplineModel& c, const FourierSolution& solution,
                                        const BucklingOptions& o = {});

/// zᵀ·K_σ·z = ∫ σ⁰_ij (∂u_k/∂x_i)(∂u_k/∂x_j) dV (J) of the displacement of harmonic n with amplitudes `sym`, `anti`
/// (n_nodes × 3 each; at n = 0 the one field (sym a, anti b, sym c)) under the torsion prestress of `prestress`, from
/// the same assembled matrices as the eigenproblem (no supports; the field should meet the axis conditions).
double geometric_stiffness_energy(const SectionMesh& s, const Material& m, const HarmonicField& prestress, int n,
                                  const Eigen::MatrixXd& sym, const Eigen::MatrixXd& anti);

}  // namespace sw
