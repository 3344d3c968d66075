#include "contact/harmonic_body.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <string>
#include <numbers>
#include <stdexcept>

#include "mesh/tet_mesh.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;

/// ∫ hat(θ − c)·cos nθ dθ / cos nc for a linear hat of height 1 and half-width h (the same for sin).
double hat_moment(int n, double h) {
  return n == 0 ? h : 2 * (1 - std::cos(n * h)) / (static_cast<double>(n) * n * h);
}

/// A flank pattern's three amplitudes (tractions at the hats' peaks, Pa) on a band with spatial vector S: radial and
/// tangential hats of half-width h at the station, a radial couple of hats h/2 wide either side. In the station's own
/// frame (e_r, e_θ) the pattern's resultant is (H_1(h)·a_r, H_1(h)·a_t + 2·H_1(h/2)·sin(h/2)·a_m)·ΣS and its moment
/// about the axis h·a_t·Σ r_i S_i (the couple's is zero), which the contact force F at radius ρ sets to (F_r, F_θ)
/// and ρ·F_θ.
struct HatAmplitudes {
  double radial = 0, tangential = 0, couple = 0;
};
HatAmplitudes amplitudes(const FlankPattern& p, double h, double sum_S, double sum_rS) {
  const double c = p.stations_rad.front();
  const double F_r = p.scale * p.force_dir.dot(Eigen::Vector2d(std::cos(c), std::sin(c)));
  const double F_t = p.scale * p.force_dir.dot(Eigen::Vector2d(-std::sin(c), std::cos(c)));
  HatAmplitudes a;
  a.radial = F_r / (hat_moment(1, h) * sum_S);
  a.tangential = p.contact_radius_m * F_t / (h * sum_rS);
  a.couple = (F_t - a.tangential * hat_moment(1, h) * sum_S) / (2 * hat_moment(1, h / 2) * std::sin(h / 2) * sum_S);
  return a;
}

/// The θ moments of every load per harmonic: row j's load of harmonic n is Σ_b Φs(j, 2b)·E_r,b + Φs(j, 2b+1)·E_θ,b
/// in the symmetric family, the same with Φa in the antisymmetric one (fem/fourier_solver.hpp HarmonicStations).
struct Moments {
  std::vector<Eigen::MatrixXd> sym, anti;
};

/// Adds a flank pattern (row `row`, band columns `col`, `col` + 1) with its amplitudes at each of its stations (the
/// half-turn partner's local frame is turned with it, so its amplitudes are the same).
void add_flank(Moments& m, Eigen::Index row, Eigen::Index col, const FlankPattern& p, const HatAmplitudes& a,
               double h) {
  for (std::size_t n = 0; n < m.sym.size(); ++n) {
    const int k = static_cast<int>(n);
    const double Hh = hat_moment(k, h), Hq = hat_moment(k, h / 2);
    for (const double c : p.stations_rad) {
      const double cs = std::cos(k * c), sn = std::sin(k * c);
      const double cp = std::cos(k * (c + h / 2)), cm = std::cos(k * (c - h / 2));
      const double sp = std::sin(k * (c + h / 2)), sm = std::sin(k * (c - h / 2));
      m.sym[n](row, col) += a.radial * Hh * cs + a.couple * Hq * (cp - cm);
      m.anti[n](row, col) += a.radial * Hh * sn + a.couple * Hq * (sp - sm);
      m.sym[n](row, col + 1) += a.tangential * Hh * sn;
      m.anti[n](row, col + 1) -= a.tangential * Hh * cs;
    }
  }
}

/// Every response the harmonic pass solved for the contact: the requested bands, then the stations' band.
std::vector<const BandResponse*> responses(const FourierSolution& s) {
  std::vector<const BandResponse*> r;
  for (const BandResponse& b : s.bands) r.push_back(&b);
  r.push_back(&s.station_band);
  return r;
}

/// G_n(2a + k, 2b + l) = E_{a,k}ᵀ·K_n⁻¹·E_{b,l} (k, l: 0 radial, 1 tangential); empty when n was not solved.
Eigen::MatrixXd gram(const std::vector<const BandResponse*>& r, std::size_t n) {
  const Eigen::Index B = static_cast<Eigen::Index>(r.size());
  if (r.front()->Ur[n].size() == 0) return {};
  Eigen::MatrixXd G(2 * B, 2 * B);
  for (Eigen::Index a = 0; a < B; ++a)
    for (Eigen::Index b = 0; b < B; ++b)
      for (int l = 0; l < 2; ++l) {
        const Eigen::MatrixXd& U = l == 0 ? r[b]->Ur[n] : r[b]->Ut[n];
        for (int k = 0; k < 2; ++k) G(2 * a + k, 2 * b + l) = r[a]->S.dot(U.col(k));
      }
  return G;
}

/// The field of loads x (per row of the moments): Σ_b the band's responses weighted by the loads' moments.
HarmonicField field_of(const Moments& m, const std::vector<const BandResponse*>& r, const Eigen::VectorXd& x) {
  HarmonicField u;
  u.sym.assign(m.sym.size(), {});
  u.anti.assign(m.sym.size(), {});
  for (std::size_t n = 0; n < m.sym.size(); ++n) {
    if (r.front()->Ur[n].size() == 0) continue;
    const Eigen::VectorXd ws = m.sym[n].transpose() * x, wa = m.anti[n].transpose() * x;
    u.sym[n] = Eigen::MatrixXd::Zero(r.front()->Ur[n].rows(), 3);
    u.anti[n] = u.sym[n];
    for (std::size_t b = 0; b < r.size(); ++b) {
      const Eigen::Index i = 2 * static_cast<Eigen::Index>(b);
      u.sym[n] += ws[i] * r[b]->Ur[n] + ws[i + 1] * r[b]->Ut[n];
      u.anti[n] += wa[i] * r[b]->Ur[n] + wa[i + 1] * r[b]->Ut[n];
    }
  }
  return u;
}

/// A band's S-weighted displacement component k (0 radial, 1 tangential) of a field as a series in θ: coefficients of
/// cos nθ and sin nθ.
struct BandSeries {
  Eigen::VectorXd c, s;
  double at(double theta) const {  // e^{inθ} by recurrence: one sin and cos per point
    const std::complex<double> step = std::polar(1.0, theta);
    std::complex<double> e = 1.0;
    double v = 0;
    for (Eigen::Index n = 0; n < c.size(); ++n, e *= step) v += c[n] * e.real() + s[n] * e.imag();
    return v;
  }
};
BandSeries band_series(const HarmonicField& u, const Eigen::VectorXd& S, int k) {
  const Eigen::Index N = static_cast<Eigen::Index>(u.sym.size());
  BandSeries b{Eigen::VectorXd::Zero(N), Eigen::VectorXd::Zero(N)};
  for (Eigen::Index n = 0; n < N; ++n) {
    if (u.sym[n].size() == 0) continue;
    const double a_sym = S.dot(u.sym[n].col(k)), a_anti = S.dot(u.anti[n].col(k));
    if (k == 0) b.c[n] = a_sym, b.s[n] = a_anti;  // u_r = a·cos + ã·sin
    else b.s[n] = a_sym, b.c[n] = -a_anti;        // u_θ = b·sin − b̃·cos
  }
  return b;
}

/// ∫ f(θ)·g(θ) dθ over [lo, hi] for a linear g (g(lo) = g_lo, g(hi) = g_hi) by Gauss–Legendre on pieces short enough
/// for the series' highest harmonic (N·piece ≤ 0.5): smooth on each piece, exact to round-off.
template <class F>
double integrate_linear(const F& f, double lo, double hi, double g_lo, double g_hi, int N) {
  static const double gx[8] = {-0.9602898564975363, -0.7966664774136267, -0.5255324099163290, -0.1834346424956498,
                               0.1834346424956498,  0.5255324099163290,  0.7966664774136267,  0.9602898564975363};
  static const double gw[8] = {0.1012285362903763, 0.2223810344533745, 0.3137066458778873, 0.3626837833783620,
                               0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const int pieces = static_cast<int>(std::ceil(N * (hi - lo) / 0.5)) + 1;
  double sum = 0;
  for (int q = 0; q < pieces; ++q) {
    const double a = lo + (hi - lo) * q / pieces, b = lo + (hi - lo) * (q + 1) / pieces;
    for (int g = 0; g < 8; ++g) {
      const double t = 0.5 * (a + b) + 0.5 * (b - a) * gx[g];
      sum += 0.5 * (b - a) * gw[g] * f(t) * (g_lo + (g_hi - g_lo) * (t - lo) / (hi - lo));
    }
  }
  return sum;
}

/// The work-conjugate displacement of a flank pattern in a field, by quadrature of its hats against the band's
/// displacement series: the reading side of A without its closed-form moments.
double read_by_quadrature(const FlankPattern& p, const HatAmplitudes& a, double h, const BandSeries& ur,
                          const BandSeries& ut, int N) {
  const auto r = [&](double t) { return ur.at(t); };
  const auto t_ = [&](double t) { return ut.at(t); };
  double w = 0;
  for (const double c : p.stations_rad) {
    for (const int side : {-1, 1}) {  // the hats' two flanks: g from 1 at the centre to 0 at the foot
      w += a.radial * integrate_linear(r, std::min(c, c + side * h), std::max(c, c + side * h), side < 0 ? 0 : 1,
                                       side < 0 ? 1 : 0, N);
      w += a.tangential * integrate_linear(t_, std::min(c, c + side * h), std::max(c, c + side * h), side < 0 ? 0 : 1,
                                           side < 0 ? 1 : 0, N);
      for (const int half : {-1, 1}) {  // the couple: +hat at c + h/2, −hat at c − h/2
        const double centre = c + half * h / 2, lo = std::min(centre, centre + side * h / 2),
                     hi = std::max(centre, centre + side * h / 2);
        w += half * a.couple * integrate_linear(r, lo, hi, side < 0 ? 0 : 1, side < 0 ? 1 : 0, N);
      }
    }
  }
  return w;
}

}  // namespace

BandRequest contact_band_request(const FlexsplineModel& c, int face_slices) {
  BandRequest r;
  r.bands.push_back({kSurfaceRimOuter});
  for (int j = 0; face_slices > 1 && j < face_slices; ++j) {
    const auto [lo, hi] = face_slice_m(c.flexspline, j, face_slices);
    r.bands.push_back({kSurfaceRimOuter, lo, hi});
  }
  r.odd_harmonics = c.gear && c.gear->teeth_flexspline % 2 != 0;
  return r;
}

HarmonicBody::HarmonicBody(const FlexsplineModel& c, const FourierSolution& s) : c_(c), s_(s) {
  if (!s.stations || s.bands.empty())
    throw std::logic_error("the harmonic solution was not solved with the contact's bands and a generator");
  stations_.unilateral = s.stations->unilateral;
  stations_.angle_rad = s.stations->angle_rad;
  stations_.half_width_rad = s.stations->half_width_rad;
}

BodyInfluence HarmonicBody::influence(const std::vector<FlankPattern>& patterns, int slices) const {
  const std::vector<const BandResponse*> r = responses(s_);
  const Eigen::Index B = static_cast<Eigen::Index>(r.size()), np = static_cast<Eigen::Index>(patterns.size());
  const HarmonicStations& hs = *s_.stations;
  const Eigen::Index rows = np + static_cast<Eigen::Index>(hs.angle_rad.size());
  if (slices > 1 && static_cast<int>(s_.bands.size()) != slices + 1)
    throw std::logic_error("the harmonic solution has no bands for " + std::to_string(slices) + " face slices");
  const int N = s_.harmonics_kept;
  const double h = 2 * kPi / c_.gear->teeth_flexspline;
  const Eigen::VectorXd& radius = s_.section.nodes.col(0);
  auto m = std::make_shared<Moments>();
  m->sym.assign(N + 1, Eigen::MatrixXd::Zero(rows, 2 * B));
  m->anti = m->sym;
  std::vector<HatAmplitudes> amp;
  std::vector<Eigen::Index> band_of;
  for (Eigen::Index j = 0; j < np; ++j) {
    const FlankPattern& p = patterns[static_cast<std::size_t>(j)];
    const Eigen::Index b = p.slice >= 0 && slices > 1 ? 1 + p.slice : 0;
    const Eigen::VectorXd& S = r[b]->S;
    amp.push_back(amplitudes(p, h, S.sum(), radius.dot(S)));
    band_of.push_back(b);
    add_flank(*m, j, 2 * b, p, amp.back(), h);
  }
  for (int n = 0; n <= N; ++n) {
    m->sym[n].block(np, 2 * (B - 1), rows - np, 2) = hs.phi_sym[n];
    m->anti[n].block(np, 2 * (B - 1), rows - np, 2) = hs.phi_anti[n];
  }
  BodyInfluence out;
  out.A = Eigen::MatrixXd::Zero(rows, rows);
  for (int n = 0; n <= N; ++n) {
    const Eigen::MatrixXd G = gram(r, n);
    if (G.size() == 0) continue;
    out.A.noalias() += m->sym[n] * G * m->sym[n].transpose() + m->anti[n] * G * m->anti[n].transpose();
  }
  out.A = 0.5 * (out.A + out.A.transpose()).eval();
  // The lever is the moment of the load the contact's partner takes back (as the TET10 body's): minus the moment
  // about z of the pattern's load on the flexspline, −(−Φa₀(·, θ)·Σ r_i S_i) (fem/fourier_solver.cpp moment_z).
  out.lever = Eigen::VectorXd::Zero(rows);
  for (Eigen::Index b = 0; b < B; ++b) out.lever += m->anti[0].col(2 * b + 1) * radius.dot(r[b]->S);
  out.check = [this, m, r, amp, band_of, patterns, h, N, A = out.A](const Eigen::VectorXd& x) {
    const HarmonicField u = field_of(*m, r, x);
    const Eigen::VectorXd by_influence = A * x;
    double worst = 0, largest = 0;
    for (std::size_t j = 0; j < patterns.size(); ++j) {
      const Eigen::VectorXd& S = r[band_of[j]]->S;
      const double direct = read_by_quadrature(patterns[j], amp[j], h, band_series(u, S, 0), band_series(u, S, 1), N);
      worst = std::max(worst, std::abs(direct - by_influence[static_cast<Eigen::Index>(j)]));
      largest = std::max(largest, std::abs(direct));
    }
    Eigen::MatrixXd anti0 = Eigen::MatrixXd::Zero(s_.section.nodes.rows(), 3);
    const Eigen::VectorXd w0 = m->anti[0].transpose() * x;
    for (std::size_t b = 0; b < r.size(); ++b) {
      anti0.col(0) += w0[2 * static_cast<Eigen::Index>(b)] * r[b]->S;
      anti0.col(1) += w0[2 * static_cast<Eigen::Index>(b) + 1] * r[b]->S;
    }
    BodyCheck c;
    c.superposition_error_rel = worst / largest;
    c.clamp_reaction_torque_Nm = clamp_reaction_moment(s_.section, c_.material, s_.clamped, u, anti0);
    return c;
  };
  return out;
}

std::vector<NeutralCurveSamples> HarmonicBody::generator_curves_at(const std::vector<double>& z_m) const {
  return neutral_curves_at(s_.section, s_.generator, neutral_radius(c_.flexspline), z_m);
}

}  // namespace sw
