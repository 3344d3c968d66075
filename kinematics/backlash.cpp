#include "kinematics/backlash.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <tuple>

#include "common/constants.hpp"
#include "common/error.hpp"

namespace sw {

namespace {

constexpr int kSamples = 8;  // intervals of the coarse scan along the flexspline flank before Brent refines

Eigen::Matrix2d rot(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

const Eigen::Matrix2d kMirror = (Eigen::Matrix2d() << 1, 0, 0, -1).finished();

double wrap_pi(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}

/// Brent's minimisation of f on [a, b] (golden section + parabolic steps), to |Δx| ≤ tol.
template <class F>
double brent_minimize(F&& f, double a, double b, double tol) {
  constexpr double kGold = 0.3819660112501051;
  double x = a + kGold * (b - a), w = x, v = x, fx = f(x), fw = fx, fv = fx, d = 0, e = 0;
  for (int it = 0; it < 200; ++it) {
    const double m = 0.5 * (a + b), tol1 = tol + 1e-15 * std::abs(x), tol2 = 2 * tol1;
    if (std::abs(x - m) <= tol2 - 0.5 * (b - a)) break;
    bool golden = true;
    if (std::abs(e) > tol1) {
      const double r = (x - w) * (fx - fv), q0 = (x - v) * (fx - fw);
      double p = (x - v) * q0 - (x - w) * r, q = 2 * (q0 - r);
      if (q > 0) p = -p;
      q = std::abs(q);
      if (std::abs(p) < std::abs(0.5 * q * e) && p > q * (a - x) && p < q * (b - x)) {
        e = d;
        d = p / q;
        const double u = x + d;
        if (u - a < tol2 || b - u < tol2) d = x < m ? tol1 : -tol1;
        golden = false;
      }
    }
    if (golden) {
      e = (x < m ? b : a) - x;
      d = kGold * e;
    }
    const double u = std::abs(d) >= tol1 ? x + d : x + (d > 0 ? tol1 : -tol1);
    const double fu = f(u);
    if (fu <= fx) {
      (u < x ? b : a) = x;
      v = w; fv = fw; w = x; fw = fx; x = u; fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w; fv = fw; w = u; fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u; fv = fu;
      }
    }
  }
  return x;
}

/// Signed distance of p (circular-spline space frame, ccw side) from the outline of the circular-spline tooth beyond
/// the ccw side: its flank (extended past the form radius as the root fillet's stand-in), its tip corner and its tip
/// land (radius r_ac, from the corner to the tooth's middle at π/z_c). Positive inside the tooth. `grad` is the unit
/// gradient of the signed distance (the direction in which p must move to go deeper).
struct OutlineDistance {
  double d = 0;
  Eigen::Vector2d foot{0, 0}, grad{0, 0};
  ToothPart part = ToothPart::Flank;
};

/// Whether direction v (from a rounding's centre) lies within the arc's angle, between its flank and land ends.
bool within_arc(const TipRounding& k, const Eigen::Vector2d& v) {
  const Eigen::Vector2d a = k.flank_point - k.centre, b = k.land_point - k.centre;
  auto cross = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y) { return x.x() * y.y() - x.y() * y.x(); };
  const double s = cross(a, b) > 0 ? 1.0 : -1.0;
  return s * cross(a, v) >= 0 && s * cross(v, b) >= 0;
}

/// With the tip corner rounded (m.round_c) the outline is the flank up to the arc, the arc, the tip land beyond it: the
/// rounded tooth is the sharp one less the cap between the arc and the corner. A sharp corner is the arc of radius 0
/// (centre and both ends on the corner).
OutlineDistance cs_distance(const BacklashModel& m, const Eigen::Vector2d& p) {
  const Involute& c = m.flank_c;
  const TipRounding& k = m.round_c;
  const double r_tip = m.radii.tip_c;
  const double R = p.norm(), arg = std::atan2(p.y(), p.x());
  const InvoluteDistance id = involute_signed_distance(c, p);
  const double tooth_middle = kPi / m.gear.teeth_circular, land_from = std::atan2(k.centre.y(), k.centre.x());
  const Eigen::Vector2d v = p - k.centre;
  const bool on_arc = k.radius_m > 0 && within_arc(k, v) && v.norm() > 0;
  const bool inside = R > r_tip && id.distance_m > 0 && arg < tooth_middle + 1e-12 && !(on_arc && v.norm() > k.radius_m);
  OutlineDistance best;
  double dist = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector2d& end : {k.flank_point, k.land_point})
    if ((p - end).norm() < dist) {
      dist = (p - end).norm();
      best.foot = end;
      best.part = ToothPart::TipCorner;
    }
  if (id.foot_roll >= k.flank_roll && std::abs(id.distance_m) <= dist) {
    dist = std::abs(id.distance_m);
    best.foot = involute_point(c, id.foot_roll);
    best.part = ToothPart::Flank;
  }
  if (arg >= land_from && arg <= tooth_middle + 1e-12 && std::abs(R - r_tip) < dist) {
    dist = std::abs(R - r_tip);
    best.foot = p * (r_tip / R);
    best.part = ToothPart::TipLand;
  }
  bool arc = false;
  if (on_arc && std::abs(v.norm() - k.radius_m) < dist) {
    dist = std::abs(v.norm() - k.radius_m);
    best.foot = k.centre + k.radius_m * v / v.norm();
    best.part = ToothPart::TipCorner;
    arc = true;
  }
  best.d = inside ? dist : -dist;
  // Gradient of the signed distance: into the material across the nearest part.
  if (best.part == ToothPart::Flank) {
    const double th = c.epsilon - id.foot_roll;
    best.grad = Eigen::Vector2d(-std::sin(th), std::cos(th));
  } else if (best.part == ToothPart::TipLand) {
    best.grad = p / R;
  } else if (arc) {
    best.grad = -v / v.norm();  // towards the arc's centre: deeper
  } else {
    const Eigen::Vector2d dc = p - best.foot;
    best.grad = dc.norm() > 0 ? Eigen::Vector2d((inside ? 1.0 : -1.0) * dc / dc.norm()) : Eigen::Vector2d(p / R);
  }
  return best;
}

/// A rounding's arc as a function of s ∈ [0, 1], from its flank end to its land end.
Eigen::Vector2d arc_point(const TipRounding& k, double s) {
  const Eigen::Vector2d a = k.flank_point - k.centre, b = k.land_point - k.centre;
  const double a0 = std::atan2(a.y(), a.x()), sweep = wrap_pi(std::atan2(b.y(), b.x()) - a0), th = a0 + s * sweep;
  return k.centre + k.radius_m * Eigen::Vector2d(std::cos(th), std::sin(th));
}

/// The flexspline tooth's ccw side in its own frame: flank u ∈ [u_min, u_max], then the tip land from the ccw tip
/// corner (angle θ_t) to the tooth's middle, as one parameter t ∈ [0, 2]: t ≤ 1 on the flank, t > 1 on the land.
/// With the tip corner rounded (m.round_f) the side runs t ∈ [0, 3]: the flank to the arc (t ≤ 1), the arc (t ≤ 2),
/// the tip land from the arc to the tooth's middle.
Eigen::Vector2d flexspline_side_point(const BacklashModel& m, double t) {
  const Involute& f = m.flank_f;
  if (const TipRounding& k = m.round_f; k.radius_m > 0) {
    if (t <= 1.0) return involute_point(f, f.u_min + t * (k.flank_roll - f.u_min));
    if (t <= 2.0) return arc_point(k, t - 1.0);
    const double a = std::atan2(k.centre.y(), k.centre.x()) * (3.0 - t);
    return m.radii.tip_f * Eigen::Vector2d(std::cos(a), std::sin(a));
  }
  if (t <= 1.0) return involute_point(f, f.u_min + t * (f.u_max - f.u_min));
  const Eigen::Vector2d corner = involute_point(f, f.u_max);
  const double a = std::atan2(corner.y(), corner.x()) * (2.0 - t);
  return m.radii.tip_f * Eigen::Vector2d(std::cos(a), std::sin(a));
}

ToothPart flexspline_part(const BacklashModel& m, double t) {
  const double corner_end = m.round_f.radius_m > 0 ? 2.0 : 1.0;
  return t < 1.0 - 1e-9 ? ToothPart::Flank : t <= corner_end + 1e-9 ? ToothPart::TipCorner : ToothPart::TipLand;
}

/// Depth of point q (flexspline tooth frame) inside the flexspline tooth's ccw half (0 when outside), with the
/// nearest point of the tooth's outline.
struct Penetration {
  double depth = 0;
  Eigen::Vector2d foot{0, 0};
  ToothPart part = ToothPart::Flank;
};

Penetration flexspline_penetration(const BacklashModel& m, const Eigen::Vector2d& q) {
  const Involute& f = m.flank_f;
  const TipRounding& k = m.round_f;  // a sharp corner: the arc of radius 0
  const double R = q.norm();
  if (R >= m.radii.tip_f || R <= m.radii.form_f) return {};
  const InvoluteDistance id = involute_signed_distance(f, q);
  if (id.distance_m >= 0) return {};
  // The rounded tooth: the sharp one less the cap between the arc and the corner.
  const Eigen::Vector2d v = q - k.centre;
  const bool on_arc = k.radius_m > 0 && within_arc(k, v) && v.norm() > 0;
  if (on_arc && v.norm() > k.radius_m) return {};
  Penetration p{std::numeric_limits<double>::infinity(), k.flank_point, ToothPart::TipCorner};
  for (const Eigen::Vector2d& end : {k.flank_point, k.land_point})
    if ((q - end).norm() < p.depth) p = {(q - end).norm(), end, ToothPart::TipCorner};
  if (id.foot_roll <= k.flank_roll && -id.distance_m < p.depth)
    p = {-id.distance_m, involute_point(f, id.foot_roll), ToothPart::Flank};
  if (std::atan2(q.y(), q.x()) <= std::atan2(k.centre.y(), k.centre.x()) && m.radii.tip_f - R < p.depth)
    p = {m.radii.tip_f - R, q * (m.radii.tip_f / R), ToothPart::TipLand};
  if (on_arc && k.radius_m - v.norm() < p.depth)
    p = {k.radius_m - v.norm(), Eigen::Vector2d(k.centre + k.radius_m * v / v.norm()), ToothPart::TipCorner};
  return p;
}

/// Closest approach of the flexspline tooth's ccw side (tooth 0 mapped by q ↦ A q + b into the space frame, already
/// mirrored for the cw side) to the circular-spline tooth beyond the space's ccw side. `back` maps space-frame points
/// to frame W. Without overlap: the minimum distance between the two outlines (flank, tip corner, tip land of each).
/// With overlap: the larger of the two penetration depths (flexspline outline into the circular spline, the
/// circular spline's tip corner into the flexspline tooth), i.e. the depth to separate them.
FlankClearance flank_clearance(const BacklashModel& m, const Eigen::Matrix2d& A, const Eigen::Vector2d& b,
                               const Eigen::Matrix2d& back) {
  auto local = [&](double t) -> Eigen::Vector2d { return A * flexspline_side_point(m, t) + b; };
  auto g = [&](double t) { return -cs_distance(m, local(t)).d; };
  double best_t = 0, best = std::numeric_limits<double>::infinity();
  // Coarse scan of the flank (kSamples intervals) and the tip land (kSamples / 2), then Brent around the best sample
  // on its own part (the corner t = 1 is a sample of both).
  // A rounded tip corner is a part of its own (t ∈ (1, 2], as many samples as the land); the outline is smooth
  // across its ends, so one Brent bracket spans the best sample's neighbours.
  const bool rounded = m.round_f.radius_m > 0;
  std::vector<double> ts;
  for (int i = 0; i <= kSamples; ++i) ts.push_back(static_cast<double>(i) / kSamples);
  for (int i = 1; i <= kSamples / 2; ++i) ts.push_back(1.0 + 2.0 * i / kSamples);
  if (rounded)
    for (int i = 1; i <= kSamples / 2; ++i) ts.push_back(2.0 + 2.0 * i / kSamples);
  size_t best_i = 0;
  for (size_t i = 0; i < ts.size(); ++i) {
    const double gi = g(ts[i]);
    if (gi < best) { best = gi; best_t = ts[i]; best_i = i; }
  }
  auto refine = [&](double lo, double hi) {
    const double t = brent_minimize(g, lo, hi, 1e-13);
    for (double u : {t, lo, hi}) {
      const double gu = g(u);
      if (gu < best) { best = gu; best_t = u; }
    }
  };
  const size_t last_flank = kSamples;
  if (rounded) {
    refine(ts[best_i > 0 ? best_i - 1 : 0], ts[std::min(best_i + 1, ts.size() - 1)]);
  } else {
    if (best_i <= last_flank) refine(ts[best_i > 0 ? best_i - 1 : 0], ts[std::min(best_i + 1, last_flank)]);
    if (best_i >= last_flank) refine(ts[best_i > last_flank ? best_i - 1 : last_flank], ts[std::min(best_i + 1, ts.size() - 1)]);
  }
  const Eigen::Vector2d pl = local(best_t);
  const OutlineDistance cd = cs_distance(m, pl);
  FlankClearance r;
  r.clearance_m = -cd.d;
  r.roll_f = best_t <= 1.0 ? m.flank_f.u_min + best_t * (m.round_f.flank_roll - m.flank_f.u_min) : m.round_f.flank_roll;
  r.point_f = back * pl;
  r.point_c = back * cd.foot;
  r.normal = back * cd.grad;
  r.part_f = flexspline_part(m, best_t);
  r.part_c = cd.part;
  // The circular spline's tip corner inside the flexspline tooth (a corner cutting into a flank or tip land); a
  // rounded one at the arc's deepest point (a scan of the arc, then Brent).
  Eigen::Vector2d corner_c = m.round_c.centre;  // the sharp corner (a rounding of radius 0)
  Penetration pen;
  if (const TipRounding& k = m.round_c; k.radius_m == 0) {
    pen = flexspline_penetration(m, A.transpose() * (corner_c - b));
  } else {
    auto depth = [&](double s) { return -flexspline_penetration(m, A.transpose() * (arc_point(k, s) - b)).depth; };
    constexpr int kArc = 16;
    int best_s = 0;
    double deepest = 0;
    for (int i = 0; i <= kArc; ++i)
      if (const double d = depth(static_cast<double>(i) / kArc); d < deepest) { deepest = d; best_s = i; }
    if (deepest < 0) {
      const double s = brent_minimize(depth, std::max(best_s - 1, 0) / double(kArc), std::min(best_s + 1, kArc) / double(kArc), 1e-13);
      const double at = depth(s) <= deepest ? s : static_cast<double>(best_s) / kArc;
      corner_c = arc_point(k, at);
      pen = flexspline_penetration(m, A.transpose() * (corner_c - b));
    }
  }
  if (pen.depth > 0 && pen.depth > -r.clearance_m) {
    const Eigen::Vector2d foot = A * pen.foot + b;
    r.clearance_m = -pen.depth;
    r.point_f = back * foot;
    r.point_c = back * corner_c;
    r.normal = back * ((foot - corner_c) / (foot - corner_c).norm());
    r.part_f = pen.part;
    r.part_c = ToothPart::TipCorner;
  }
  r.lever_arm_m = r.point_f.x() * r.normal.y() - r.point_f.y() * r.normal.x();
  return r;
}

}  // namespace

BacklashModel make_backlash_model(const GearParams& gear, NeutralCurve curve) {
  BacklashModel m;
  m.gear = gear;
  m.radii = gear_radii(gear);
  m.flank_f = flexspline_flank(gear);
  m.flank_c = circular_space_flank(gear);
  m.round_f = flexspline_tip_rounding(gear);
  m.round_c = circular_tip_rounding(gear);
  if (!(curve.mean_radius_m > 0 && curve.mean_radius_m < m.radii.root_f)) {
    throw InputError("flexspline: rim neutral radius r_m = " + std::to_string(curve.mean_radius_m * 1e3) +
                     " mm must lie inside the tooth root circle r = " + std::to_string(m.radii.root_f * 1e3) +
                     " mm; check inner_radius_mm and rim_thickness_mm against [gear]");
  }
  m.curve = std::move(curve);
  return m;
}

double tooth_material_angle(const GearParams& gear, int k, double wg_angle_rad) {
  return wrap_pi(2.0 * kPi * k / gear.teeth_flexspline -
                 wg_angle_rad * static_cast<double>(gear.teeth_circular) / gear.teeth_flexspline);
}

ToothPlacement place_tooth(const NeutralCurve& curve, double phi, double phi0) {
  const double rm = curve.mean_radius_m;
  const double w = curve.w.value(phi), v = curve.v.value(phi);
  const double dw = curve.w.derivative(phi), dv = curve.v.derivative(phi);
  const Eigen::Vector2d e(std::cos(phi), std::sin(phi)), e1(-std::sin(phi), std::cos(phi));
  ToothPlacement t;
  t.angle_rad = phi + phi0 + std::atan2(v - dw, rm + w + dv);
  t.offset_m = rot(phi0) * ((rm + w) * e + v * e1) - rot(t.angle_rad) * Eigen::Vector2d(rm, 0.0);
  return t;
}

namespace {

/// The circular-spline space a placed tooth meets: the one whose centre σ = φ·z_f/z_c + j·2π/z_c is nearest to the
/// tooth centre line's polar angle. Returns (σ, j).
std::pair<double, int> facing_space(const BacklashModel& m, double phi, const ToothPlacement& tooth) {
  const double zf = m.gear.teeth_flexspline, zc = m.gear.teeth_circular, pitch_c = 2.0 * kPi / zc;
  const double base = phi * zf / zc;
  const Eigen::Vector2d centre = rot(tooth.angle_rad) * Eigen::Vector2d(m.curve.mean_radius_m, 0.0) + tooth.offset_m;
  const int j = static_cast<int>(std::lround(wrap_pi(std::atan2(centre.y(), centre.x()) - base) / pitch_c));
  return {base + j * pitch_c, j};
}

/// One flank of a placed tooth against the space centred at σ.
FlankClearance one_flank(const BacklashModel& m, const ToothPlacement& tooth, double sigma, Flank flank) {
  // ccw: flexspline point q ↦ R_σᵀ (R_γ q + t);  cw: mirror the tooth and the space, q ↦ M R_σᵀ (R_γ M q + t).
  const Eigen::Matrix2d Rg = rot(tooth.angle_rad), Rs = rot(sigma), RsT = Rs.transpose();
  if (flank == Flank::Ccw) return flank_clearance(m, RsT * Rg, RsT * tooth.offset_m, Rs);
  return flank_clearance(m, kMirror * RsT * Rg * kMirror, kMirror * RsT * tooth.offset_m, Rs * kMirror);
}

}  // namespace

PairClearance tooth_clearance(const BacklashModel& m, const ToothPlacement& tooth, double sigma) {
  PairClearance p;
  const Eigen::Vector2d tip = rot(tooth.angle_rad) * Eigen::Vector2d(m.radii.tip_f, 0.0) + tooth.offset_m;
  p.depth_m = tip.norm() - m.radii.tip_c;
  p.engaged = p.depth_m > 0;
  p.tip_to_root_m = m.radii.root_c - tip.norm();
  p.ccw = one_flank(m, tooth, sigma, Flank::Ccw);
  p.cw = one_flank(m, tooth, sigma, Flank::Cw);
  return p;
}

const char* part_name(ToothPart part) {
  switch (part) {
    case ToothPart::Flank: return "flank";
    case ToothPart::TipCorner: return "tip corner";
    default: return "tip land";
  }
}

PairClearance pair_clearance(const BacklashModel& m, double phi, double phi0) {
  const ToothPlacement tooth = place_tooth(m.curve, phi, phi0);
  const auto [sigma, j] = facing_space(m, phi, tooth);
  PairClearance p = tooth_clearance(m, tooth, sigma);
  p.phi_rad = wrap_pi(phi);
  const double from_major = std::min(std::abs(p.phi_rad), kPi - std::abs(p.phi_rad));  // nearest end of the axis
  p.position_deg = 90.0 - from_major * 180.0 / kPi;
  p.space = j;
  return p;
}

ClosedFlank closed_flank(const BacklashModel& m, double phi, double phi0, Flank flank, double drawn_in_m) {
  // The space is chosen once, at the start: a closing turn (≪ the circular pitch) does not change which space the
  // tooth faces.
  const auto [sigma, j] = facing_space(m, phi, place_tooth(m.curve, phi, phi0));
  (void)j;
  const double sign = flank == Flank::Ccw ? 1.0 : -1.0;
  auto f = [&](double delta) {
    ToothPlacement t = place_tooth(m.curve, phi, phi0 + sign * delta);
    t.offset_m -= drawn_in_m * (rot(t.angle_rad) * Eigen::Vector2d(1.0, 0.0));  // along the tooth's centre line
    return one_flank(m, t, sigma, flank);
  };
  const FlankClearance c0 = f(0.0);
  const double j0 = c0.clearance_m;
  if (j0 == 0.0) return {0.0, c0};
  // Rate at which a turn closes the flank: sign·lever (the cw lever is negative); bounded below so that a flank whose
  // nearest parts are tip lands (radial normal) still brackets.
  const double rate = std::max(sign * c0.lever_arm_m, 0.2 * m.curve.mean_radius_m);
  // Bracket the root in the direction that moves the clearance towards zero, then Illinois regula falsi.
  const double dir = j0 > 0 ? 1.0 : -1.0;
  double a = 0.0, fa = j0, step = 1.2 * std::abs(j0) / rate, b = dir * step, fb = f(b).clearance_m;
  int expansions = 0;
  while (fb * fa > 0) {
    if (++expansions > 40 || std::abs(b) > 0.1)
      return {j0 > 0 ? std::numeric_limits<double>::infinity() : j0 / rate, c0};
    a = b;
    fa = fb;
    step *= 2.0;
    b += dir * step;
    fb = f(b).clearance_m;
  }
  int side = 0;
  for (int it = 0; it < 100 && std::abs(b - a) > 1e-13; ++it) {
    const double c = (a * fb - b * fa) / (fb - fa), fc = f(c).clearance_m;
    if (fc == 0.0) return {c, c0};
    if (fc * fb < 0) {
      a = b;
      fa = fb;
      side = 0;
    } else if (side == -1) {
      fa *= 0.5;
    }
    b = c;
    fb = fc;
    if (fc * fa > 0 && side != -1) side = -1;
  }
  return {std::abs(fa) < std::abs(fb) ? a : b, c0};
}

double closing_angle_rad(const BacklashModel& m, double phi, double phi0, Flank flank) {
  return closed_flank(m, phi, phi0, flank).turn_rad;
}

std::vector<PairClearance> pair_clearances(const BacklashModel& m, double wg, double phi0, bool engaged_only) {
  std::vector<PairClearance> out;
  const int zf = m.gear.teeth_flexspline;
  const double rm = m.curve.mean_radius_m;
  for (int k = 0; k < zf; ++k) {
    const double phi = tooth_material_angle(m.gear, k, wg);
    if (engaged_only) {  // cheap radial pre-check: tip radius ≈ ρ + (r_af − r_m) misses by < 1e-6 m in practice
      const double w = m.curve.w.value(phi);
      if (rm + w + (m.radii.tip_f - rm) < m.radii.tip_c - 5e-6) continue;
    }
    PairClearance p = pair_clearance(m, phi, phi0);
    if (engaged_only && !p.engaged) continue;
    p.pair = k;
    out.push_back(p);
  }
  return out;
}

double min_backlash_m(const BacklashModel& m, double wg, double phi0) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& p : pair_clearances(m, wg, phi0, true)) best = std::min(best, p.backlash_m());
  return best;
}

MeshState mesh_state(const BacklashModel& m, double wg, double phi0) {
  MeshState st;
  st.wg_angle_rad = wg;
  st.min_backlash_m = std::numeric_limits<double>::infinity();
  st.closing_ccw_rad = st.closing_cw_rad = std::numeric_limits<double>::infinity();
  const auto pairs = pair_clearances(m, wg, phi0, true);
  st.engaged_pairs = static_cast<int>(pairs.size());
  // First-order closing angles j/lever pick the candidates; the few nearest the smallest are solved exactly.
  const double min_lever = 0.2 * m.curve.mean_radius_m;
  std::vector<std::pair<double, const PairClearance*>> ccw, cw;
  for (const auto& p : pairs) {
    st.min_backlash_m = std::min(st.min_backlash_m, p.backlash_m());
    for (int i = 0; i < 3; ++i) {
      st.near_ccw[i] += p.ccw.clearance_m < kNearContact_m[i];
      st.near_cw[i] += p.cw.clearance_m < kNearContact_m[i];
    }
    if (p.ccw.lever_arm_m > min_lever) ccw.emplace_back(p.ccw.clearance_m / p.ccw.lever_arm_m, &p);
    if (-p.cw.lever_arm_m > min_lever) cw.emplace_back(p.cw.clearance_m / -p.cw.lever_arm_m, &p);
  }
  auto solve = [&](std::vector<std::pair<double, const PairClearance*>>& list, Flank flank, double& angle, int& pair) {
    if (list.empty()) return;
    std::sort(list.begin(), list.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    const double cut = list.front().first + std::max(0.2 * std::abs(list.front().first), 2e-6);
    for (const auto& [first_order, p] : list) {
      if (first_order > cut) break;
      const double exact = closing_angle_rad(m, p->phi_rad, phi0, flank);
      if (exact < angle) { angle = exact; pair = p->pair; }
    }
  };
  solve(ccw, Flank::Ccw, st.closing_ccw_rad, st.pair_ccw);
  solve(cw, Flank::Cw, st.closing_cw_rad, st.pair_cw);
  return st;
}

RevolutionSweep sweep_revolution(const BacklashModel& m, double phi0, int steps) {
  // The tooth set repeats every circular-spline pitch of the generator: φ_k(ψ + 2π/z_c) = φ_{k−1}(ψ). Steps whose
  // generator angles agree modulo 2π/z_c (to 1e-12 rad) therefore have identical pair sets; each is solved once.
  RevolutionSweep s;
  steps = std::max(steps, 1);
  s.min_m = s.angular_play_min_rad = std::numeric_limits<double>::infinity();
  s.max_m = s.angular_play_max_rad = -std::numeric_limits<double>::infinity();
  s.engaged_pairs_min = std::numeric_limits<int>::max();
  const double period = 2.0 * kPi / m.gear.teeth_circular;
  std::map<long long, MeshState> solved;  // residue in 1e-12 rad -> state
  for (int i = 0; i < steps; ++i) {
    const double wg = 2.0 * kPi * i / steps;
    double residue = std::fmod(wg, period);
    if (period - residue < 1e-12) residue = 0.0;
    const long long key = std::llround(residue * 1e12);
    auto it = solved.find(key);
    if (it == solved.end()) it = solved.emplace(key, mesh_state(m, residue, phi0)).first;
    const MeshState& st = it->second;
    s.wg_angle_rad.push_back(wg);
    s.min_backlash_m.push_back(st.min_backlash_m);
    if (st.min_backlash_m < s.min_m) { s.min_m = st.min_backlash_m; s.min_at_rad = wg; }
    s.max_m = std::max(s.max_m, st.min_backlash_m);
    s.engaged_pairs_min = std::min(s.engaged_pairs_min, st.engaged_pairs);
    s.engaged_pairs_max = std::max(s.engaged_pairs_max, st.engaged_pairs);
    s.angular_play_min_rad = std::min(s.angular_play_min_rad, st.angular_play_rad());
    s.angular_play_max_rad = std::max(s.angular_play_max_rad, st.angular_play_rad());
  }
  s.distinct_positions = static_cast<int>(solved.size());
  for (const auto& [key, st] : solved) s.period.push_back(st);
  return s;
}

namespace {

/// Smallest clearance (and the pair) over engaged pairs at material angles φ on a grid over [from, to] (rad),
/// refined by Brent around the worst sample; tip/root overlaps count as clearances too.
std::pair<double, PairClearance> worst_engaged(const BacklashModel& m, double from, double to, double step) {
  double worst = std::numeric_limits<double>::infinity();
  PairClearance at;
  double at_phi = 0;
  auto value = [&](const PairClearance& p) {
    return p.engaged ? std::min(p.backlash_m(), p.tip_to_root_m) : std::numeric_limits<double>::infinity();
  };
  const int n = static_cast<int>(std::ceil((to - from) / step));
  for (int i = 0; i <= n; ++i) {
    const double phi = from + (to - from) * i / n;
    const PairClearance p = pair_clearance(m, phi, 0.0);
    if (value(p) < worst) { worst = value(p); at = p; at_phi = phi; }
  }
  if (std::isfinite(worst)) {
    const double h = (to - from) / n;
    const double phi = brent_minimize([&](double x) { return std::min(value(pair_clearance(m, x, 0.0)), 1.0); },
                                      at_phi - h, at_phi + h, 1e-10);
    const PairClearance p = pair_clearance(m, phi, 0.0);
    if (value(p) < worst) { worst = value(p); at = p; }
  }
  return {worst, at};
}

NeutralCurve scaled(NeutralCurve c, double factor) {
  for (auto* series : {&c.w, &c.v, &c.mu}) {
    for (auto& x : series->a) x *= factor;
    for (auto& x : series->b) x *= factor;
  }
  return c;
}

}  // namespace

TightestPair tightest_pair_at_rest(const BacklashModel& m) {
  const double step = 0.25 * kPi / 180.0;
  const auto [clearance, pair] = worst_engaged(m, -kPi + step, kPi, step);
  return {clearance, pair};
}

GeometryCheck check_geometry(const GearParams& gear, const NeutralCurve& curve) {
  const BacklashModel m = make_backlash_model(gear, curve);
  GeometryCheck g;
  g.radii = m.radii;
  g.w_major_m = curve.w.value(0.0);
  g.w_minor_m = curve.w.value(0.5 * kPi);
  g.working_depth_m = m.radii.tip_f + g.w_major_m - m.radii.tip_c;
  g.two_w0_m = 2.0 * g.w_major_m;
  g.minor_axis_tip_clearance_m = m.radii.tip_c - (m.radii.tip_f + g.w_minor_m);
  g.major_axis_tip_root_m = m.radii.root_c - (m.radii.tip_f + g.w_major_m);
  g.major_axis_root_tip_m = m.radii.root_f + g.w_major_m - m.radii.tip_c;
  g.major_axis = pair_clearance(m, 0.0, 0.0);
  g.major_axis_play_rad = closing_angle_rad(m, 0.0, 0.0, Flank::Ccw) + closing_angle_rad(m, 0.0, 0.0, Flank::Cw);
  const TightestPair t = tightest_pair_at_rest(m);
  g.worst_clearance_m = t.clearance_m;
  g.worst = t.pair;
  const double step = 0.25 * kPi / 180.0;
  g.interference = g.worst_clearance_m < 0;
  if (!g.interference) return g;
  // Remedies, on one engagement zone (the generator's two lobes are alike) at 0.5° steps.
  auto free_of_interference = [&](const GearParams& gg, const NeutralCurve& cc) {
    try {
      return worst_engaged(make_backlash_model(gg, cc), -0.5 * kPi, 0.5 * kPi, 2.0 * step).first >= 0;
    } catch (const InputError&) {
      return false;  // proportions that cannot be cut
    }
  };
  auto with_addenda = [&](double s) {
    GearParams gg = gear;
    gg.addendum_coefficient_flexspline *= s;
    gg.addendum_coefficient_circular *= s;
    return gg;
  };
  if (free_of_interference(with_addenda(0.3), curve)) {
    double lo = 0.3, hi = 1.0;
    while (hi - lo > 1e-3) {
      const double mid = 0.5 * (lo + hi);
      (free_of_interference(with_addenda(mid), curve) ? lo : hi) = mid;
    }
    g.addendum_scale_free = lo;
    g.addendum_free_flexspline = lo * gear.addendum_coefficient_flexspline;
    g.addendum_free_circular = lo * gear.addendum_coefficient_circular;
  }
  for (int i = 0; i <= 50; ++i) {
    const double f = 0.5 + 0.02 * i;
    if (free_of_interference(gear, scaled(curve, f))) {
      if (g.w0_scale_free_lo == 0) g.w0_scale_free_lo = f;
      g.w0_scale_free_hi = f;
    }
  }
  return g;
}

std::vector<Interference> interferences(const PairClearance& p) {
  std::vector<Interference> out;
  auto where = [](const char* side, const FlankClearance& c) {
    return std::string(side) + " side: flexspline " + part_name(c.part_f) + " into circular-spline " + part_name(c.part_c);
  };
  if (p.ccw.clearance_m < 0) out.push_back({p.phi_rad, where("ccw", p.ccw), -p.ccw.clearance_m, p.ccw.point_f});
  if (p.cw.clearance_m < 0) out.push_back({p.phi_rad, where("cw", p.cw), -p.cw.clearance_m, p.cw.point_f});
  if (p.engaged && p.tip_to_root_m < 0) out.push_back({p.phi_rad, "tip/root", -p.tip_to_root_m, {0, 0}});
  return out;
}

}  // namespace sw
