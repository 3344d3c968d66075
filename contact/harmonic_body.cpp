#include "contact/harmonic_body.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <string>
#include <numbers>
#include <stdexcept>

#include "common/constants.hpp"
#include "contact/hat_patterns.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {
namespace {

/// Every response the harmonic pass solved for the contact: the requested bands, then the stations' band.
std::vector<const BandResponse*> responses(const FourierSolution& s) {
  std::vector<const BandResponse*> r;
  for (const BandResponse& b : s.bands) r.push_back(&b);
  r.push_back(&s.station_band);
  return r;
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

/// ∫ f(θ)·g(θ) dθ over [lo, hi] for a linear g (g(lo) = g_lo, g(hi) = g_hi), to round-off for a series up to N
/// (fem/fourier_loads.hpp series_quadrature).
template <class F>
double integrate_linear(const F& f, double lo, double hi, double g_lo, double g_hi, int N) {
  double sum = 0;
  for (const auto& [t, w] : series_quadrature(lo, hi, N))
    sum += w * f(t) * (g_lo + (g_hi - g_lo) * (t - lo) / (hi - lo));
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
  const FlankHats hats = add_flanks(*m, patterns, slices, r, radius, h);
  const std::vector<HatAmplitudes>& amp = hats.amplitude;
  const std::vector<Eigen::Index>& band_of = hats.band;
  for (int n = 0; n <= N; ++n) {
    m->sym[n].block(np, 2 * (B - 1), rows - np, 2) = hs.phi_sym[n];
    m->anti[n].block(np, 2 * (B - 1), rows - np, 2) = hs.phi_anti[n];
  }
  BodyInfluence out;
  out.A = influence_of(*m, r);
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
    BodyCheck c;
    c.superposition_error_rel = worst / largest;
    c.clamp_reaction_torque_Nm = clamp_reaction_moment(s_.section, c_.material, s_.clamped, u, anti0_loads(*m, r, x));
    return c;
  };
  out.energy_by_region_J = [this, m, r](const Eigen::VectorXd& x) {
    return strain_energy_by_region_J(s_.section, c_.material, field_of(*m, r, x));
  };
  return out;
}

std::vector<NeutralCurveSamples> HarmonicBody::generator_curves_at(const std::vector<double>& z_m) const {
  return neutral_curves_at(s_.section, s_.generator, neutral_radius(c_.flexspline), z_m);
}

}  // namespace sw
