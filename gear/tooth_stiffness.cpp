#include "gear/tooth_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include <Eigen/Geometry>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "gear/tooth_profile.hpp"

namespace sw {
namespace {

constexpr double kShearFactor = 1.2;  // Timoshenko's κ of a rectangular section (Yang & Lin 1987; Tian 2004)
constexpr int kSamples = 600;          // outline samples from root to contact: the integrals converge to < 1e-5

Eigen::Vector2d e_perp(double a) { return {-std::sin(a), std::cos(a)}; }
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// One tooth in its own frame: centre line = +x from the root section, half-thickness y(x) as a polyline, the contact
/// point P (on the +y flank) and the unit load direction there (into the tooth).
struct Cantilever {
  std::vector<double> x, y;   ///< outline samples from the root section (x[0]) up to the contact height
  double root_x = 0;          ///< x of the root circle on the centre line (u_f is measured from it)
  double root_half_angle = 0; ///< θ_f
  double root_radius = 0;     ///< r_f
  Eigen::Vector2d contact = Eigen::Vector2d::Zero();
  Eigen::Vector2d load = Eigen::Vector2d::Zero();  ///< unit vector
};

/// Half-angle of a tooth at radius R given the flank's polar angle law and a quarter-ellipse fillet of radial drop
/// `drop` and angular extent `dth` below the form radius (the rule of flexspline_outline).
struct FlankLaw {
  Involute flank;
  double form_radius = 0, root_radius = 0, dth = 0;
  bool internal = false;  ///< the involute bounds a space (circular spline): tooth half-angle = π/z − space angle
  double half_pitch = 0;
};

double involute_angle(const Involute& f, double radius) {
  return f.epsilon - involute_function(std::acos(std::min(1.0, f.base_radius / radius)));
}

/// Samples the tooth's flank from the root circle to radius `contact_radius` as (radius, tooth half-angle).
std::vector<std::pair<double, double>> flank_samples(const FlankLaw& l, double contact_radius) {
  std::vector<std::pair<double, double>> s;
  const double drop = std::abs(l.form_radius - l.root_radius);
  const double sgn = l.internal ? -1.0 : 1.0;  // external: radius grows from root to tip; internal: it shrinks
  auto tooth_angle = [&](double space_or_tooth) { return l.internal ? l.half_pitch - space_or_tooth : space_or_tooth; };
  const double form_angle = tooth_angle(involute_angle(l.flank, l.form_radius));
  const int nf = kSamples / 4, ni = kSamples - nf;
  if (drop > 0) {
    // Fillet, root (s = π/2) to form (s = 0): R = root + sgn·drop·(1 − sin s), angle = form + dth·(1 − cos s).
    for (int i = 0; i < nf; ++i) {
      const double t = 0.5 * kPi * (1.0 - double(i) / nf);
      s.emplace_back(l.root_radius + sgn * drop * (1.0 - std::sin(t)), form_angle + l.dth * (1.0 - std::cos(t)));
    }
  }
  for (int i = 0; i <= ni; ++i) {
    const double r = l.form_radius + (contact_radius - l.form_radius) * i / ni;
    s.emplace_back(r, tooth_angle(involute_angle(l.flank, r)));
  }
  return s;
}

/// Builds the cantilever: external teeth have x = R cos θ, internal teeth x = r_root − R cos θ (pointing inwards).
Cantilever make_cantilever(const FlankLaw& l, double contact_radius, const Eigen::Vector2d& load_in_gear_frame,
                           double tooth_centre_angle) {
  Cantilever c;
  const auto s = flank_samples(l, contact_radius);
  const double sx = l.internal ? -1.0 : 1.0, x0 = l.internal ? l.root_radius : 0.0;
  for (const auto& [r, a] : s) {
    c.x.push_back(x0 + sx * r * std::cos(a));
    c.y.push_back(r * std::sin(a));
  }
  c.root_x = x0 + sx * l.root_radius;
  c.root_half_angle = s.front().second;
  c.root_radius = l.root_radius;
  c.contact = {c.x.back(), c.y.back()};
  // Load into the tooth frame: rotate by −(tooth centre angle). The internal tooth's contact flank lies on its −y
  // side and its centre line points inwards: mirror both axes so that it reads like the external one.
  const Eigen::Vector2d f = Eigen::Rotation2Dd(-tooth_centre_angle).toRotationMatrix() * load_in_gear_frame;
  c.load = l.internal ? Eigen::Vector2d(-f.x(), -f.y()) : f;
  return c;
}

struct ToothCompliance {
  double beam = 0, foundation = 0;
};

/// Sainsot et al. (2004) table 1 polynomial X*(h_f, θ_f).
double sainsot(const double (&k)[6], double hf, double th) {
  return k[0] / (th * th) + k[1] * hf * hf + k[2] * hf / th + k[3] / th + k[4] * hf + k[5];
}

ToothCompliance cantilever_compliance(const Cantilever& c, const Material& m, double bore_ratio) {
  const double E = m.youngs_modulus_Pa, nu = m.poisson_ratio, Ep = E / (1 - nu * nu), G = m.shear_modulus_Pa();
  const Eigen::Vector2d f = c.load, P = c.contact, C(c.contact.x(), 0.0);
  // Virtual work, trapezoidal rule over the outline samples (sections x = const, perpendicular to the centre line).
  auto integrand = [&](double x, double y) {
    const Eigen::Vector2d X(x, 0.0);
    const double M = cross(P - X, f), Mv = cross(C - X, f);  // real (load at P) and virtual (unit load at C)
    const double V = f.y(), N = f.x();
    const double A = 2 * y, I = A * A * A / 12.0;
    return M * Mv / (Ep * I) + kShearFactor * V * V / (G * A) + N * N / (Ep * A);
  };
  ToothCompliance out;
  for (std::size_t i = 1; i < c.x.size(); ++i)
    out.beam += 0.5 * (integrand(c.x[i - 1], c.y[i - 1]) + integrand(c.x[i], c.y[i])) * (c.x[i] - c.x[i - 1]);

  // Foundation, Sainsot et al. (2004) eq. 3, table 1 (rows L*, M*, P*, Q*; columns A..F).
  static constexpr double kTable[4][6] = {{-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045},
                                          {60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086},
                                          {-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236},
                                          {-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904}};
  const double th = std::max(c.root_half_angle, FoundationFit::kMinRootHalfAngle_rad);
  const double hf = (bore_ratio > 1.0) ? std::min(bore_ratio, FoundationFit::kMaxBodyRatio) : FoundationFit::kMaxBodyRatio;
  const double L = sainsot(kTable[0], hf, th), Mm = sainsot(kTable[1], hf, th), Pp = sainsot(kTable[2], hf, th),
               Q = sainsot(kTable[3], hf, th);
  // u_f: from the root circle to where the line of action crosses the centre line (Sainsot et al. 2004, fig. 1).
  const double uf = (P.x() - P.y() * f.x() / f.y()) - c.root_x, Sf = 2 * c.root_radius * c.root_half_angle;
  const double cos_am = std::abs(f.y()), tan_am = std::abs(f.x()) / std::max(cos_am, 1e-12);
  const double ratio = uf / Sf;
  out.foundation = cos_am * cos_am / E * (L * ratio * ratio + Mm * ratio + Pp * (1 + Q * tan_am * tan_am));
  return out;
}

/// Distance from P along the line of direction f to the tooth's centre line (the x axis of the cantilever).
double distance_to_centre_line(const Cantilever& c) {
  return std::abs(c.contact.y() / c.load.y());
}

/// Weber & Banaschek (1953): secant contact compliance of the pair at line load w. The formula assumes h ≫ b and turns
/// negative for h ≲ 0.6 b (reached by the conformal internal contact of a strain wave gear's small teeth at tens of
/// N/mm); a body's term is then taken as zero, not negative.
double weber_banaschek(const Material& m, double w, double rho_rel, double h1, double h2) {
  const double E = m.youngs_modulus_Pa, nu = m.poisson_ratio;
  const double b = std::sqrt(8 * w * rho_rel * (1 - nu * nu) / (kPi * E));
  auto body = [&](double h) { return std::max(0.0, std::log(2 * h / b) - nu / (2 * (1 - nu))); };
  return 2 * (1 - nu * nu) / (kPi * E) * (body(h1) + body(h2));
}

void check_load(double w) {
  if (!(w > 0)) {
    std::ostringstream s;
    s << "tooth pair: line load = " << w << " N/m; must be > 0";
    throw InputError(s.str());
  }
}

void check_radius(double r, double lo, double hi, const char* what) {
  if (!(r >= lo * (1 - 1e-12) && r <= hi * (1 + 1e-12))) {
    std::ostringstream s;
    s.precision(6);
    s << "tooth pair: contact radius = " << r * 1e3 << " mm on the " << what << "; must lie on its active flank ["
      << lo * 1e3 << ", " << hi * 1e3 << "] mm (form to tip radius)";
    throw InputError(s.str());
  }
}

/// Flank law of the flexspline (external) tooth of g.
FlankLaw external_law(const GearParams& g) {
  const GearRadii r = gear_radii(g);
  FlankLaw l;
  l.flank = flexspline_flank(g);
  l.form_radius = r.form_f;
  l.root_radius = r.root_f;
  const double gap = kPi / g.teeth_flexspline - involute_angle(l.flank, r.form_f);
  l.dth = std::min((r.form_f - r.root_f) / r.root_f, 0.8 * gap);  // flexspline_outline's fillet rule
  return l;
}

}  // namespace

ToothPairCompliance tooth_pair_compliance(const GearParams& g, const Material& m, double contact_radius_f_m,
                                          double line_load_N_per_m, double rim_inner_radius_m,
                                          double contact_radius_c_m) {
  check_load(line_load_N_per_m);
  const GearRadii r = gear_radii(g);
  check_radius(contact_radius_f_m, r.form_f, r.tip_f, "flexspline");
  const FlankLaw lf = external_law(g);
  const double uf = roll_at_radius(lf.flank.base_radius, contact_radius_f_m);
  // Load on the flexspline's ccw flank: along the involute's normal, into the tooth (−e′(ε − u)).
  const Eigen::Vector2d load_f = -e_perp(lf.flank.epsilon - uf);
  const Cantilever cf = make_cantilever(lf, contact_radius_f_m, load_f, 0.0);

  // Circular spline: the tooth between space 0 and space 1, centred on π/z_c; its contact point is the conjugate one.
  FlankLaw lc;
  lc.flank = circular_space_flank(g);
  lc.internal = true;
  lc.half_pitch = kPi / g.teeth_circular;
  lc.form_radius = r.form_c;
  lc.root_radius = r.root_c;
  const double space_at_form = involute_angle(lc.flank, r.form_c);
  lc.dth = std::min((r.root_c - r.form_c) / r.root_c, 0.8 * space_at_form);
  const double al = g.pressure_angle_rad;
  const double inv_w = involute_function(al) + 2 * std::tan(al) * (g.profile_shift_circular - g.profile_shift_flexspline) /
                                                   (g.teeth_circular - g.teeth_flexspline);
  const double alw = inverse_involute(inv_w);
  const double aw = (r.base_c - r.base_f) / std::cos(alw);
  const double uc_raw = contact_radius_c_m > 0 ? roll_at_radius(r.base_c, contact_radius_c_m)
                                               : (aw * std::sin(alw) + r.base_f * uf) / r.base_c;
  const double uc = std::clamp(uc_raw, lc.flank.u_min, lc.flank.u_max);
  const double rc = r.base_c * std::sqrt(1 + uc * uc);
  // Reaction on the circular spline's tooth: along the same line of action, into its tooth (+e′(ε_c − u_c)).
  const Eigen::Vector2d load_c = e_perp(lc.flank.epsilon - uc);
  const Cantilever cc = make_cantilever(lc, rc, load_c, lc.half_pitch);

  const double bore = rim_inner_radius_m > 0 ? r.root_f / rim_inner_radius_m : 0.0;
  const ToothCompliance tf = cantilever_compliance(cf, m, bore);
  const ToothCompliance tc = cantilever_compliance(cc, m, 0.0);
  ToothPairCompliance out;
  out.bending_f = tf.beam;
  out.foundation_f = tf.foundation;
  out.bending_c = tc.beam;
  out.foundation_c = tc.foundation;
  const double rho_f = r.base_f * uf, rho_c = r.base_c * uc;  // involute radii of curvature (internal: concave)
  const double rho_rel = 1.0 / (1.0 / rho_f - 1.0 / rho_c);
  out.contact = weber_banaschek(m, line_load_N_per_m, rho_rel, distance_to_centre_line(cf), distance_to_centre_line(cc));
  return out;
}

GearParams spur_gear_as_external(const SpurPair& p, int which) {
  GearParams g;
  g.module_m = p.module_m;
  g.pressure_angle_rad = p.pressure_angle_rad;
  g.teeth_flexspline = which == 1 ? p.teeth_1 : p.teeth_2;
  g.profile_shift_flexspline = which == 1 ? p.profile_shift_1 : p.profile_shift_2;
  g.cutter_teeth = 2000;  // a shaper of 2000 teeth cuts the rack's involute and root circle to < 1e-3 m
  g.addendum_coefficient_flexspline = 1.0;
  g.dedendum_coefficient_flexspline = 1.25;
  // The circular-spline fields are unused; any set gear_radii accepts.
  g.teeth_circular = g.teeth_flexspline + 2;
  g.profile_shift_circular = 2.0;
  return g;
}

double spur_pitch_radius_1(const SpurPair& p) {
  const double al = p.pressure_angle_rad;
  const double inv_w = involute_function(al) + 2 * std::tan(al) * (p.profile_shift_1 + p.profile_shift_2) /
                                                   (p.teeth_1 + p.teeth_2);
  const double alw = inverse_involute(inv_w);
  return 0.5 * p.module_m * p.teeth_1 * std::cos(al) / std::cos(alw);
}

ToothPairCompliance spur_pair_compliance(const SpurPair& p, const Material& m, double contact_radius_1_m,
                                         double line_load_N_per_m) {
  check_load(line_load_N_per_m);
  const GearParams g1 = spur_gear_as_external(p, 1), g2 = spur_gear_as_external(p, 2);
  const GearRadii r1 = gear_radii(g1), r2 = gear_radii(g2);
  check_radius(contact_radius_1_m, r1.form_f, r1.tip_f, "gear 1");
  const FlankLaw l1 = external_law(g1), l2 = external_law(g2);
  const double al = p.pressure_angle_rad;
  const double inv_w = involute_function(al) + 2 * std::tan(al) * (p.profile_shift_1 + p.profile_shift_2) /
                                                   (p.teeth_1 + p.teeth_2);
  const double alw = inverse_involute(inv_w);
  const double aw = (r1.base_f + r2.base_f) / std::cos(alw);
  const double u1 = roll_at_radius(r1.base_f, contact_radius_1_m);
  const double u2_raw = (aw * std::sin(alw) - r1.base_f * u1) / r2.base_f;
  const double u2 = std::clamp(u2_raw, l2.flank.u_min, l2.flank.u_max);
  const double rad2 = r2.base_f * std::sqrt(1 + u2 * u2);
  const Cantilever c1 = make_cantilever(l1, contact_radius_1_m, -e_perp(l1.flank.epsilon - u1), 0.0);
  const Cantilever c2 = make_cantilever(l2, rad2, -e_perp(l2.flank.epsilon - u2), 0.0);
  const double bore = p.bore_ratio;
  const ToothCompliance t1 = cantilever_compliance(c1, m, bore), t2 = cantilever_compliance(c2, m, bore);
  ToothPairCompliance out;
  out.bending_f = t1.beam;
  out.foundation_f = t1.foundation;
  out.bending_c = t2.beam;
  out.foundation_c = t2.foundation;
  const double rho_rel = 1.0 / (1.0 / (r1.base_f * u1) + 1.0 / (r2.base_f * u2));
  out.contact = weber_banaschek(m, line_load_N_per_m, rho_rel, distance_to_centre_line(c1), distance_to_centre_line(c2));
  return out;
}

double iso6336_theoretical_single_stiffness(int zn1, int zn2, double x1, double x2) {
  constexpr double C1 = 0.04723, C2 = 0.15551, C3 = 0.25791, C4 = -0.00635, C5 = -0.11654, C6 = -0.00193,
                   C7 = -0.24188, C8 = 0.00529, C9 = 0.00182;
  const double q = C1 + C2 / zn1 + C3 / zn2 + C4 * x1 + C5 * x1 / zn1 + C6 * x2 + C7 * x2 / zn2 + C8 * x1 * x1 +
                   C9 * x2 * x2;
  return 1.0 / q;
}

}  // namespace sw
