#include "fem/generator_contact.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Cholesky>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "fem/loads.hpp"

namespace sw {
namespace {


}  // namespace

BandStations band_stations(const TetMesh& mesh, double z_m, double width_m, const std::vector<double>& angles_rad,
                           double half_width_rad, const NormalTilt& tilt) {
  const auto band = select_faces(mesh, kSurfaceInner, [&](const Eigen::Vector3d& x) {
    return std::abs(x[2] - z_m) <= 0.5 * width_m;
  });
  if (band.empty())
    throw InputError("wave_generator: no inner-wall faces in the generator's band at z = " + std::to_string(z_m * 1e3) +
                     " mm; check wave_generator.axial_position_mm / band_width_mm or refine mesh.size_mm");
  const AngularHats hats(mesh, band);
  BandStations s;
  s.angle_rad = angles_rad;
  s.half_width_rad = half_width_rad;
  std::vector<Eigen::Triplet<double>> triplets;
  for (std::size_t j = 0; j < angles_rad.size(); ++j) {
    Eigen::VectorXd column = Eigen::VectorXd::Zero(3 * mesh.n_nodes());
    for (const double station : {angles_rad[j], angles_rad[j] + kPi}) {
      const Eigen::VectorXd f = hats.load(station, half_width_rad, [&](double t) -> Eigen::Vector3d {
        const double k = tilt ? tilt(t) : 0.0;
        return (Eigen::Vector3d(std::cos(t), std::sin(t), 0) - k * Eigen::Vector3d(-std::sin(t), std::cos(t), 0)) /
               std::sqrt(1 + k * k);
      });
      if (f.size() == 0)
        throw InputError("wave_generator: no inner-wall faces under the contact station at " +
                         std::to_string(station * 180 / kPi) + " deg; refine mesh.size_mm");
      column += f;
    }
    for (Eigen::Index i = 0; i < column.size(); ++i)
      if (column[i] != 0.0) triplets.emplace_back(static_cast<int>(i), static_cast<int>(j), column[i]);
  }
  s.loads.resize(3 * static_cast<Eigen::Index>(mesh.n_nodes()), static_cast<Eigen::Index>(angles_rad.size()));
  s.loads.setFromTriplets(triplets.begin(), triplets.end());
  return s;
}

StationForces unilateral_contact(const Eigen::MatrixXd& C, const Eigen::VectorXd& b) {
  const Eigen::Index n = b.size();
  const double tol = 1e-12 * std::max(b.cwiseAbs().maxCoeff(), 1e-300);
  Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
  std::vector<bool> active(n, false);  // stations in contact (the "passive set" of Lawson–Hanson)
  StationForces out;
  for (int outer = 0; outer < 4 * n + 10; ++outer) {
    const Eigen::VectorXd w = b - C * p;  // minus the gap: positive where the generator would penetrate
    Eigen::Index add = -1;
    double worst = tol;
    for (Eigen::Index i = 0; i < n; ++i)
      if (!active[i] && w[i] > worst) worst = w[add = i];
    if (add < 0) {
      out.force_N = p;
      out.gap_m = C * p - b;
      out.iterations = outer;
      return out;
    }
    active[add] = true;
    for (bool first = true;; first = false) {
      std::vector<Eigen::Index> idx;
      for (Eigen::Index i = 0; i < n; ++i)
        if (active[i]) idx.push_back(i);
      Eigen::MatrixXd Caa(idx.size(), idx.size());
      Eigen::VectorXd ba(idx.size());
      for (std::size_t r = 0; r < idx.size(); ++r) {
        ba[r] = b[idx[r]];
        for (std::size_t c = 0; c < idx.size(); ++c) Caa(r, c) = C(idx[r], idx[c]);
      }
      const Eigen::VectorXd za = Caa.ldlt().solve(ba);
      Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
      for (std::size_t r = 0; r < idx.size(); ++r) z[idx[r]] = za[r];
      if (first && z[add] <= 0) {  // round-off: the station cannot carry load after all
        active[add] = false;
        out.force_N = p;
        out.gap_m = C * p - b;
        out.iterations = outer;
        return out;
      }
      if ((za.array() > 0).all()) {
        p = z;
        break;
      }
      double alpha = 1.0;
      for (Eigen::Index i : idx)
        if (z[i] <= 0) alpha = std::min(alpha, p[i] / (p[i] - z[i]));
      p += alpha * (z - p);
      for (Eigen::Index i : idx)
        if (p[i] <= 1e-15 * p.cwiseAbs().maxCoeff()) {
          p[i] = 0;
          active[i] = false;
        }
    }
  }
  throw std::runtime_error("unilateral_contact: the active-set iteration did not converge");
}

StationForces generator_contact(const Eigen::MatrixXd& C, const Eigen::VectorXd& b, double band_turn_ext_rad,
                                const GeneratorContactModel& model) {
  const bool turn = model.turn_gap_m_per_rad.size() > 0;
  const bool series = static_cast<bool>(model.approach_m);
  if (!turn && !series) return unilateral_contact(C, b);
  const Eigen::Index n = b.size();
  Eigen::VectorXd m = turn ? model.turn_gap_m_per_rad : Eigen::VectorXd::Zero(n);
  Eigen::VectorXd h = turn ? model.band_turn_rad_per_N : Eigen::VectorXd::Zero(n);
  auto approach = [&](double p) { return series ? model.approach_m(std::max(p, 0.0)) : 0.0; };
  Eigen::VectorXd c = Eigen::VectorXd::Zero(n);  // secant compliance in series, per pair
  // The fixed point of the secants (and of the band's turn): converged when no station's force moves by more than
  // 1e-12 of the largest, round-off of the solve; a station that carries almost nothing, where a(p)/p has no finite
  // limit, can keep it crawling at that level, so past the iteration limit a change within 1e-6 of the largest force
  // (a micronewton in a newton: nothing a ball or a bore can feel) stands, with a line saying so.
  constexpr int kIterations = 200;
  StationForces s;
  Eigen::VectorXd p = Eigen::VectorXd::Zero(n);
  for (int it = 1;; ++it) {
    const double chi = band_turn_ext_rad + h.dot(p);
    Eigen::MatrixXd Ce = C;
    Ce.diagonal() += c;
    s = unilateral_contact(Ce, b + m * chi);
    const double change = (s.force_N - p).cwiseAbs().maxCoeff();
    p = s.force_N;
    const double p_max = std::max(p.maxCoeff(), 1e-300);
    // The secant a(p)/p, from a floor where a station carries nothing (a(p)/p grows without bound as p → 0).
    for (Eigen::Index k = 0; k < n && series; ++k) {
      const double pk = std::max(p[k], 1e-9 * p_max);
      c[k] = approach(pk) / pk;
    }
    s.iterations = it;
    if (it > 1 && change <= 1e-12 * p_max) break;
    if (it == kIterations) {
      const std::string what = "generator: the stations' forces with the bearing in series still moved by " +
                               std::to_string(change / p_max) + " of the largest (" + std::to_string(p_max) +
                               " N) after " + std::to_string(kIterations) + " secant iterations";
      if (change > 1e-6 * p_max)
        throw InputError(what + "; a station at the edge of the contact zone lifts off and lands again: a finer [mesh] "
                                "or another generator fit (wave_generator.fit_um) moves it off that edge");
      progress(what + " (under 1e-6 of it): the last iterate stands");
      break;
    }
  }
  s.gap_m = C * p - m * (band_turn_ext_rad + h.dot(p)) - b;
  for (Eigen::Index k = 0; k < n; ++k) s.gap_m[k] += approach(p[k]);
  return s;
}

double ball_load_N(const GeneratorBearing& bearing, double spacing_rad, double station_force_N) {
  return station_force_N * 2 * kPi / (bearing.balls * spacing_rad);
}

std::function<double(double)> bearing_pair_approach(const GeneratorBearing& bearing, double spacing_rad) {
  const double unit = ball_approach_m(bearing, 1.0);  // δ(1 N): the contact ellipse's shape does not depend on Q
  const double per_N = ball_load_N(bearing, spacing_rad, 1.0);
  return [unit, per_N](double p) {
    const double Q = std::max(p, 0.0) * per_N;
    return 2 * unit * std::cbrt(Q * Q);
  };
}

StationForces bilateral_support(const Eigen::MatrixXd& C, const Eigen::VectorXd& b) {
  StationForces out;
  out.force_N = C.ldlt().solve(b);
  out.gap_m = C * out.force_N - b;
  return out;
}

std::vector<bool> touching(const StationForces& s, double touching_gap_m) {
  const double fmax = s.force_N.size() ? s.force_N.maxCoeff() : 0.0;
  std::vector<bool> t(s.force_N.size());
  for (Eigen::Index j = 0; j < s.force_N.size(); ++j)
    t[j] = (fmax > 0 && s.force_N[j] > 1e-9 * fmax) || 0.5 * s.gap_m[j] <= touching_gap_m;
  return t;
}

std::vector<std::pair<double, double>> contact_zones_deg(const std::vector<double>& pair_angle_rad,
                                                          const std::vector<bool>& touching, double step_rad) {
  // Stations over the whole circle, sorted by angle in [−180, 180).
  std::vector<std::pair<double, bool>> st;
  for (std::size_t j = 0; j < pair_angle_rad.size(); ++j)
    for (const double a : {pair_angle_rad[j], pair_angle_rad[j] + kPi})
      st.emplace_back(std::round(wrap_pi(a) * 180 / kPi * 1e6) / 1e6, touching[j]);
  std::sort(st.begin(), st.end());
  const std::size_t n = st.size();
  const double step_deg = step_rad * 180 / kPi * 1.001;
  // Station i continues the zone of station i − 1 when both touch and they are neighbours.
  auto joins = [&](std::size_t i) {
    const std::size_t prev = (i + n - 1) % n;
    return st[i].second && st[prev].second &&
           std::abs(std::remainder(st[i].first - st[prev].first, 360.0)) <= step_deg;
  };
  std::vector<std::pair<double, double>> zones;
  std::size_t start = 0;  // a station that begins no zone across it, so a zone across ±180° stays whole
  while (start < n && joins(start)) ++start;
  if (start == n) return {{-180.0, 180.0}};
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = (start + k) % n;
    if (!st[i].second) continue;
    if (k > 0 && joins(i)) zones.back().second = st[i].first;
    else zones.emplace_back(st[i].first, st[i].first);
  }
  return zones;
}

}  // namespace sw
