#pragma once
// The harmonic model's loads on the meridian section, expanded exactly in θ (as fem/loads.hpp for the TET10 model):
// tractions piecewise constant in θ on boundary edges, the generator's stations (HarmonicStations), the bands'
// responses; and the readings of a harmonic field there (as fem/post.hpp): moments, the series at given angles, a
// ring's w, v and normal rotation. Internal to the harmonic solver (fem/fourier_solver.cpp, fem/fourier_analysis.cpp).
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "fem/fourier_solver.hpp"

namespace sw::fourier {

struct Window {
  double from = 0, to = 0, weight = 1;
};

/// ∫ g(θ) cos nθ dθ
double cos_moment(const std::vector<Window>& ws, int n);

/// ∫ g(θ) sin nθ dθ
double sin_moment(const std::vector<Window>& ws, int n);

/// Traction t(θ, s) = g(θ)·h(s) on boundary edges: `spatial` holds ∫ h_k N_i r ds (n_nodes × 3, k = r, θ, z).
struct LoadTerm {
  std::vector<Window> windows;
  Eigen::MatrixXd spatial;
};

/// ∫ h(r, z) N_i r ds over the given edges (3-point Gauss), n_nodes × 3 (cylindrical components of h).
template <class H>
Eigen::MatrixXd edge_integral(const SectionMesh& s, const std::vector<const SectionEdge*>& edges, H h) {
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(s.n_nodes()), 3);
  const double g = std::sqrt(0.6), gp[3] = {-g, 0, g}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  for (const auto* e : edges) {
    const Eigen::Vector2d x0 = s.nodes.row(e->nodes[0]), x1 = s.nodes.row(e->nodes[1]), xm = s.nodes.row(e->nodes[2]);
    for (int k = 0; k < 3; ++k) {
      const double t = gp[k];
      const double N[3] = {0.5 * t * (t - 1), 0.5 * t * (t + 1), 1 - t * t};
      const double dN[3] = {t - 0.5, t + 0.5, -2 * t};
      const Eigen::Vector2d x = N[0] * x0 + N[1] * x1 + N[2] * xm;
      const double ds = (dN[0] * x0 + dN[1] * x1 + dN[2] * xm).norm();
      const Eigen::Vector3d hv = h(x);
      for (int a = 0; a < 3; ++a) out.row(e->nodes[a]) += (gw[k] * ds * x[0] * N[a]) * hv.transpose();
    }
  }
  return out;
}

std::vector<const SectionEdge*> select_edges(const SectionMesh& s, int marker,
                                             const std::function<bool(const Eigen::Vector2d&)>& keep = {});

/// The edges of a band: its marker's, with the midside node in z_lo_m..z_hi_m.
std::vector<const SectionEdge*> band_edges(const SectionMesh& s, const SurfaceBand& b);

/// A band's spatial vector S_i = ∫ N_i r ds over its edges.
Eigen::VectorXd band_vector(const SectionMesh& s, const std::vector<const SectionEdge*>& edges);

/// Generalised nodal loads of harmonic n (n_nodes × 3 per family) of a sum of terms.
void harmonic_loads(const std::vector<LoadTerm>& terms, int n, Eigen::MatrixXd& sym, Eigen::MatrixXd& anti);

/// The stations of the case's generator (angles, hats, normals and standoffs as fem/flexspline_system.cpp's
/// generator_stations), but no finer than the series resolves: a hat of half-width Δ has its spectrum's main lobe up
/// to n = 2π/Δ, so Δ ≥ 2π/N (pairs ≤ N/2). `S`: ∫ N_i r ds over the band's inner-wall edges.
HarmonicStations harmonic_stations(const FlexsplineModel& c, const Eigen::VectorXd& S, int N);

/// Moment about z (N·m) of the physical loads whose harmonic-0 antisymmetric generalised forces are F (n_nodes × 3).
double moment_z(const SectionMesh& s, const Eigen::MatrixXd& anti0);

/// The bands' unit loads E_r = (S, 0, 0) and E_θ = (0, S, 0) on the equations of a numbering: columns 2b, 2b + 1.
Eigen::MatrixXd band_load_columns(const HarmonicDofs& d, const std::vector<BandResponse>& bands, Eigen::Index nodes);

/// Harmonic n's responses of the bands: their columns of the solution X, from column `first`.
void store_band_responses(std::vector<BandResponse>& bands, int n, const HarmonicDofs& d, const Eigen::MatrixXd& X,
                          Eigen::Index first);

/// A field's circumferential series as terms: term r is cos nθ (is_sine false) or sin nθ of n = harmonic[r], and
/// column r of `amplitudes` its amplitude at every section node (9·n_section_nodes x n_terms, node by node: u_r, u_θ,
/// u_z, σ_r, σ_z, σ_θ, τ_rz, τ_rθ, τ_θz). Harmonics not solved have no terms.
struct SeriesTerms {
  std::vector<int> harmonic;
  std::vector<bool> is_sine;
  Eigen::MatrixXd amplitudes;

  /// The nine quantities at every section node at each angle: 9·n_section_nodes x angles, one product for them all.
  Eigen::MatrixXd at(const std::vector<double>& theta) const {
    Eigen::MatrixXd terms(amplitudes.cols(), static_cast<Eigen::Index>(theta.size()));
    for (Eigen::Index k = 0; k < terms.cols(); ++k)
      for (Eigen::Index r = 0; r < terms.rows(); ++r) {
        const double nt = harmonic[static_cast<std::size_t>(r)] * theta[static_cast<std::size_t>(k)];
        terms(r, k) = is_sine[static_cast<std::size_t>(r)] ? std::sin(nt) : std::cos(nt);
      }
    return amplitudes * terms;
  }
};

SeriesTerms series_terms(Eigen::Index section_nodes, const HarmonicField& u,
                         const std::vector<Eigen::MatrixXd>& stress_sym, const std::vector<Eigen::MatrixXd>& stress_anti);

/// Generalised loads of a tangential traction ∝ r·e_θ over `edges` in `windows`, scaled to a unit moment about z.
LoadTerm unit_moment_term(const SectionMesh& s, const std::vector<const SectionEdge*>& edges,
                          std::vector<Window> windows);

/// w, v and the normal's rotation μ = (v − dw/dθ)/r of field u on the circle of radius r through probe p, at 1°
/// steps; dw/dθ exactly from the series (the θ-derivative of the radial amplitudes).
void ring_curve(const HarmonicField& u, const Probe& p, double radius_m, std::vector<double>& wv,
                std::vector<double>& vv, std::vector<double>& mu);

}  // namespace sw::fourier
