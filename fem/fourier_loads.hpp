#pragma once
// The harmonic model's loads on the meridian section, expanded exactly in θ (as fem/loads.hpp for the TET10 model):
// tractions piecewise constant in θ on boundary edges, the generator's stations (HarmonicStations), the bands'
// responses; and the readings of a harmonic field there (as fem/post.hpp): moments, the series at given angles, a
// ring's w, v and normal rotation. The functions are the harmonic solver's (fem/fourier_solver.cpp,
// fem/fourier_analysis.cpp); the stations and the bands are read by the loaded contact too.
#include <functional>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "fem/flexspline_model.hpp"
#include "fem/fourier_element.hpp"
#include "fem/fourier_section.hpp"

namespace sw {

/// Gauss–Legendre points (8 a piece) on [lo, hi] in pieces short enough for a series up to harmonic N (N·piece ≤
/// 0.5): a smooth function on each piece times a linear one (a hat's flank) integrates to round-off. (θ, weight).
std::vector<std::pair<double, double>> series_quadrature(double lo, double hi, int N);

/// The wave generator's contact stations (fem/flexspline_system.hpp's generator_stations) in the harmonic basis.
/// Station pair j's unit load, 1 N of normal force spread by the hat at θ_j and at θ_j + π, uniform across the band,
/// has the generalised loads of harmonic n
///   symmetric family: Φs(j,0)·E_r + Φs(j,1)·E_θ,   antisymmetric family: Φa(j,0)·E_r + Φa(j,1)·E_θ,
/// with E_r = (S, 0, 0), E_θ = (0, S, 0), S_i = ∫ N_i r ds over the band's inner-wall edges, and Φ the θ moments of
/// the hat times the normal's components (Φs = (∫g_r cos nθ, ∫g_θ sin nθ), Φa = (∫g_r sin nθ, −∫g_θ cos nθ), g the
/// traction per unit S). So every station's load of a harmonic lies in the span of E_r and E_θ: two solves per
/// harmonic, U_r = K_n⁻¹E_r and U_θ = K_n⁻¹E_θ, give the whole influence matrix (exact up to the truncation at N)
///   C = Σ_n Φs_n·G_n·Φs_nᵀ + Φa_n·G_n·Φa_nᵀ,   G_n(a, b) = E_aᵀ·U_b,
/// and the displacement of any station forces p is Σ_n (Φs_nᵀp)·(U_r, U_θ) per family.
struct HarmonicStations {
  bool unilateral = false;
  std::vector<double> angle_rad;      ///< first station of each pair (the other at + π)
  double half_width_rad = 0;          ///< of each station's hat (the stations' spacing)
  Eigen::VectorXd obstacle_m;         ///< per pair, as GeneratorStations::obstacle_m
  Eigen::VectorXd S;                  ///< n_nodes
  std::vector<Eigen::MatrixXd> phi_sym, phi_anti;  ///< per harmonic: pairs × 2

  Eigen::MatrixXd unit(int component) const {
    Eigen::MatrixXd E = Eigen::MatrixXd::Zero(S.size(), 3);
    E.col(component) = S;
    return E;
  }
  double load_norm(int n) const {
    return std::max(phi_sym[n].cwiseAbs().maxCoeff(), phi_anti[n].cwiseAbs().maxCoeff()) * S.cwiseAbs().maxCoeff();
  }
  /// (E_rᵀu, E_θᵀu) of amplitudes u (n_nodes × 3).
  Eigen::Vector2d moments(const Eigen::MatrixXd& u) const { return {S.dot(u.col(0)), S.dot(u.col(1))}; }
  Eigen::MatrixXd influence(const std::vector<Eigen::MatrixXd>& Ur, const std::vector<Eigen::MatrixXd>& Ut) const {
    const Eigen::Index m = static_cast<Eigen::Index>(angle_rad.size());
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(m, m);
    for (std::size_t n = 0; n < Ur.size(); ++n) {
      if (Ur[n].size() == 0) continue;
      Eigen::Matrix2d G;
      G.col(0) = moments(Ur[n]);
      G.col(1) = moments(Ut[n]);
      C.noalias() += phi_sym[n] * G * phi_sym[n].transpose() + phi_anti[n] * G * phi_anti[n].transpose();
    }
    return 0.5 * (C + C.transpose());  // symmetric up to round-off (G_n is); make it exactly so
  }
  /// Work-conjugate displacement of each pair (f_jᵀu) in a field.
  Eigen::VectorXd project(const HarmonicField& u) const {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(angle_rad.size()));
    for (std::size_t n = 0; n < u.sym.size(); ++n)
      if (u.sym[n].size() != 0) v += phi_sym[n] * moments(u.sym[n]) + phi_anti[n] * moments(u.anti[n]);
    return v;
  }
  HarmonicField field(const Eigen::VectorXd& p, const std::vector<Eigen::MatrixXd>& Ur,
                      const std::vector<Eigen::MatrixXd>& Ut) const {
    HarmonicField h;
    h.sym.assign(Ur.size(), {});
    h.anti.assign(Ur.size(), {});
    for (std::size_t n = 0; n < Ur.size(); ++n) {
      if (Ur[n].size() == 0) continue;
      const Eigen::Vector2d s = phi_sym[n].transpose() * p, a = phi_anti[n].transpose() * p;
      h.sym[n] = s[0] * Ur[n] + s[1] * Ut[n];
      h.anti[n] = a[0] * Ur[n] + a[1] * Ut[n];
    }
    return h;
  }
  /// Adds the generalised loads of harmonic n of station forces p to sym, anti (n_nodes × 3).
  void loads(const Eigen::VectorXd& p, int n, Eigen::MatrixXd& sym, Eigen::MatrixXd& anti) const {
    if (p.size() == 0 || n >= static_cast<int>(phi_sym.size())) return;
    const Eigen::Vector2d s = phi_sym[n].transpose() * p, a = phi_anti[n].transpose() * p;
    sym.col(0) += s[0] * S;
    sym.col(1) += s[1] * S;
    anti.col(0) += a[0] * S;
    anti.col(1) += a[1] * S;
  }
};

/// A part of the section's boundary on which a later stage puts loads of its own: the edges with `marker` whose
/// midside node lies in z_lo_m..z_hi_m. Every traction uniform across it along e_r or e_θ, of any angular shape, has
/// the generalised loads of harmonic n in the span of E_r = (S, 0, 0) and E_θ = (0, S, 0), S_i = ∫ N_i r ds over the
/// band: its responses K_n⁻¹E_r, K_n⁻¹E_θ give every such load's response (the loaded contact's flanks,
/// contact/harmonic_body.hpp).
struct SurfaceBand {
  int marker = kSurfaceOther;
  double z_lo_m = -std::numeric_limits<double>::infinity(), z_hi_m = std::numeric_limits<double>::infinity();
};

/// A band's spatial vector S and its responses per harmonic 0..N (n_nodes × 3 amplitudes (a, b, c); empty where the
/// harmonic was not solved).
struct BandResponse {
  Eigen::VectorXd S;
  std::vector<Eigen::MatrixXd> Ur, Ut;
};

}  // namespace sw

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
