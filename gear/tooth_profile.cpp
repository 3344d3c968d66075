#include "gear/tooth_profile.hpp"

#include <algorithm>
#include <numbers>
#include <sstream>

#include "common/constants.hpp"
#include "common/error.hpp"

namespace sw {

namespace {

[[noreturn]] void bad_gear(const std::string& what) { throw InputError("[gear]: " + what); }

double half_thickness_at_reference_f(const GearParams& g) {
  return kPi / (2.0 * g.teeth_flexspline) + 2.0 * g.profile_shift_flexspline * std::tan(g.pressure_angle_rad) / g.teeth_flexspline;
}

double half_space_at_reference_c(const GearParams& g) {
  return kPi / (2.0 * g.teeth_circular) + 2.0 * g.profile_shift_circular * std::tan(g.pressure_angle_rad) / g.teeth_circular;
}

}  // namespace

double inverse_involute(double inv_alpha) {
  // Start from the series alpha ≈ (3 inv)^(1/3) and polish with Newton on tan a − a − inv (derivative tan² a).
  double a = std::cbrt(3.0 * inv_alpha);
  for (int i = 0; i < 40; ++i) {
    const double t = std::tan(a);
    const double f = t - a - inv_alpha;
    const double step = f / std::max(t * t, 1e-300);
    a -= step;
    if (std::abs(step) < 1e-16) break;
  }
  return a;
}

double roll_at_radius(double base_radius_m, double radius_m) {
  const double q = radius_m / base_radius_m;
  return std::sqrt(std::max(q * q - 1.0, 0.0));
}

GearRadii gear_radii(const GearParams& g) {
  validate_gear(g);
  const double m = g.module_m, al = g.pressure_angle_rad;
  GearRadii r;
  // Flexspline.
  r.pitch_f = m * g.teeth_flexspline / 2.0;
  r.base_f = r.pitch_f * std::cos(al);
  const double z0 = g.cutter_teeth, x0 = 0.0;
  const double inv_w0 = involute_function(al) + 2.0 * std::tan(al) * (g.profile_shift_flexspline + x0) / (g.teeth_flexspline + z0);
  r.cutter_pressure_angle_rad = inverse_involute(inv_w0);
  r.cutter_centre_distance = m * (g.teeth_flexspline + z0) / 2.0 * std::cos(al) / std::cos(r.cutter_pressure_angle_rad);
  const double ra0 = m * (z0 / 2.0 + g.dedendum_coefficient_flexspline + x0);
  const double rb0 = m * z0 / 2.0 * std::cos(al);
  r.root_f = r.cutter_centre_distance - ra0;
  r.tip_f = r.pitch_f + m * (g.addendum_coefficient_flexspline + g.profile_shift_flexspline);
  const double gl = r.cutter_centre_distance * std::sin(r.cutter_pressure_angle_rad) - std::sqrt(ra0 * ra0 - rb0 * rb0);
  r.form_f = gl > 0 ? std::hypot(r.base_f, gl) : r.base_f;
  r.form_f = std::max(r.form_f, r.root_f);
  // Circular spline.
  r.pitch_c = m * g.teeth_circular / 2.0;
  r.base_c = r.pitch_c * std::cos(al);
  const double hac = g.addendum_coefficient_circular, hfc = g.dedendum_coefficient_circular;
  r.tip_c = r.pitch_c - m * (hac - g.profile_shift_circular);
  r.root_c = r.pitch_c + m * (hfc + g.profile_shift_circular);
  r.form_c = r.pitch_c + m * (std::min(hac, hfc) + g.profile_shift_circular);
  if (r.form_f >= r.tip_f) {
    std::ostringstream s;
    s << "profile_shift_flexspline = " << g.profile_shift_flexspline << ": the involute starts at r = " << r.form_f * 1e3
      << " mm, above the tip r = " << r.tip_f * 1e3 << " mm; reduce the shift or use more cutter_teeth";
    bad_gear(s.str());
  }
  if (r.tip_c <= r.base_c) {
    std::ostringstream s;
    s << "profile_shift_circular = " << g.profile_shift_circular << ": circular-spline tip r = " << r.tip_c * 1e3
      << " mm is inside its base circle r = " << r.base_c * 1e3 << " mm; increase the shift";
    bad_gear(s.str());
  }
  if (flexspline_tooth_thickness(g, r.tip_f) <= 0) {
    std::ostringstream s;
    s << "profile_shift_flexspline = " << g.profile_shift_flexspline << ": flexspline teeth are pointed below the tip"
      << " (r = " << r.tip_f * 1e3 << " mm); reduce the shift";
    bad_gear(s.str());
  }
  return r;
}

double flexspline_tooth_thickness(const GearParams& g, double radius_m) {
  const double rb = g.module_m * g.teeth_flexspline / 2.0 * std::cos(g.pressure_angle_rad);
  const double aR = std::acos(std::min(1.0, rb / radius_m));
  return 2.0 * radius_m * (half_thickness_at_reference_f(g) + involute_function(g.pressure_angle_rad) - involute_function(aR));
}

Involute flexspline_flank(const GearParams& g) {
  const GearRadii r = gear_radii(g);
  Involute f;
  f.base_radius = r.base_f;
  f.epsilon = half_thickness_at_reference_f(g) + involute_function(g.pressure_angle_rad);
  f.u_min = roll_at_radius(r.base_f, r.form_f);
  f.u_max = roll_at_radius(r.base_f, r.tip_f);
  return f;
}

Involute circular_space_flank(const GearParams& g) {
  const GearRadii r = gear_radii(g);
  Involute f;
  f.base_radius = r.base_c;
  f.epsilon = half_space_at_reference_c(g) + involute_function(g.pressure_angle_rad);
  f.u_min = roll_at_radius(r.base_c, r.tip_c);
  f.u_max = roll_at_radius(r.base_c, r.form_c);
  return f;
}

namespace {

/// The arc of radius ρ tangent to involute f and to the circle of radius r_tip, its centre on the material's side:
/// at radius r_tip − side·ρ and signed involute distance side·ρ (side = −1: the flexspline tooth, inside its ccw flank
/// and its tip circle; +1: the circular spline's tooth, beyond its space's ccw side and outside its tip circle).
/// Throws InputError naming `key` when the arc does not fit between the flank's end and the tooth's middle.
TipRounding tip_rounding(const Involute& f, double r_tip, double side, double rho,
                         double tooth_middle_rad, const char* key) {
  TipRounding k;
  k.radius_m = rho;
  if (rho == 0) {
    k.flank_roll = side < 0 ? f.u_max : f.u_min;
    k.centre = k.flank_point = k.land_point = involute_point(f, k.flank_roll);
    return k;
  }
  const double rc = r_tip + side * rho, rb = f.base_radius;
  const double ac = std::acos(std::min(1.0, rb / rc));
  const double arg = f.epsilon - involute_function(ac) + side * rho / rb;  // r_b (arg + inv α − ε) = side·ρ
  k.centre = rc * Eigen::Vector2d(std::cos(arg), std::sin(arg));
  k.flank_roll = f.epsilon - arg + ac;  // the normal through the centre meets the flank here
  k.flank_point = involute_point(f, k.flank_roll);
  k.land_point = r_tip * Eigen::Vector2d(std::cos(arg), std::sin(arg));
  const bool on_flank = rc > rb && k.flank_roll >= f.u_min && k.flank_roll <= f.u_max;
  const bool leaves_land = side < 0 ? arg > 0 : arg < tooth_middle_rad;
  if (!on_flank || !leaves_land) {
    std::ostringstream s;
    s << "gear." << key << " = " << rho * 1e3 << "; the rounding must end on the flank (above its form radius) and "
      << "leave part of the tip land: make it smaller";
    throw InputError(s.str());
  }
  return k;
}

}  // namespace

TipRounding flexspline_tip_rounding(const GearParams& g) {
  return tip_rounding(flexspline_flank(g), gear_radii(g).tip_f, -1.0, g.tip_rounding_flexspline_m, 0.0,
                      "tip_rounding_flexspline_mm");
}

TipRounding circular_tip_rounding(const GearParams& g) {
  return tip_rounding(circular_space_flank(g), gear_radii(g).tip_c, +1.0, g.tip_rounding_circular_m,
                      kPi / g.teeth_circular, "tip_rounding_circular_mm");
}

Eigen::Vector2d involute_point(const Involute& f, double u) {
  const double t = f.epsilon - u, c = std::cos(t), s = std::sin(t);
  return f.base_radius * Eigen::Vector2d(c - u * s, s + u * c);
}

Eigen::Vector2d involute_tangent(const Involute& f, double u) {
  const double t = f.epsilon - u;
  return f.base_radius * u * Eigen::Vector2d(std::cos(t), std::sin(t));
}

InvoluteDistance involute_signed_distance(const Involute& f, const Eigen::Vector2d& p) {
  const double R = p.norm();
  const double aR = std::acos(std::min(1.0, f.base_radius / R));
  const double arg = std::atan2(p.y(), p.x());
  return {f.base_radius * (arg + std::tan(aR) - aR - f.epsilon), f.epsilon - arg + aR};
}

namespace {

/// The flexspline tooth's outline rule in polar form: the involute's polar angle at a radius, and the root fillet (a
/// quarter ellipse from the form radius down to the root circle, `drop` deep and `dth` wide in angle).
struct OutlineRule {
  GearRadii r;
  Involute f;
  double half_pitch = 0, th_form = 0, th_tip = 0, drop = 0, dth = 0;
  double flank_angle(double rad) const {
    return f.epsilon - involute_function(std::acos(std::min(1.0, f.base_radius / rad)));
  }
  /// The fillet at parameter s in [0, π/2]: (radius, polar angle), from the form radius (s = 0) to the root circle.
  std::pair<double, double> fillet(double s) const {
    return {r.root_f + drop * (1.0 - std::sin(s)), th_form + dth * (1.0 - std::cos(s))};
  }
};

OutlineRule outline_rule(const GearParams& g) {
  OutlineRule o;
  o.r = gear_radii(g);
  o.f = flexspline_flank(g);
  o.half_pitch = kPi / g.teeth_flexspline;
  o.th_form = o.flank_angle(o.r.form_f);
  o.th_tip = o.flank_angle(o.r.tip_f);
  o.drop = o.r.form_f - o.r.root_f;
  const double gap = o.half_pitch - o.th_form;  // angular half-width of the gap at the form radius
  if (gap <= 0) bad_gear("flexspline teeth overlap at the form radius; reduce profile_shift_flexspline");
  o.dth = std::min(o.drop / o.r.root_f, 0.8 * gap);  // fillet's angular extent
  return o;
}

}  // namespace

double flexspline_solidity(const GearParams& g, double radius_m) {
  const OutlineRule o = outline_rule(g);
  if (radius_m <= o.r.root_f) return 1.0;
  if (radius_m > o.r.tip_f) return 0.0;
  double half_angle;
  if (radius_m >= o.r.form_f) {
    half_angle = o.flank_angle(radius_m);
  } else {  // on the fillet: radius = root + drop (1 − sin s)
    const double s = std::asin(std::clamp(1.0 - (radius_m - o.r.root_f) / o.drop, 0.0, 1.0));
    half_angle = o.fillet(s).second;
  }
  return std::clamp(half_angle / o.half_pitch, 0.0, 1.0);
}

std::vector<Eigen::Vector2d> flexspline_outline(const GearParams& g, int points_per_flank) {
  const int n = std::max(points_per_flank, 2);
  const OutlineRule o = outline_rule(g);
  const GearRadii& r = o.r;
  const int z = g.teeth_flexspline;
  const double half_pitch = o.half_pitch;
  auto polar = [](double rad, double ang) { return Eigen::Vector2d(rad * std::cos(ang), rad * std::sin(ang)); };
  auto flank_angle = [&](double rad) { return o.flank_angle(rad); };

  // Template of one pitch, tooth centred on angle 0, from the gap centre at −π/z (inclusive) to +π/z (exclusive),
  // as (radius, angle) pairs.
  std::vector<std::pair<double, double>> pitch;
  const double th_form = o.th_form, th_tip = o.th_tip, drop = o.drop, dth = o.dth;
  const int nr = std::max(1, n / 4), nf = std::max(2, n / 2), nt = std::max(1, n / 3);
  // Root arc (cw half), at the root radius from −π/z to the start of the cw fillet.
  const double root_start = -half_pitch, root_end = -(th_form + dth);
  for (int i = 0; i < nr; ++i) pitch.emplace_back(r.root_f, root_start + (root_end - root_start) * i / nr);
  // cw fillet: root to form (mirror of the ccw fillet, traversed in the opposite direction).
  auto fillet = [&](double s) { return o.fillet(s); };
  if (drop > 0) {
    for (int i = nf; i >= 1; --i) {
      auto [rad, ang] = fillet(0.5 * kPi * i / nf);
      pitch.emplace_back(rad, -ang);
    }
  }
  // cw flank: form to tip (equally spaced in radius), then the tip arc interior, then the ccw flank tip to form.
  for (int i = 0; i < n; ++i) {
    const double rad = r.form_f + (r.tip_f - r.form_f) * i / (n - 1);
    pitch.emplace_back(rad, -flank_angle(rad));
  }
  for (int i = 1; i <= nt; ++i) pitch.emplace_back(r.tip_f, -th_tip + 2.0 * th_tip * i / (nt + 1));
  for (int i = n - 1; i >= 0; --i) {
    const double rad = r.form_f + (r.tip_f - r.form_f) * i / (n - 1);
    pitch.emplace_back(rad, flank_angle(rad));
  }
  if (drop > 0) {
    for (int i = 1; i <= nf; ++i) pitch.push_back(fillet(0.5 * kPi * i / nf));
  }
  for (int i = 1; i < nr; ++i) pitch.emplace_back(r.root_f, -root_end + (half_pitch + root_end) * i / nr);

  std::vector<Eigen::Vector2d> out;
  out.reserve(static_cast<size_t>(z) * pitch.size());
  for (int k = 0; k < z; ++k) {
    const double off = 2.0 * kPi * k / z;
    for (const auto& [rad, ang] : pitch) out.push_back(polar(rad, ang + off));
  }
  return out;
}

}  // namespace sw
