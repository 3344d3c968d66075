#include "kinematics/backlash.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include "common/error.hpp"

namespace sw {

namespace {

constexpr double kPi = std::numbers::pi;
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

/// Signed distance of p (circular-spline space frame, ccw side) into the circular spline's material, with the
/// foot on the flank or, past the tip, on the tip corner. Returns distance, foot point and unit gradient.
struct CsDistance {
  double d;
  Eigen::Vector2d foot, grad;
};

CsDistance cs_distance(const Involute& c, double tip_radius, const Eigen::Vector2d& p) {
  double t = 0;
  const double s = involute_signed_distance(c, p, &t);
  if (t >= c.u_min) {  // foot on the flank (past the form radius: on its extension, the root fillet's stand-in)
    const double th = c.epsilon - t;
    return {s, involute_point(c, t), Eigen::Vector2d(-std::sin(th), std::cos(th))};
  }
  const Eigen::Vector2d corner = involute_point(c, c.u_min);
  const Eigen::Vector2d dc = p - corner;
  const double dist = dc.norm();
  const double R = p.norm();
  if (s > 0 && R > tip_radius) {  // inside the tooth, beyond its tip corner: nearest of tip land and flank
    if (R - tip_radius < dist) return {R - tip_radius, p * (tip_radius / R), p / R};
    return {dist, corner, dc / dist};
  }
  return {-dist, corner, dist > 0 ? Eigen::Vector2d(-dc / dist) : Eigen::Vector2d(0, 0)};
}

/// Closest approach of the flexspline flank (ccw flank of tooth 0 mapped by q ↦ A q + b into the space frame, already
/// mirrored for the cw side) to the space's flank. `back` maps space-frame points to frame W.
FlankClearance flank_clearance(const BacklashModel& m, const Eigen::Matrix2d& A, const Eigen::Vector2d& b,
                               const Eigen::Matrix2d& back) {
  const Involute& f = m.flank_f;
  auto local = [&](double u) -> Eigen::Vector2d { return A * involute_point(f, u) + b; };
  auto g = [&](double u) { return -cs_distance(m.flank_c, m.radii.tip_c, local(u)).d; };
  double best_u = f.u_min, best = std::numeric_limits<double>::infinity();
  int best_i = 0;
  const double du = (f.u_max - f.u_min) / kSamples;
  for (int i = 0; i <= kSamples; ++i) {
    const double u = f.u_min + du * i, gi = g(u);
    if (gi < best) { best = gi; best_u = u; best_i = i; }
  }
  const double lo = f.u_min + du * std::max(best_i - 1, 0), hi = f.u_min + du * std::min(best_i + 1, kSamples);
  const double ub = brent_minimize(g, lo, hi, 1e-12);
  for (double u : {ub, lo, hi}) {
    const double gu = g(u);
    if (gu < best) { best = gu; best_u = u; }
  }
  const Eigen::Vector2d pl = local(best_u);
  const CsDistance cd = cs_distance(m.flank_c, m.radii.tip_c, pl);
  FlankClearance r;
  r.clearance_m = -cd.d;
  r.roll_f = best_u;
  r.point_f = back * pl;
  r.point_c = back * cd.foot;
  r.normal = back * cd.grad;
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
  const NeutralPoint np = curve.at(phi);
  const double rho = rm + np.w_m;
  const double phi1 = phi + np.v_m / rm + phi0;
  ToothPlacement t;
  t.angle_rad = phi1 + np.mu_rad;
  t.offset_m = rho * Eigen::Vector2d(std::cos(phi1), std::sin(phi1)) - rot(t.angle_rad) * Eigen::Vector2d(rm, 0.0);
  return t;
}

PairClearance tooth_clearance(const BacklashModel& m, const ToothPlacement& tooth, double sigma) {
  const Eigen::Matrix2d Rg = rot(tooth.angle_rad);
  const Eigen::Vector2d& t = tooth.offset_m;
  const Eigen::Matrix2d Rs = rot(sigma), RsT = Rs.transpose();
  PairClearance p;
  const Eigen::Vector2d tip = Rg * Eigen::Vector2d(m.radii.tip_f, 0.0) + t;
  p.depth_m = tip.norm() - m.radii.tip_c;
  p.engaged = p.depth_m > 0;
  p.tip_to_root_m = m.radii.root_c - tip.norm();
  // ccw: flexspline point q ↦ R_σᵀ (R_γ q + t);  cw: mirror the tooth and the space, q ↦ M R_σᵀ (R_γ M q + t).
  p.ccw = flank_clearance(m, RsT * Rg, RsT * t, Rs);
  p.cw = flank_clearance(m, kMirror * RsT * Rg * kMirror, kMirror * RsT * t, Rs * kMirror);
  return p;
}

PairClearance pair_clearance(const BacklashModel& m, double phi, double phi0) {
  const ToothPlacement tooth = place_tooth(m.curve, phi, phi0);
  const double zf = m.gear.teeth_flexspline, zc = m.gear.teeth_circular, pitch_c = 2.0 * kPi / zc;
  const double base = phi * zf / zc;
  // Tooth centre line's polar angle: the tip centre's direction (= φ₁′ up to O(w·μ)).
  const Eigen::Vector2d centre = rot(tooth.angle_rad) * Eigen::Vector2d(m.curve.mean_radius_m, 0.0) + tooth.offset_m;
  const int j = static_cast<int>(std::lround(wrap_pi(std::atan2(centre.y(), centre.x()) - base) / pitch_c));
  PairClearance p = tooth_clearance(m, tooth, base + j * pitch_c);
  p.phi_rad = wrap_pi(phi);
  const double from_major = std::min(std::abs(p.phi_rad), kPi - std::abs(p.phi_rad));  // nearest end of the axis
  p.position_deg = 90.0 - from_major * 180.0 / kPi;
  p.space = j;
  return p;
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

RevolutionSweep sweep_revolution(const BacklashModel& m, double phi0, int steps) {
  // The tooth set repeats every circular-spline pitch of the generator: φ_k(ψ + 2π/z_c) = φ_{k−1}(ψ). Steps whose
  // generator angles agree modulo 2π/z_c (to 1e-12 rad) therefore have identical pair sets; each is solved once.
  RevolutionSweep s;
  steps = std::max(steps, 1);
  s.min_m = std::numeric_limits<double>::infinity();
  s.max_m = -std::numeric_limits<double>::infinity();
  s.engaged_pairs_min = std::numeric_limits<int>::max();
  const double period = 2.0 * kPi / m.gear.teeth_circular;
  std::map<long long, std::pair<double, int>> solved;  // residue in 1e-12 rad -> (min backlash, engaged pairs)
  for (int i = 0; i < steps; ++i) {
    const double wg = 2.0 * kPi * i / steps;
    double residue = std::fmod(wg, period);
    if (period - residue < 1e-12) residue = 0.0;
    const long long key = std::llround(residue * 1e12);
    auto it = solved.find(key);
    if (it == solved.end()) {
      const auto pairs = pair_clearances(m, residue, phi0, true);
      double best = std::numeric_limits<double>::infinity();
      for (const auto& p : pairs) best = std::min(best, p.backlash_m());
      it = solved.emplace(key, std::pair{best, static_cast<int>(pairs.size())}).first;
    }
    const auto [best, n] = it->second;
    s.wg_angle_rad.push_back(wg);
    s.min_backlash_m.push_back(best);
    if (best < s.min_m) { s.min_m = best; s.min_at_rad = wg; }
    s.max_m = std::max(s.max_m, best);
    s.engaged_pairs_min = std::min(s.engaged_pairs_min, n);
    s.engaged_pairs_max = std::max(s.engaged_pairs_max, n);
  }
  s.distinct_positions = static_cast<int>(solved.size());
  return s;
}

std::vector<Interference> interferences(const PairClearance& p) {
  std::vector<Interference> out;
  if (p.ccw.clearance_m < 0) out.push_back({p.phi_rad, "ccw flank", -p.ccw.clearance_m, p.ccw.point_f});
  if (p.cw.clearance_m < 0) out.push_back({p.phi_rad, "cw flank", -p.cw.clearance_m, p.cw.point_f});
  if (p.engaged && p.tip_to_root_m < 0) out.push_back({p.phi_rad, "tip/root", -p.tip_to_root_m, {0, 0}});
  return out;
}

}  // namespace sw
