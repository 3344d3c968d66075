#include "datasheet/limits.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <cstdio>
#include <numbers>
#include <string>
#include <tuple>

#include "common/error.hpp"
#include "contact/contact_body.hpp"
#include "gear/tooth_root.hpp"
#include "generator/bearing_life.hpp"

namespace sw {

double pulsating_allowable_stress_Pa(double fatigue_limit_Pa, double ultimate_strength_Pa) {
  return 2 / (1 / fatigue_limit_Pa + 1 / ultimate_strength_Pa);
}

namespace {
/// h_t of the flexspline's teeth: addendum plus dedendum.
double flexspline_tooth_depth_m(const GearParams& gear) {
  return (gear.addendum_coefficient_flexspline + gear.dedendum_coefficient_flexspline) * gear.module_m;
}
}  // namespace

std::string tooth_root_not_covered(const GearParams& gear, const FlexsplineParams& flexspline) {
  const double depth_m = flexspline_tooth_depth_m(gear);
  const double ratio = flexspline.rim_thickness_m / depth_m;
  if (flexspline.rim_thickness_m == 0 || ratio > kRimBackupRatioMin) return "";
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "not computed: the rim under the teeth (%.3f mm) is %.2f of their depth (%.3f mm), and ISO 6336-3's rim "
                "factor Y_B covers rims thicker than %.1f of it",
                flexspline.rim_thickness_m * 1e3, ratio, depth_m * 1e3, kRimBackupRatioMin);
  return buf;
}

ToothRootFigure tooth_root_limit(const GearParams& gear, const FlexsplineParams& flexspline, const Material& material,
                                 const ContactAnalysis& contact) {
  if (!material.fatigue_limit_Pa || !material.ultimate_strength_Pa)
    throw InputError("the teeth's root limit needs material.fatigue_limit_MPa and material.ultimate_strength_MPa");
  const TorqueStep& rated = contact.steps.back();
  const SpurTeeth teeth = flexspline_teeth(gear);
  (void)external_root_form(teeth, spur_tip_radius_m(teeth, false));  // the tooth itself: its errors are the case's
  RootStressFactors factors;
  factors.rim_thickness = rim_thickness_factor(flexspline.rim_thickness_m, flexspline_tooth_depth_m(gear));
  // Each contact over its own band of the face (a face in sections: each section's force over the band it stands
  // for, so the load's gathering along the face is in the stress, as ISO's K_Fβ would put it), at its own radius.
  double sigma = 0, force_N = 0, radius_m = 0, band_m = 0;
  int below = 0;
  ToothRootForm form;
  for (std::size_t i = 0; i < contact.flanks.size(); ++i) {
    if (!(rated.flank_force_N[i] > 0)) continue;
    const FlankContact& f = contact.flanks[i];
    const double band = flexspline.rim_width_m * face_slice(f.slice, contact.face_slices).width();
    ToothRootForm at;
    try {
      at = external_root_form(teeth, f.contact_radius_m);
    } catch (const InputError&) {  // loaded below the 30° tangent's section (arm ≤ 0) or off the flank
      ++below;
      continue;
    }
    const double s = nominal_root_stress_Pa(at, gear.module_m, rated.flank_force_N[i] * std::cos(gear.pressure_angle_rad),
                                            band, factors);
    if (s > sigma) std::tie(sigma, force_N, radius_m, band_m, form) = std::tuple{s, rated.flank_force_N[i],
                                                                               f.contact_radius_m, band, at};
  }
  const double allowable = pulsating_allowable_stress_Pa(*material.fatigue_limit_Pa, *material.ultimate_strength_Pa);
  ToothRootFigure out;
  out.root_stress_at_rated_Pa = sigma;
  out.torque_Nm = sigma > 0 ? contact.rated_torque_Nm * allowable / sigma : std::numeric_limits<double>::infinity();
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "ISO 6336-3 method B on the flexspline's flank contact of largest root stress at rated torque (%.1f N "
                "over %.2f mm of the face, contact radius %.3f mm): Y_F %.3f, Y_S %.3f, Y_B %.3f, root stress %.0f MPa "
                "against the pulsating allowable %.0f MPa (Goodman, the material's S_e and S_u); %d loaded contacts "
                "below the root's critical section left out (the method does not cover them); the flank force taken "
                "proportional to torque beyond rated",
                force_N, band_m * 1e3, radius_m * 1e3, form.form_factor, form.stress_correction, factors.rim_thickness,
                sigma / 1e6, allowable / 1e6, below);
  out.method = buf;
  return out;
}

std::vector<double> ball_loads_N(const BodyStations& stations, const std::vector<double>& station_force_N, int balls) {
  constexpr double kTwoPi = 2 * std::numbers::pi;
  // The line load over the whole circle: each pair's first station and its partner half a turn on, by angle, each
  // with its force over the stations' spacing; linear in between (the hats sum to one), periodic.
  std::vector<std::pair<double, double>> at;  // (angle in [0, 2π), force per unit angle)
  for (std::size_t j = 0; j < stations.angle_rad.size(); ++j)
    for (const double turn : {0.0, std::numbers::pi})
      at.emplace_back(std::fmod(std::fmod(stations.angle_rad[j] + turn, kTwoPi) + kTwoPi, kTwoPi),
                      station_force_N[j] / stations.half_width_rad);
  std::sort(at.begin(), at.end());
  at.emplace_back(at.front().first + kTwoPi, at.front().second);  // close the period
  at.insert(at.begin(), {at[at.size() - 2].first - kTwoPi, at[at.size() - 2].second});
  // ∫ q over [a, b] (a ≤ b, within one period of the list's range), exactly: trapezoids of the linear pieces.
  const auto q_at = [&](double t) {
    // The piece holding t; at the period's closing point (t = 2π with a station at 0) the last one, not past the end.
    const auto hi = std::clamp(
        std::upper_bound(at.begin(), at.end(), std::make_pair(t, std::numeric_limits<double>::infinity())),
        at.begin() + 1, at.end() - 1);
    const auto lo = hi - 1;
    return lo->second + (hi->second - lo->second) * (t - lo->first) / (hi->first - lo->first);
  };
  const auto integral = [&](double a, double b) {
    double sum = 0, t = a, qt = q_at(a);
    for (const auto& [angle, q] : at) {
      if (angle <= a) continue;
      if (angle >= b) break;
      sum += 0.5 * (qt + q) * (angle - t);
      t = angle;
      qt = q;
    }
    return sum + 0.5 * (qt + q_at(b)) * (b - t);
  };
  // Each ball carries the line load of its own arc, ±π/Z about it: the ring between the balls is not rigid, and what
  // presses on it goes to the nearest ball (the balls together carry exactly the stations' force).
  std::vector<double> Q(static_cast<std::size_t>(balls));
  for (int b = 0; b < balls; ++b) {
    const double psi = kTwoPi * b / balls, half = kTwoPi / balls / 2;
    const double lo = psi - half, hi = psi + half;
    const double load = lo < 0 ? integral(lo + kTwoPi, kTwoPi) + integral(0, hi) : integral(lo, hi);
    Q[static_cast<std::size_t>(b)] = std::max(0.0, load);
  }
  return Q;
}

std::size_t step_nearest(const ContactAnalysis& contact, double torque_Nm) {
  std::size_t best = 0;
  for (std::size_t i = 0; i < contact.steps.size(); ++i)
    if (std::abs(contact.steps[i].torque_Nm - torque_Nm) <= std::abs(contact.steps[best].torque_Nm - torque_Nm))
      best = i;
  return best;
}

BearingLifeFigure generator_bearing_life(const GeneratorBearing& bearing, const BodyStations& stations,
                                         const ContactAnalysis& contact, double ratio, double input_speed_rpm) {
  if (!stations.unilateral || stations.angle_rad.empty() || contact.steps.back().station_force_N.empty())
    throw InputError("the generator bearing's life needs its ball loads: a cam or rollers in contact with the bore "
                     "(wave_generator.model = \"cam\" or \"rollers\")");
  const double signed_ratio = -ratio;  // circular spline fixed: the flexspline turns against the input
  const auto hours = [&](const TorqueStep& s) {
    return generator_bearing_l10_hours(bearing, ball_loads_N(stations, s.station_force_N, bearing.balls),
                                       input_speed_rpm, signed_ratio);
  };
  const TorqueStep& rated = contact.steps.back();
  const TorqueStep* half = &contact.steps[step_nearest(contact, rated.torque_Nm / 2)];
  BearingLifeFigure out;
  out.input_speed_rpm = input_speed_rpm;
  out.l10_h = hours(rated);
  out.life_exponent = std::log(hours(*half) / out.l10_h) / std::log(rated.torque_Nm / half->torque_Nm);
  const std::vector<double> Q = ball_loads_N(stations, rated.station_force_N, bearing.balls);
  const double total = std::accumulate(Q.begin(), Q.end(), 0.0);
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "ISO 281 / Lundberg–Palmgren raceway ratings (C_r %.0f N) with the ball loads of the loaded contact at "
                "rated torque (the generator's preload and the mesh forces: largest %.0f N, sum %.0f N over %d balls), "
                "the load zone turning with the cam; at %.0f rpm input, no life modification factor (a_ISO = 1)",
                basic_dynamic_load_rating_N(bearing), *std::max_element(Q.begin(), Q.end()), total, bearing.balls,
                input_speed_rpm);
  out.method = buf;
  return out;
}

}  // namespace sw
