#include "kinematics/neutral_curve.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <variant>

#include <Eigen/Dense>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/overloaded.hpp"

namespace sw {

namespace {

/// Derived series v = −∫₀^φ w dφ and μ = −(1/r_m) dw/dφ of an inextensible ring from w (w must have no constant term).
void derive_inextensible(NeutralCurve& c) {
  const size_t n = c.w.a.size();
  c.v.a.assign(n, 0.0);
  c.v.b.assign(n, 0.0);
  c.mu.a.assign(n, 0.0);
  c.mu.b.assign(n, 0.0);
  for (size_t k = 1; k < n; ++k) {
    const double kk = static_cast<double>(k);
    // ∫₀^φ (a cos kφ + b sin kφ) = (a/k) sin kφ − (b/k)(cos kφ − 1)
    c.v.b[k] = -c.w.a[k] / kk;
    c.v.a[k] = c.w.b[k] / kk;
    c.v.a[0] -= c.w.b[k] / kk;
    // d/dφ (a cos kφ + b sin kφ) = −k a sin kφ + k b cos kφ
    c.mu.b[k] = kk * c.w.a[k] / c.mean_radius_m;
    c.mu.a[k] = -kk * c.w.b[k] / c.mean_radius_m;
  }
}

}  // namespace

double FourierSeries::value(double phi) const {
  if (a.empty()) return 0.0;
  const double c1 = std::cos(phi), s1 = std::sin(phi);
  double c = 1.0, s = 0.0, sum = a[0];
  for (size_t k = 1; k < a.size(); ++k) {
    const double cn = c * c1 - s * s1;
    s = s * c1 + c * s1;
    c = cn;
    sum += a[k] * c + b[k] * s;
  }
  return sum;
}

double FourierSeries::derivative(double phi) const {
  if (a.empty()) return 0.0;
  const double c1 = std::cos(phi), s1 = std::sin(phi);
  double c = 1.0, s = 0.0, sum = 0.0;
  for (size_t k = 1; k < a.size(); ++k) {
    const double cn = c * c1 - s * s1;
    s = s * c1 + c * s1;
    c = cn;
    sum += static_cast<double>(k) * (b[k] * c - a[k] * s);
  }
  return sum;
}

NeutralPoint NeutralCurve::at(double phi) const { return {w.value(phi), v.value(phi), mu.value(phi)}; }

double rim_mean_radius(const FlexsplineParams& f) { return f.inner_radius_m + 0.5 * f.rim_thickness_m; }

NeutralCurve cam_neutral_curve(double mean_radius_m, double w0_m) {
  NeutralCurve c;
  c.mean_radius_m = mean_radius_m;
  c.w.a = {0.0, 0.0, w0_m};
  c.w.b = {0.0, 0.0, 0.0};
  derive_inextensible(c);
  std::ostringstream s;
  s << "cam w0·cos2φ, w0 = " << w0_m * 1e3 << " mm";
  c.source = s.str();
  return c;
}

namespace {

/// The thin ring's forces of a force generator (rollers: where they touch), each end of the major axis alike, and
/// what the curve is called.
struct RingForces {
  std::vector<WaveGeneratorForce> forces;
  std::string name;
};
RingForces four_forces(double beta_rad) {
  RingForces r;
  for (double base : {0.0, kPi})
    for (double sgn : {-1.0, 1.0}) r.forces.push_back({base + sgn * beta_rad, 1.0});
  std::ostringstream name;
  name << "thin ring, four forces at ±" << beta_rad * 180.0 / kPi << "° and 180°±" << beta_rad * 180.0 / kPi << "°";
  r.name = name.str();
  return r;
}
RingForces ring_forces(const GeneratorModel& model) {
  return std::visit(
      overloaded{[](const FourForce& f) { return four_forces(f.beta_rad); },
                 [](const Rollers& r) { return four_forces(r.beta_rad); },  // the ring touches the rollers at ±β
                 [](const TwoForce&) {
                   return RingForces{{{0.0, 1.0}, {kPi, 1.0}}, "thin ring, two forces on the major axis"};
                 },
                 [](const GivenForces& g) {
                   if (g.forces.empty())
                     throw InputError("[wave_generator]: model = \"forces\" needs a non-empty forces list");
                   RingForces r;
                   for (const auto& f : g.forces) {
                     r.forces.push_back(f);
                     r.forces.push_back({f.angle_rad + kPi, f.weight});
                   }
                   r.name = "thin ring, " + std::to_string(r.forces.size()) +
                            " forces (list mirrored to both ends of the major axis)";
                   return r;
                 },
                 [](const Cam&) -> RingForces { throw std::logic_error("ring_forces: a cam is no force model"); }},
      model);
}

}  // namespace

NeutralCurve generator_neutral_curve(double mean_radius_m, double w0_m, const WaveGeneratorParams& wg, int n_max) {
  if (cam_of(wg)) return cam_neutral_curve(mean_radius_m, w0_m);
  const RingForces ring = ring_forces(wg.model);
  const std::vector<WaveGeneratorForce>& forces = ring.forces;
  NeutralCurve c;
  c.mean_radius_m = mean_radius_m;
  c.w.a.assign(n_max + 1, 0.0);
  c.w.b.assign(n_max + 1, 0.0);
  for (int n = 2; n <= n_max; ++n) {
    const double g = 1.0 / std::pow(n * n - 1.0, 2);
    for (const auto& f : forces) {
      c.w.a[n] += f.weight * g * std::cos(n * f.angle_rad);
      c.w.b[n] += f.weight * g * std::sin(n * f.angle_rad);
    }
  }
  const double w_at_0 = c.w.value(0.0);
  if (!(w_at_0 > 0)) {
    throw InputError("[wave_generator]: the forces give no outward displacement on the major axis (w(0) = " +
                     std::to_string(w_at_0) + " in units of P·R³/EI); put them near 0° and 180°");
  }
  for (int n = 0; n <= n_max; ++n) {
    c.w.a[n] *= w0_m / w_at_0;
    c.w.b[n] *= w0_m / w_at_0;
  }
  derive_inextensible(c);
  std::ostringstream name;
  name << ring.name << ", w0 = " << w0_m * 1e3 << " mm";
  c.source = name.str();
  return c;
}

NeutralCurve fit_neutral_curve(double mean_radius_m, const std::vector<double>& phi, const std::vector<double>& w,
                               const std::vector<double>& v, const std::vector<double>& mu, std::string source) {
  if (phi.size() < 360 || w.size() != phi.size() || v.size() != phi.size() || mu.size() != phi.size())
    throw InputError(source + ": " + std::to_string(phi.size()) +
                     " samples; need at least 360 (one per degree over the full circle) of phi, w, v and mu");
  const double span = *std::max_element(phi.begin(), phi.end()) - *std::min_element(phi.begin(), phi.end());
  if (span < 2.0 * kPi * (1.0 - 2.0 / phi.size()) - 1e-9)
    throw InputError(source + ": phi spans " + std::to_string(span) + " rad; expected the full circle (2π)");
  const int order = std::min<int>(64, static_cast<int>(phi.size()) / 2 - 1);
  Eigen::MatrixXd A(phi.size(), 2 * order + 1);
  for (size_t i = 0; i < phi.size(); ++i) {
    A(i, 0) = 1.0;
    for (int k = 1; k <= order; ++k) {
      A(i, 2 * k - 1) = std::cos(k * phi[i]);
      A(i, 2 * k) = std::sin(k * phi[i]);
    }
  }
  const auto qr = A.colPivHouseholderQr();
  auto fit = [&](const std::vector<double>& y) {
    const Eigen::VectorXd c = qr.solve(Eigen::Map<const Eigen::VectorXd>(y.data(), y.size()));
    FourierSeries s;
    s.a.assign(order + 1, 0.0);
    s.b.assign(order + 1, 0.0);
    s.a[0] = c(0);
    for (int k = 1; k <= order; ++k) {
      s.a[k] = c(2 * k - 1);
      s.b[k] = c(2 * k);
    }
    return s;
  };
  NeutralCurve c;
  c.mean_radius_m = mean_radius_m;
  c.w = fit(w);
  c.v = fit(v);
  c.mu = fit(mu);
  c.source = std::move(source);
  return c;
}

}  // namespace sw
