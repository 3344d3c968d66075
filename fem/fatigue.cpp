#include "fem/fatigue.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "common/constants.hpp"

namespace sw {
namespace {

constexpr int kSteps = 360;  // 1° of generator rotation

/// Normal stress along the unit vector d of a Voigt stress (xx yy zz yz xz xy).
double normal_stress(const Eigen::VectorXd& s, const Eigen::Vector3d& d) {
  return s[0] * d[0] * d[0] + s[1] * d[1] * d[1] + s[2] * d[2] * d[2] +
         2 * (s[3] * d[1] * d[2] + s[4] * d[0] * d[2] + s[5] * d[0] * d[1]);
}

std::optional<FatiguePoint> history(const std::string& place, double r, double z, double t_r, double t_z,
                                    const Material& m, const PointSampler& sampler, const RowMatrixX6d& stress) {
  const auto h = revolution_history(r, z, t_r, t_z, sampler, stress);
  if (!h) return std::nullopt;
  FatiguePoint p{place, r, z, stress_cycle(h->hoop_Pa), stress_cycle(h->meridional_Pa), 0.0};
  if (m.fatigue_limit_Pa && m.ultimate_strength_Pa)
    p.safety_factor = std::min(goodman_safety_factor(p.hoop, *m.fatigue_limit_Pa, *m.ultimate_strength_Pa),
                               goodman_safety_factor(p.meridional, *m.fatigue_limit_Pa, *m.ultimate_strength_Pa));
  return p;
}

/// True when a is worse than b: a lower safety factor, or without fatigue data a larger alternating stress.
bool worse(const FatiguePoint& a, const FatiguePoint& b) {
  if (a.safety_factor > 0 || b.safety_factor > 0) return a.safety_factor < b.safety_factor;
  return std::max(a.hoop.alternating_Pa, a.meridional.alternating_Pa) >
         std::max(b.hoop.alternating_Pa, b.meridional.alternating_Pa);
}

}  // namespace

std::optional<RevolutionHistory> revolution_history(double r, double z, double t_r, double t_z,
                                                   const PointSampler& sampler, const RowMatrixX6d& stress) {
  RevolutionHistory h;
  h.hoop_Pa.resize(kSteps);
  h.meridional_Pa.resize(kSteps);
  for (int k = 0; k < kSteps; ++k) {
    const double t = 2 * kPi * k / kSteps, c = std::cos(t), s = std::sin(t);
    if (sampler.locate(Eigen::Vector3d(r * c, r * s, z)).first < 0) return std::nullopt;
    const Eigen::VectorXd sig = sampler.interpolate(Eigen::Vector3d(r * c, r * s, z), stress);
    h.hoop_Pa[k] = normal_stress(sig, Eigen::Vector3d(-s, c, 0));
    h.meridional_Pa[k] = normal_stress(sig, Eigen::Vector3d(t_r * c, t_r * s, t_z));
  }
  return h;
}

StressCycle stress_cycle(const std::vector<double>& h) {
  const auto [lo, hi] = std::minmax_element(h.begin(), h.end());
  return {0.5 * (*hi - *lo), 0.5 * (*hi + *lo)};
}

double goodman_safety_factor(const StressCycle& s, double fatigue_limit_Pa, double ultimate_strength_Pa) {
  const double d = s.alternating_Pa / fatigue_limit_Pa + std::max(0.0, s.mean_Pa) / ultimate_strength_Pa;
  return d > 0 ? 1.0 / d : std::numeric_limits<double>::infinity();
}

FatigueReadout flexspline_fatigue(const FlexsplineParams& f, double rim_outer_radius_m, double generator_z_m,
                                  double band_width_m, const Material& material, const PointSampler& sampler,
                                  const RowMatrixX6d& stress) {
  const double inset = 1e-3 * f.inner_radius_m;
  FatigueReadout out;
  // Rim: bore and outer surface over its width (or over the generator's band on a plain tube), 9 levels; the ends
  // are kept half a level in from the open end and the rim's shoulder.
  const bool rim = f.rim_width_m > 0;
  const double z0 = rim ? f.length_m - f.rim_width_m : generator_z_m - 0.5 * band_width_m;
  const double z1 = rim ? f.length_m : generator_z_m + 0.5 * band_width_m;
  const double r_out = rim ? rim_outer_radius_m : f.inner_radius_m + f.wall_thickness_m;
  std::optional<FatiguePoint> rim_worst;
  for (int k = 0; k < 9; ++k) {
    const double z = std::min(z0 + (k + 0.5) * (z1 - z0) / 9, f.length_m - inset);
    for (const auto& [place, r] : {std::pair<std::string, double>{"rim bore", f.inner_radius_m + inset},
                                   std::pair<std::string, double>{"rim outer surface", r_out - inset}}) {
      const auto p = history(place, r, z, 0.0, 1.0, material, sampler, stress);
      if (p && (!rim_worst || worse(*p, *rim_worst))) rim_worst = p;
    }
  }
  if (!rim_worst) throw std::logic_error("flexspline_fatigue: no rim point lies inside the mesh");
  out.rim = *rim_worst;
  if (f.shape != FlexsplineShape::Cup) return out;
  // Diaphragm: the fillet between its top face and the bore (centre (r_i − R, t_d + R)), meridional = the arc's
  // tangent. Not its edge at the boss: the model clamps the boss rigidly, a re-entrant corner whose stress grows
  // without bound with mesh refinement (an artefact, not the hub's fillet).
  const double R = f.fillet_radius_m, td = f.diaphragm_thickness_m, ri = f.inner_radius_m;
  std::optional<FatiguePoint> worst;
  for (int k = 0; k <= 9; ++k) {
    const double a = 0.5 * kPi * k / 9;
    const double r = ri - R + (R + inset) * std::sin(a), z = td + R - (R + inset) * std::cos(a);
    const auto p = history("diaphragm fillet", r, z, std::cos(a), std::sin(a), material, sampler, stress);
    if (p && (!worst || worse(*p, *worst))) worst = p;
  }
  out.diaphragm = worst;
  return out;
}

}  // namespace sw
