#pragma once
// Semi-analytical solver for flexsplines that are bodies of revolution (teeth "ring", "layer" or "none"): the displacement is
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
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "fem/flexspline_model.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/fourier_element.hpp"
#include "fem/fourier_loads.hpp"
#include "fem/fourier_section.hpp"
#include "mesh/estimate.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Stiffness of a 6-node triangle of the isotropic material for harmonic n (18 × 18, dofs node-major (a, b, c)), N/m:
/// integrated directly, the independent statement of element_polynomials' (which also hold the tooth layer's).
Eigen::Matrix<double, 18, 18> harmonic_element_stiffness(const Eigen::Matrix<double, 6, 2>& X, const Material& m,
                                                         int n);

/// One harmonic on the section with supports of the caller's: solves K_n·U = F (U, F: n_nodes × 3 amplitudes
/// (a, b, c) of one family) with the dofs where `fixed` (size 3·n_nodes) is true held at 0, and the axis conditions.
Eigen::MatrixXd solve_harmonic(const SectionMesh& s, const Material& m, int n, const std::vector<bool>& fixed,
                               const Eigen::MatrixXd& F);

/// ∫ t N_i r ds over the boundary edges with `marker` (n_nodes × 3) for a traction t = (t_r, t_θ, t_z) uniform on
/// them: times the θ integral of the load's angular shape it is the generalised load of a harmonic.
Eigen::MatrixXd section_traction_load(const SectionMesh& s, int marker, const Eigen::Vector3d& traction);



/// The responses of `bands` on a section with supports of the caller's (a body other than the case's flexspline: the
/// circular spline, contact/circular_spline.hpp): per band its S and, for harmonics 0..N (the even ones only unless
/// `odd_harmonics`; the others left empty), K_n⁻¹E_r and K_n⁻¹E_θ with the dofs where `fixed` (size 3·n_nodes) is
/// true held at 0, and the axis conditions. One analysis per numbering (n = 0, 1, ≥ 2), refactorised per harmonic.
/// Throws InputError for a band no boundary edge lies in, and CholmodFactor's error when the supports leave a
/// rigid-body mode free.
std::vector<BandResponse> band_responses(const SectionMesh& s, const Material& m, const std::vector<bool>& fixed,
                                         const std::vector<SurfaceBand>& bands, int N, bool odd_harmonics);

/// What a later stage asks of the harmonic pass besides the FEM's figures: the responses of its bands, and every
/// harmonic (the odd ones too) when its loads are not symmetric under a half turn.
struct BandRequest {
  std::vector<SurfaceBand> bands;
  bool odd_harmonics = false;
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
  /// What 1 N·m adds with the generator in place (its stations' forces solved again under the torque: linear about
  /// the case's torque for a cam or rollers); the torque alone when there is no generator.
  HarmonicField torque_with_generator;
  HarmonicField generator;     ///< scaled to the case (w0 or force)
  std::vector<HarmonicStats> harmonics;  ///< the harmonics solved (those with a load)
  int harmonics_kept = 0;      ///< N
  double section_s = 0;        ///< meshing the section
  TetMesh grid;                ///< the section revolved into TET10 (for VTU), when asked for
  /// For the loaded contact: the generator's stations and their band's responses (a generator only), the requested
  /// bands' responses, and the nodes held by the clamp.
  std::optional<HarmonicStations> stations;
  BandResponse station_band;
  std::vector<BandResponse> bands;
  std::vector<bool> clamped;
};

/// The case's meridian section (the generator's band, when it has one, marked on the bore).
SectionMesh case_section(const FlexsplineModel& c);

/// The harmonic model's size on its section before anything is assembled, for refuse_if_too_large: 3 equations per
/// node and harmonic 0..c.solver.harmonics, peak memory 150 MB + 150 bytes per such equation (measured peak: size 17
/// at its case mesh 251 MB against 336 estimated; at a 0.1 mm section, 62k nodes, 4.8 GB against 5.2).
ModelSizeEstimate fourier_model_size(const FlexsplineModel& c, const SectionMesh& section);

/// The rim's neutral curves (w, v, μ at 1° steps in the *_wg fields) of a harmonic field (the generator case) at
/// sections z_m of the neutral radius: the harmonic counterpart of fem/flexspline_analysis.hpp's neutral_curves_at.
std::vector<NeutralCurveSamples> neutral_curves_at(const SectionMesh& s, const HarmonicField& u, double radius_m,
                                                   const std::vector<double>& z_m);

/// Strain energy of each harmonic 0..N of a field over the whole body (J): ½ uᵀK_n u of its two families (at n = 0
/// the one field (sym a, anti b, sym c)). The harmonics are orthogonal in energy, so they add to the field's; a
/// travelling wave of harmonic n (the generator's deformation as the body turns under it) keeps U_n at every instant.
std::vector<double> harmonic_strain_energy_J(const SectionMesh& s, const Material& m, const HarmonicField& u);

/// Strain energy of a field per region of the section (J, indexed by SectionMesh::region: 0 body wall, 1 rim,
/// 2 diaphragm, 3 boss), all harmonics together; the regions add to harmonic_strain_energy_J's sum.
std::vector<double> strain_energy_by_region_J(const SectionMesh& s, const Material& m, const HarmonicField& u);

/// Moment about z (N·m) of the clamp's reaction to a harmonic field under loads whose harmonic-0 antisymmetric
/// generalised forces are `anti0` (n_nodes × 3): K₀·u − F on the clamped nodes.
double clamp_reaction_moment(const SectionMesh& s, const Material& m, const std::vector<bool>& clamped,
                             const HarmonicField& u, const Eigen::MatrixXd& anti0);

}  // namespace sw
