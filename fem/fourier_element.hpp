#pragma once
// The harmonic solver's element level, shared by its analyses (fem/fourier_solver.hpp: the flexspline's load cases;
// fem/fourier_buckling.hpp: the buckling of its torsion prestress): the 6-node triangle of the meridian section with
// its quadrature, the strain amplitudes of harmonic n, the element stiffness as a polynomial in n, the equations of
// one harmonic (supports and the axis conditions), the assembly, probes that read a field at a point of the section,
// and the nodal stresses of a field. Conventions: fem/fourier_solver.hpp's header (the two families, node-major
// dofs (a, b, c)).
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "common/material.hpp"
#include "fem/assembly.hpp"
#include "fem/fourier_section.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Amplitudes of one load case over the section: per harmonic 0..N, n_nodes × 3 (a, b, c) of each family.
struct HarmonicField {
  std::vector<Eigen::MatrixXd> sym, anti;
  int harmonics() const { return static_cast<int>(sym.size()) - 1; }
  /// Cylindrical displacement (u_r, u_θ, u_z) at the point of element e with natural coordinates q, angle θ.
  Eigen::Vector3d displacement(const SectionMesh& s, long e, const Eigen::Vector2d& q, double theta) const;
  HarmonicField& operator+=(const HarmonicField& o);
  HarmonicField operator*(double k) const;
};

namespace fourier {

using Mat6x2 = Eigen::Matrix<double, 6, 2>;
using Mat6x18 = Eigen::Matrix<double, 6, 18>;
using Mat18 = Eigen::Matrix<double, 18, 18>;

// 7-point rule on the reference triangle, exact to degree 5 (Strang & Fix); weights sum to 1/2.
struct TriangleRule {
  double xi[7], eta[7], w[7];
  TriangleRule() {
    const double s = std::sqrt(15.0);
    const double a1 = (6 - s) / 21, b1 = (9 + 2 * s) / 21, a2 = (6 + s) / 21, b2 = (9 - 2 * s) / 21;
    const double w1 = (155 - s) / 2400, w2 = (155 + s) / 2400;
    const double x[7] = {1.0 / 3, a1, b1, a1, a2, b2, a2}, y[7] = {1.0 / 3, a1, a1, b1, a2, a2, b2};
    const double ww[7] = {9.0 / 80, w1, w1, w1, w2, w2, w2};
    for (int k = 0; k < 7; ++k) xi[k] = x[k], eta[k] = y[k], w[k] = ww[k];
  }
};

inline const TriangleRule kRule;

// Natural coordinates of the six nodes.
constexpr double kNodeXi[6] = {0, 1, 0, 0.5, 0.5, 0}, kNodeEta[6] = {0, 0, 1, 0, 0.5, 0.5};

Mat6x2 coords(const SectionMesh& s, std::size_t e);

using Mat6 = Eigen::Matrix<double, 6, 6>;

/// Elasticity in the order (ε_r, ε_z, ε_θ, γ_rz, γ_rθ, γ_θz).
Mat6 elasticity(const Material& m);

/// The tooth layer's elasticity at solidity φ (teeth = "layer"), the teeth homogenised as ribs along the face, one per
/// pitch, whose flanks are free: no stress crosses the spaces, so σ_θ = 0 and each tooth is in plane stress in its
/// (r, z) plane. The layer carries φ times plane stress in (ε_r, ε_z, γ_rz) (the rule of mixtures of parallel ribs:
/// exact for stress along the ribs) and nothing in hoop. The two shears across a rib's flanks:
/// - γ_rθ at φ G: a tooth's section carries the shear of a cantilever on the rim (Timoshenko's, over the tooth's
///   width), which keeps the ribs standing on the rim as it bends and turns; the rim's shear-free bending strains the
///   layer not at all. The flanks' load and the tooth's bending under it stay in series (contact/tooth_fem.hpp).
/// - γ_θz at κ φ G, `shear_factor` κ from the periodic cell of one pitch (fem/rib_cell.hpp): a rib tilting along the
///   face relaxes away from its root, and is held to the rim at it.
/// Left out: the ribs' plate bending between sections (∝ the tooth's thickness cubed) and the cell's curvature.
/// The hoop term keeps kToothLayerResidual of the material's modulus so the layer's displacement around the rim is
/// determined (the ribs carry no hoop load). Its value is numerical, not physical: on the designed drives 1e-4 and
/// 1e-6 gave the same twist to 5e-4 (size 14 ratio 30, size 17 ratio 100, with every θ term residual), but from 1e-5
/// down the loaded contact of the designed size 17 was no longer its own mirror image about the major axis (the
/// generator locked at ±0.3 of a pitch: 1.1e-3 of the twist at rated against 3e-7 at 1e-4 and 1e-3,
/// test_generator_angle), so 1e-4 is kept.
Mat6 tooth_layer_elasticity(const Material& m, double solidity, double shear_factor);
inline constexpr double kToothLayerResidual = 1e-4;

/// The elasticity of triangle e at radius r: the material's, or in the tooth layer tooth_layer_elasticity at its
/// solidity there.
Mat6 elasticity_at(const SectionMesh& s, std::size_t e, const Material& m, double r_m);

/// Strain amplitudes of harmonic n at a point: rows (ε_r, ε_z, ε_θ, γ_rz | γ_rθ, γ_θz), the first four multiplying
/// cos nθ (sin nθ in the antisymmetric family), the last two sin nθ (−cos nθ); columns node-major (a, b, c).
/// Also the point's radius and the Jacobian determinant.
/// The 6-node triangle at a point: shape functions, their derivatives along r and z, the radius and the Jacobian's
/// determinant (of the map from natural coordinates).
struct ShapePoint {
  Eigen::Matrix<double, 6, 1> N;
  Eigen::Matrix<double, 2, 6> dN;  ///< rows d/dr, d/dz
  double r = 0, det = 0;
};
ShapePoint shape_point(const Mat6x2& X, double xi, double eta);

struct StrainPoint {
  Mat6x18 B;
  double r = 0, det = 0;
};

StrainPoint strain_matrix(const Mat6x2& X, double xi, double eta, int n);

double theta_weight(int n);

/// Equation numbers of one harmonic: −1 fixed; a dof tied to another shares its equation with sign −1.
struct HarmonicDofs {
  std::vector<std::int64_t> eq;
  std::vector<double> sign;
  std::vector<std::int64_t> node_of_eq;
  std::int64_t n_eq = 0;
};

HarmonicDofs number_dofs(std::size_t n_nodes, int n, const std::vector<bool>& fixed, const std::vector<bool>& axis);

std::vector<bool> axis_nodes(const SectionMesh& s);

/// Loads (n_nodes × 3) onto the equations, and a solution back onto every node (fixed dofs from `fixed_values`).
Eigen::VectorXd to_equations(const HarmonicDofs& d, const Eigen::MatrixXd& F);

Eigen::MatrixXd to_nodes(const HarmonicDofs& d, const Eigen::VectorXd& x, Eigen::MatrixXd fixed_values);

/// The element stiffness as a polynomial in the harmonic: B = B₀ + n·B₁, so ∫BᵀDB r dA = K₀ + n·K₁ + n²·K₂; integrated
/// once per element, each harmonic's matrix is a sum (the integration was most of a harmonic's cost).
struct ElementPolynomial {
  Mat18 k0, k1, k2;
  Mat18 at(int n) const { return theta_weight(n) * (k0 + n * k1 + (static_cast<double>(n) * n) * k2); }
};

/// D_at(r): the elasticity at a quadrature point's radius.
ElementPolynomial element_polynomial(const Mat6x2& X, const std::function<Mat6(double r_m)>& D_at);

std::vector<ElementPolynomial> element_polynomials(const SectionMesh& s, const Material& m);

/// Σ_e of an element quantity (18 × 18 per element) on the equations of a numbering, upper triangle.
template <class ElementMatrix>
SymmetricCsc assemble(const SectionMesh& s, const HarmonicDofs& d, ElementMatrix element) {
  std::vector<Eigen::Triplet<double, std::int64_t>> trip;
  trip.reserve(s.triangles.size() * 18 * 19 / 2);
  for (std::size_t e = 0; e < s.triangles.size(); ++e) {
    const Mat18& Ke = element(e);
    const auto& t = s.triangles[e];
    for (int p = 0; p < 18; ++p) {
      const std::int64_t ip = d.eq[3 * t[p / 3] + p % 3];
      if (ip < 0) continue;
      const double sp = d.sign[3 * t[p / 3] + p % 3];
      for (int q = 0; q < 18; ++q) {
        const std::int64_t iq = d.eq[3 * t[q / 3] + q % 3];
        if (iq < 0 || ip > iq) continue;
        trip.emplace_back(ip, iq, sp * d.sign[3 * t[q / 3] + q % 3] * Ke(p, q));
      }
    }
  }
  Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t> K(d.n_eq, d.n_eq);
  K.setFromTriplets(trip.begin(), trip.end());
  K.makeCompressed();
  SymmetricCsc out;
  out.n = d.n_eq;
  out.column_start.assign(K.outerIndexPtr(), K.outerIndexPtr() + d.n_eq + 1);
  out.row.assign(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros());
  out.value.assign(K.valuePtr(), K.valuePtr() + K.nonZeros());
  return out;
}

/// The global K₀, K₁, K₂ of one numbering (the harmonics with the same axis conditions, n ≥ 2, share one): each
/// harmonic's matrix is w_n·(K₀ + n·K₁ + n²·K₂) on one pattern, O(nnz) per harmonic.
struct GlobalPolynomial {
  HarmonicDofs dofs;
  SymmetricCsc k0;
  std::vector<double> v1, v2;
  SymmetricCsc at(int n) const {
    SymmetricCsc K = k0;
    const double w = theta_weight(n), nn = static_cast<double>(n) * n;
    for (std::size_t i = 0; i < K.value.size(); ++i) K.value[i] = w * (k0.value[i] + n * v1[i] + nn * v2[i]);
    return K;
  }
};

GlobalPolynomial assemble_polynomial(const SectionMesh& s, const std::vector<ElementPolynomial>& poly, HarmonicDofs d);



/// Where a quantity is read: section nodes with weights (a node, or the six of a located point).
struct Probe {
  std::array<int, 6> node{};
  Eigen::Matrix<double, 6, 1> weight = Eigen::Matrix<double, 6, 1>::Zero();
};

Probe probe_at(const SectionMesh& s, const Eigen::Vector2d& rz);

Probe probe_node(int i);

/// cos nθ and sin nθ for n = 0..N at one angle (the series are summed at many points of few angles).
struct Trig {
  std::vector<double> c, s;
  Trig(double theta, std::size_t harmonics) : c(harmonics), s(harmonics) {
    for (std::size_t n = 0; n < harmonics; ++n) {
      c[n] = std::cos(static_cast<double>(n) * theta);
      s[n] = std::sin(static_cast<double>(n) * theta);
    }
  }
};

/// (u_r, u_θ, u_z) of a field at a probe: a, c go with cos (sym), b with sin.
Eigen::Vector3d displacement_at(const HarmonicField& f, const Probe& p, const Trig& trig);

Eigen::Vector3d displacement_at(const HarmonicField& f, const Probe& p, double theta);

Eigen::Vector3d to_cartesian(const Eigen::Vector3d& cyl, double theta);

/// Nodal stress amplitudes (σ_r, σ_z, σ_θ, τ_rz | τ_rθ, τ_θz) per harmonic and family: each element's stress at its
/// own nodes, averaged over the elements at a node weighted by their area (as the tet10 path's nodal_stress).
/// Nodes on the axis are evaluated a hair inside their elements (the amplitudes' 1/r terms are 0/0 there).
void nodal_stress(const SectionMesh& s, const Material& m, const HarmonicField& f, std::vector<Eigen::MatrixXd>& sym,
                  std::vector<Eigen::MatrixXd>& anti);

/// Hoop stress σ_θθ at a probe and angle from the nodal amplitudes (column 2 is σ_θ, a cos-type column).
double hoop_at(const std::vector<Eigen::MatrixXd>& sym, const std::vector<Eigen::MatrixXd>& anti, const Probe& p,
               const Trig& trig);

/// Cartesian Voigt stress (xx yy zz yz xz xy) from cylindrical (σ_r, σ_z, σ_θ, τ_rz, τ_rθ, τ_θz) at angle θ.
Eigen::Matrix<double, 1, 6> cartesian_stress(const Eigen::Matrix<double, 6, 1>& c, double theta);

/// The section revolved into TET10: nodes = every section node at 2·sectors angular stations (corners at even
/// stations are the prisms' corners; odd stations and midside nodes give every TET10 midside node exactly), each prism
/// (triangle × sector) split into three tets by Dompierre's rule on global corner numbers (conforming). Tets that
/// degenerate on the axis are dropped. Grid node k·n_section_nodes + i is section node i at station k (θ = kπ/sectors).
TetMesh revolve_section(const SectionMesh& s, int sectors);

/// The Cartesian displacement (3·n_grid) of a field at every node of revolve_section(s, sectors)'s grid.
Eigen::VectorXd revolved_displacement(const SectionMesh& s, const HarmonicField& f, int sectors);

}  // namespace fourier
}  // namespace sw
