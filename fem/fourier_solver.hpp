#pragma once
// Semi-analytical solver for flexsplines that are bodies of revolution (teeth "ring" or "none"): the displacement is
// expanded in circumferential harmonics n = 0..N,
//   symmetric family:      u_r = a(r,z)·cos nθ,  u_θ =  b(r,z)·sin nθ,  u_z = c(r,z)·cos nθ
//   antisymmetric family:  u_r = a(r,z)·sin nθ,  u_θ = −b(r,z)·cos nθ,  u_z = c(r,z)·sin nθ
// (Wilson 1965; Abaqus's CAXA). For linear elasticity of a body of revolution the harmonics and the families
// decouple exactly, and both families of one harmonic have the same stiffness K_n = w_n ∫∫ Bₙᵀ D Bₙ r dr dz
// (w_0 = 2π, w_n = π: the θ integrals of cos², sin², done exactly). So each harmonic is a 2-D problem on the meridian
// section (fem/fourier_section.hpp), factorised once by CHOLMOD and solved for both families and every load case.
// At n = 0 the symmetric family is (a, c) and the antisymmetric one is b alone (torsion); one matrix holds both.
//
// Loads are expanded exactly in θ (patches and zones are piecewise constant in θ, integrated in closed form) and
// integrated over the section's boundary edges with 3 Gauss points; what is truncated is the series at N, nothing
// else. The generator models (the cam and rollers in unilateral contact on the band's stations, with the bearing in
// series and the gaps blind to the band's turn as fem/generator_contact.hpp's model; the force models with the torque
// case held radially at them), torque loadings, supports and the figures read from the solution are
// those of fem/flexspline_analysis.hpp (same conventions; see there), with these differences: the four-force patches
// are exactly ±3° × the band on the inner wall (the section has node lines at the band's edges); the stations are
// the tet10 path's but at most N/2 pairs (a hat of half-width Δ needs harmonics up to 2π/Δ), and their influence
// matrix is exact up to the truncation (two solves per harmonic; see HarmonicStations in the source).
// Nodes on the axis (the cup's boss) carry the regularity conditions: n = 0: a = b = 0; n = 1: c = 0, b = −a;
// n ≥ 2: a = b = c = 0.
#include <vector>

#include <Eigen/Core>

#include "fem/flexspline_model.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/fourier_section.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Stiffness of a 6-node triangle of the section for harmonic n (18 × 18, dofs node-major (a, b, c)), N/m.
Eigen::Matrix<double, 18, 18> harmonic_element_stiffness(const Eigen::Matrix<double, 6, 2>& X, const Material& m,
                                                         int n);

/// One harmonic on the section with supports of the caller's: solves K_n·U = F (U, F: n_nodes × 3 amplitudes
/// (a, b, c) of one family) with the dofs where `fixed` (size 3·n_nodes) is true held at 0, and the axis conditions.
Eigen::MatrixXd solve_harmonic(const SectionMesh& s, const Material& m, int n, const std::vector<bool>& fixed,
                               const Eigen::MatrixXd& F);

/// ∫ t N_i r ds over the boundary edges with `marker` (n_nodes × 3) for a traction t = (t_r, t_θ, t_z) uniform on
/// them: times the θ integral of the load's angular shape it is the generalised load of a harmonic.
Eigen::MatrixXd section_traction_load(const SectionMesh& s, int marker, const Eigen::Vector3d& traction);

/// Amplitudes of one load case over the section: per harmonic 0..N, n_nodes × 3 (a, b, c) of each family.
struct HarmonicField {
  std::vector<Eigen::MatrixXd> sym, anti;
  int harmonics() const { return static_cast<int>(sym.size()) - 1; }
  /// Cylindrical displacement (u_r, u_θ, u_z) at the point of element e with natural coordinates q, angle θ.
  Eigen::Vector3d displacement(const SectionMesh& s, long e, const Eigen::Vector2d& q, double theta) const;
  HarmonicField& operator+=(const HarmonicField& o);
  HarmonicField operator*(double k) const;
};

/// Per-harmonic statistics of the solve.
struct HarmonicStats {
  int n = 0;
  std::int64_t equations = 0;
  double factor_nnz = 0, factor_gflop = 0, factor_s = 0;
  double load_norm = 0;   ///< largest |load| of the harmonic over the load cases (0: not solved)
};

struct FourierSolution {
  SectionMesh section;
  FlexsplineSolution figures;  ///< φ₀, C_τ, neutral curve, hoop stress, reactions (cases[].u empty unless a grid)
  HarmonicField torque_unit;   ///< T = 1 N·m, without the generator's support
  HarmonicField generator;     ///< scaled to the case (w0 or force)
  std::vector<HarmonicStats> harmonics;  ///< the harmonics solved (those with a load)
  int harmonics_kept = 0;      ///< N
  double section_s = 0;        ///< meshing the section
  TetMesh grid;                ///< the section revolved into TET10 (for VTU), when asked for
};

/// Solves the case (teeth "ring" or "none") by harmonics 0..c.solver.harmonics on its meridian section. With
/// `grid_sectors` > 0 also revolves the section into a TET10 grid of that many sectors (midside nodes included,
/// every node evaluated from the series) and fills figures.cases[].u / .stress on it for VTU output.
FourierSolution analyse_flexspline_fourier(const FlexsplineModel& c, int grid_sectors = 0);

/// Same on a given section (tests: the annulus of fem/fourier_section.hpp).
FourierSolution analyse_section_fourier(const FlexsplineModel& c, SectionMesh section, int grid_sectors = 0);

}  // namespace sw
