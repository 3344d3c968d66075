#include "fem/fourier_loads.hpp"

#include <cmath>

#include "common/constants.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/flexspline_system.hpp"

namespace sw {

std::vector<std::pair<double, double>> series_quadrature(double lo, double hi, int N) {
  static const double gx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                               0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
  static const double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                               0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const int pieces = static_cast<int>(std::ceil(N * (hi - lo) / 0.5)) + 1;
  std::vector<std::pair<double, double>> points;
  points.reserve(8 * static_cast<std::size_t>(pieces));
  for (int q = 0; q < pieces; ++q) {
    const double a = lo + (hi - lo) * q / pieces, b = lo + (hi - lo) * (q + 1) / pieces;
    for (int g = 0; g < 8; ++g) points.emplace_back(0.5 * (a + b) + 0.5 * (b - a) * gx[g], 0.5 * (b - a) * gw[g]);
  }
  return points;
}

namespace fourier {

double cos_moment(const std::vector<Window>& ws, int n) {  // ∫ g(θ) cos nθ dθ
  double m = 0;
  for (const auto& w : ws) m += w.weight * (n == 0 ? w.to - w.from : (std::sin(n * w.to) - std::sin(n * w.from)) / n);
  return m;
}

double sin_moment(const std::vector<Window>& ws, int n) {  // ∫ g(θ) sin nθ dθ
  double m = 0;
  for (const auto& w : ws) m += w.weight * (n == 0 ? 0.0 : (std::cos(n * w.from) - std::cos(n * w.to)) / n);
  return m;
}

std::vector<const SectionEdge*> select_edges(const SectionMesh& s, int marker,
                                             const std::function<bool(const Eigen::Vector2d&)>& keep) {
  std::vector<const SectionEdge*> out;
  for (const auto& e : s.edges)
    if (e.marker == marker && (!keep || keep(s.nodes.row(e.nodes[2]).transpose()))) out.push_back(&e);
  return out;
}

std::vector<const SectionEdge*> band_edges(const SectionMesh& s, const SurfaceBand& b) {
  return select_edges(s, b.marker, [&](const Eigen::Vector2d& x) { return x[1] >= b.z_lo_m && x[1] <= b.z_hi_m; });
}

Eigen::VectorXd band_vector(const SectionMesh& s, const std::vector<const SectionEdge*>& edges) {
  return edge_integral(s, edges, [](const Eigen::Vector2d&) { return Eigen::Vector3d(1, 0, 0); }).col(0);
}

void harmonic_loads(const std::vector<LoadTerm>& terms, int n, Eigen::MatrixXd& sym, Eigen::MatrixXd& anti) {
  for (const auto& t : terms) {
    const double C = cos_moment(t.windows, n), S = sin_moment(t.windows, n);
    sym.col(0) += C * t.spatial.col(0);
    sym.col(1) += S * t.spatial.col(1);
    sym.col(2) += C * t.spatial.col(2);
    anti.col(0) += S * t.spatial.col(0);
    anti.col(1) -= C * t.spatial.col(1);
    anti.col(2) += S * t.spatial.col(2);
  }
}

HarmonicStations harmonic_stations(const FlexsplineModel& c, const Eigen::VectorXd& S, int N) {
  const auto& w = *c.wave_generator;
  const double r = c.flexspline.inner_radius_m;
  if (N < 2)
    throw InputError("solver.harmonics = " + std::to_string(N) +
                     ": a wave generator deforms the flexspline in harmonics 2 and up; use harmonics >= 2");
  HarmonicStations h;
  h.S = S;
  const int pairs = std::min(static_cast<int>(std::lround(kPi / station_spacing(c))), N / 2);
  const double spacing = kPi / pairs;
  h.half_width_rad = spacing;
  const StationLayout layout = station_layout(w, r, spacing);
  h.unilateral = layout.unilateral;
  h.angle_rad = layout.angle_rad;
  const std::function<double(double)> tilt = layout.tilt ? layout.tilt : [](double) { return 0.0; };
  const Eigen::Index m = static_cast<Eigen::Index>(h.angle_rad.size());
  h.obstacle_m = layout.obstacle_m;
  h.phi_sym.assign(N + 1, Eigen::MatrixXd::Zero(m, 2));
  h.phi_anti.assign(N + 1, Eigen::MatrixXd::Zero(m, 2));
  // θ moments by quadrature of the hat's two linear flanks (series_quadrature: exact to round-off).
  const std::vector<std::pair<double, double>> flank = series_quadrature(0.0, spacing, N);  // distance from the centre
  const double area = spacing * S.sum();  // ∫ hat dA: ∫ hat dθ = Δ, ∫ r ds = Σ S_i
  for (Eigen::Index j = 0; j < m; ++j)
    for (const double centre : {h.angle_rad[j], h.angle_rad[j] + kPi})
      for (int side : {-1, 1})
        for (const auto& [d, w] : flank) {
          const double t = centre + side * d;
          const double weight = w * (1 - d / spacing) / area;
          const double k = tilt(t), nr = 1 / std::sqrt(1 + k * k), nt = -k * nr;
          for (int n = 0; n <= N; ++n) {
            const double cn = std::cos(n * t), sn = std::sin(n * t);
            h.phi_sym[n](j, 0) += weight * nr * cn;
            h.phi_sym[n](j, 1) += weight * nt * sn;
            h.phi_anti[n](j, 0) += weight * nr * sn;
            h.phi_anti[n](j, 1) -= weight * nt * cn;
          }
        }
  return h;
}

double moment_z(const SectionMesh& s, const Eigen::MatrixXd& anti0) { return -s.nodes.col(0).dot(anti0.col(1)); }

Eigen::MatrixXd band_load_columns(const HarmonicDofs& d, const std::vector<BandResponse>& bands, Eigen::Index nodes) {
  Eigen::MatrixXd B(d.n_eq, 2 * static_cast<Eigen::Index>(bands.size()));
  for (std::size_t b = 0; b < bands.size(); ++b)
    for (int k = 0; k < 2; ++k) {
      Eigen::MatrixXd E = Eigen::MatrixXd::Zero(nodes, 3);
      E.col(k) = bands[b].S;
      B.col(2 * static_cast<Eigen::Index>(b) + k) = to_equations(d, E);
    }
  return B;
}

void store_band_responses(std::vector<BandResponse>& bands, int n, const HarmonicDofs& d, const Eigen::MatrixXd& X,
                          Eigen::Index first) {
  const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(d.eq.size() / 3), 3);
  for (std::size_t b = 0; b < bands.size(); ++b) {
    bands[b].Ur[n] = to_nodes(d, X.col(first + 2 * static_cast<Eigen::Index>(b)), zero);
    bands[b].Ut[n] = to_nodes(d, X.col(first + 2 * static_cast<Eigen::Index>(b) + 1), zero);
  }
}

SeriesTerms series_terms(Eigen::Index section_nodes, const HarmonicField& u,
                         const std::vector<Eigen::MatrixXd>& stress_sym, const std::vector<Eigen::MatrixXd>& stress_anti) {
  SeriesTerms t;
  for (std::size_t n = 0; n < u.sym.size(); ++n)
    if (u.sym[n].size() != 0)
      for (bool sine : {false, true}) {
        t.harmonic.push_back(static_cast<int>(n));
        t.is_sine.push_back(sine);
      }
  t.amplitudes.resize(9 * section_nodes, static_cast<Eigen::Index>(t.harmonic.size()));
  // u_r, u_z, the normal stresses and τ_rz go as a·cos + b·sin (a sym, b anti); u_θ, τ_rθ, τ_θz as a·sin − b·cos.
  constexpr bool kGoesWithSine[9] = {false, true, false, false, false, false, false, true, true};
  for (std::size_t r = 0; r < t.harmonic.size(); ++r) {
    const std::size_t n = static_cast<std::size_t>(t.harmonic[r]);
    for (Eigen::Index i = 0; i < section_nodes; ++i)
      for (int q = 0; q < 9; ++q) {
        const double a = q < 3 ? u.sym[n](i, q) : stress_sym[n](i, q - 3);
        const double b = q < 3 ? u.anti[n](i, q) : stress_anti[n](i, q - 3);
        const double with_cos = kGoesWithSine[q] ? -b : a, with_sin = kGoesWithSine[q] ? a : b;
        t.amplitudes(9 * i + q, static_cast<Eigen::Index>(r)) = t.is_sine[r] ? with_sin : with_cos;
      }
  }
  return t;
}

LoadTerm unit_moment_term(const SectionMesh& s, const std::vector<const SectionEdge*>& edges,
                          std::vector<Window> windows) {
  LoadTerm t;
  t.windows = std::move(windows);
  t.spatial = edge_integral(s, edges, [](const Eigen::Vector2d& x) { return Eigen::Vector3d(0, x[0], 0); });
  // Moment of the term: Σ window widths × ∫ h_θ r · r ds = cos-moment(0) × Σ_i r_i spatial_θ,i.
  const double moment = cos_moment(t.windows, 0) * s.nodes.col(0).dot(t.spatial.col(1));
  t.spatial /= moment;
  return t;
}

void ring_curve(const HarmonicField& u, const Probe& p, double radius_m, std::vector<double>& wv,
                std::vector<double>& vv, std::vector<double>& mu) {
  for (int k = 0; k < kRingSamples; ++k) {
    const double t = 2 * kPi * k / kRingSamples;
    const Eigen::Vector3d d = displacement_at(u, p, t);
    double dw = 0;
    for (std::size_t n = 1; n < u.sym.size(); ++n) {
      if (u.sym[n].size() == 0) continue;
      double as = 0, aa = 0;
      for (int j = 0; j < 6; ++j) {
        as += p.weight[j] * u.sym[n](p.node[j], 0);
        aa += p.weight[j] * u.anti[n](p.node[j], 0);
      }
      dw += n * (-as * std::sin(n * t) + aa * std::cos(n * t));
    }
    wv.push_back(d[0]);
    vv.push_back(d[1]);
    mu.push_back((d[1] - dw) / radius_m);
  }
}

}  // namespace fourier
}  // namespace sw
