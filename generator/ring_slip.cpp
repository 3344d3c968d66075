#include "generator/ring_slip.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "common/error.hpp"

namespace sw {

std::vector<double> bore_curvature_change_per_m(const CamSurface& cam, double bore_radius_m,
                                                const std::vector<double>& angle_rad) {
  // ρ' and ρ'' by central differences: ρ is smooth (a closed form or a C² spline), and at h = 1e-3 rad the truncation
  // (h²/12·ρ'''') and the round-off (ε·ρ/h²) are both below 1e-6 of the curvature change of any w0 the model takes.
  constexpr double h = 1e-3;
  std::vector<double> out;
  out.reserve(angle_rad.size());
  for (const double t : angle_rad) {
    const double r = cam.radius_m(t), rp = cam.radius_m(t + h), rm = cam.radius_m(t - h);
    const double d1 = (rp - rm) / (2 * h), d2 = (rp - 2 * r + rm) / (h * h);
    const double kappa = (r * r + 2 * d1 * d1 - r * d2) / std::pow(r * r + d1 * d1, 1.5);
    out.push_back(kappa - 1.0 / bore_radius_m);
  }
  return out;
}

double ring_slip_lever_m(double rim_thickness_m, const GeneratorBearing& b) {
  return 0.5 * rim_thickness_m + 0.5 * kOuterRingWallPerBallDiameter * b.ball_diameter_m;
}

RingSlip ring_slip(const std::vector<double>& force_N, const std::vector<double>& curvature_change_per_m,
                   double bore_radius_m, double lever_m, double friction) {
  const auto fail = [](const std::string& what, double v, const char* must) {
    std::ostringstream os;
    os << "ring slip: " << what << " " << v << "; must be " << must;
    throw InputError(os.str());
  };
  if (force_N.size() != curvature_change_per_m.size())
    fail("stations' curvatures", static_cast<double>(curvature_change_per_m.size()), "one per station force");
  if (!(bore_radius_m > 0)) fail("bore radius", bore_radius_m, "> 0 m");
  if (!(lever_m > 0)) fail("lever", lever_m, "> 0 m");
  if (!(friction >= 0 && friction <= 1)) fail("friction coefficient", friction, "in [0, 1]");
  double total = 0;
  for (const double f : force_N) {
    if (!(f >= 0) || !std::isfinite(f)) fail("station force", f, "finite and >= 0 N");
    total += f;
  }
  RingSlip out;
  if (total == 0) return out;
  // The weighted median: the station at which the forces below and above it each stay within half the total.
  std::vector<std::size_t> order(force_N.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return curvature_change_per_m[a] < curvature_change_per_m[b]; });
  double below = 0;
  for (const std::size_t i : order) {
    below += force_N[i];
    if (below >= 0.5 * total) {
      out.creep_curvature_per_m = curvature_change_per_m[i];
      break;
    }
  }
  double sum = 0;
  for (std::size_t i = 0; i < force_N.size(); ++i)
    sum += force_N[i] * std::abs(curvature_change_per_m[i] - out.creep_curvature_per_m);
  out.moment_Nm = friction * bore_radius_m * lever_m * sum;
  return out;
}

double ring_on_bore_moment_Nm(const RingOnBore& ring, const std::vector<double>& station_force_N) {
  if (ring.curvature_change_per_m.empty()) return 0;
  return 2 * ring_slip(station_force_N, ring.curvature_change_per_m, ring.bore_radius_m, ring.lever_m, ring.friction)
                 .moment_Nm;
}

}  // namespace sw
