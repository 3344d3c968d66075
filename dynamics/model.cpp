#include "dynamics/model.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <sstream>

#include "common/constants.hpp"
#include "common/error.hpp"

namespace sw {
namespace {

double ring_inertia(double density, double width, double r1, double r2) {
  return density * kPi * width * (std::pow(r2, 4) - std::pow(r1, 4)) / 2.0;
}

double sign(double x) { return x < 0.0 ? -1.0 : 1.0; }

}  // namespace

const char* body_name(BodyId b) {
  switch (b) {
    case BodyId::WaveGenerator: return "wave_generator";
    case BodyId::FlexsplineRim: return "flexspline_rim";
    case BodyId::FlexsplineFlange: return "flexspline";
    case BodyId::CircularSpline: return "circular_spline";
  }
  return "?";
}

SteadyState steady_state(const DynamicsModel& m) {
  const auto& p = m.params;
  const double zf = m.teeth_flexspline, zc = m.teeth_circular, rho = zc / zf;
  assert(zf > 0 && zc > zf && p.drive_speed_rpm > 0);
  const double w = p.drive_speed_rpm * 2.0 * kPi / 60.0;
  const bool compliant = p.flexspline_compliance_rad_per_Nm > 0.0;
  SteadyState s;
  auto set = [&](BodyId b, BodyRole r) { s.role[static_cast<int>(b)] = r; };
  auto speed = [&](BodyId b) -> double& { return s.speed_rad_s[static_cast<int>(b)]; };
  double wf = 0, wc = 0, ww = 0;
  switch (p.configuration) {
    case DynamicsConfiguration::CsFixed:
      set(BodyId::WaveGenerator, BodyRole::Driven); set(BodyId::CircularSpline, BodyRole::Fixed);
      set(BodyId::FlexsplineFlange, BodyRole::Free);
      s.driven = BodyId::WaveGenerator; s.output = BodyId::FlexsplineFlange;
      ww = w; wf = (1.0 - rho) * w; wc = 0.0;
      break;
    case DynamicsConfiguration::FsFixed:
      set(BodyId::WaveGenerator, BodyRole::Driven); set(BodyId::FlexsplineFlange, BodyRole::Fixed);
      set(BodyId::CircularSpline, BodyRole::Free);
      s.driven = BodyId::WaveGenerator; s.output = BodyId::CircularSpline;
      ww = w; wf = 0.0; wc = (1.0 - 1.0 / rho) * w;
      break;
    case DynamicsConfiguration::WgFixed:
      set(BodyId::WaveGenerator, BodyRole::Fixed); set(BodyId::FlexsplineFlange, BodyRole::Driven);
      set(BodyId::CircularSpline, BodyRole::Free);
      s.driven = BodyId::FlexsplineFlange; s.output = BodyId::CircularSpline;
      ww = 0.0; wf = w; wc = w / rho;
      break;
    case DynamicsConfiguration::AllFree: {
      set(BodyId::WaveGenerator, BodyRole::Driven); set(BodyId::FlexsplineFlange, BodyRole::Free);
      set(BodyId::CircularSpline, BodyRole::Free);
      s.driven = BodyId::WaveGenerator; s.output = BodyId::FlexsplineFlange;
      const double b = p.circular_spline_drag_Nms_per_rad;
      // The flexspline carries the load T, the circular spline reacts it through its brake: along the differential's
      // free mode (z_c, z_f) the generalized forces cancel, z_c·T − z_f·b·ω_c = 0, and the kinematic relation gives
      // ω_f. The load resists the flexspline's (backward) motion only while ω_f < 0, i.e. b > b_min.
      // With output drag D(ω_f) the flexspline's torque is T + D(ω_f) and
      //   g(ω_f) = ω_f − (1 − ρ)·ω_w − ρ²·(T + D(ω_f))/b = 0,   g' = 1 − ρ²·D'/b ≥ 1: bisection on a bracket.
      const double T = p.load_torque_Nm;
      auto g = [&](double wf_) { return wf_ - (1.0 - rho) * w - rho * rho * (T + output_drag_Nm(p, wf_)) / b; };
      double lo = -1.0, hi = 1.0;
      while (g(lo) > 0) lo *= 2.0;
      while (g(hi) < 0) hi *= 2.0;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (mid == lo || mid == hi) break;
        (g(mid) < 0 ? lo : hi) = mid;
      }
      wf = 0.5 * (lo + hi);
      if (!(wf < 0.0) && T > 0.0) {
        const double b_min = rho * rho * T / (w * (rho - 1.0));
        std::ostringstream os;
        os << "[dynamics] circular_spline_drag_Nms_per_rad = " << b << "; with load_torque_Nm = " << T
           << " and configuration = \"all_free\" it must be > " << b_min
           << " (more with output drag; else the load drives the flexspline instead of resisting it)";
        throw InputError(os.str());
      }
      ww = w;
      wc = (wf - (1.0 - rho) * w) / rho;
      s.load_torque_Nm = T;
      break;
    }
  }
  set(BodyId::FlexsplineRim, compliant ? BodyRole::Free : BodyRole::MergedIntoFlange);
  speed(BodyId::WaveGenerator) = ww;
  speed(BodyId::FlexsplineRim) = wf;
  speed(BodyId::FlexsplineFlange) = wf;
  speed(BodyId::CircularSpline) = wc;
  if (p.configuration != DynamicsConfiguration::AllFree)
    s.load_torque_Nm = -sign(s.speed_rad_s[static_cast<int>(s.output)]) * p.load_torque_Nm;
  s.drag_torque_Nm = output_drag_Nm(p, s.speed_rad_s[static_cast<int>(s.output)]);
  // Steady mesh torque from the free body that carries the load: flexspline (Q_f = −M) or circular spline (Q_c = ρM).
  const double on_output = s.load_torque_Nm + s.drag_torque_Nm;
  s.mesh_torque_Nm = s.output == BodyId::FlexsplineFlange ? on_output : -on_output / rho;
  s.mesh_frequency_Hz = zf * std::abs(wf - ww) / (2.0 * kPi);
  return s;
}

double output_drag_Nm(const DynamicsParams& p, double omega) {
  double d = p.output_drag_viscous_Nms_per_rad * omega;
  if (p.output_drag_coulomb_Nm != 0.0) d += p.output_drag_coulomb_Nm * std::tanh(omega / p.drag_smoothing_rad_per_s);
  return -d;
}

double ramp(RampShape shape, double t, double t0, double t1) {
  if (t <= t0) return 0.0;
  if (t >= t1) return 1.0;
  const double d = (t - t0) / (t1 - t0);
  if (shape == RampShape::Cubic) return d * d * (3.0 - 2.0 * d);
  return d <= 0.5 ? 2.0 * d * d : 1.0 - 2.0 * (1.0 - d) * (1.0 - d);
}

double ramp_rate(RampShape shape, double t, double t0, double t1) {
  if (t <= t0 || t >= t1) return 0.0;
  const double T = t1 - t0, d = (t - t0) / T;
  if (shape == RampShape::Cubic) return 6.0 * d * (1.0 - d) / T;
  return d <= 0.5 ? 4.0 * d / T : 4.0 * (1.0 - d) / T;
}

double ramp_integral(RampShape shape, double t, double t0, double t1) {
  if (t <= t0) return 0.0;
  const double T = t1 - t0;
  if (t >= t1) return 0.5 * T + (t - t1);
  const double d = (t - t0) / T;
  if (shape == RampShape::Cubic) return T * (d * d * d - 0.5 * d * d * d * d);
  if (d <= 0.5) return T * (2.0 / 3.0) * d * d * d;
  const double e = 1.0 - d;
  return T * (1.0 / 12.0 + (d - 0.5) + (2.0 / 3.0) * (e * e * e - 0.125));
}

FlankForce flank_force(const DynamicsParams& p, double stiffness, double delta, double rate) {
  if (delta <= 0.0) return {};
  const double el = stiffness * (p.exponent_stiffness == 1.0 ? delta : std::pow(delta, p.exponent_stiffness));
  double damp = p.damping_Ns_per_m * rate;
  if (p.exponent_damping != 0.0) damp *= std::pow(std::abs(rate), p.exponent_damping);
  if (p.exponent_indentation != 0.0) damp *= std::pow(delta, p.exponent_indentation);
  return {std::max(0.0, el + damp), el};
}

LoadSharing quasi_static_load_sharing(const std::vector<ToothPair>& pairs, const DynamicsParams& p, double M) {
  auto forces = [&](double e, std::vector<double>* out) {
    double torque = 0.0;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const double a = pairs[i].arm_m(), b = pairs[i].coast_arm();
      const double fd = flank_force(p, p.stiffness_N_per_m, a * e - pairs[i].clearance_drive_m, 0.0).force_N;
      const double fc = flank_force(p, p.stiffness_N_per_m, -b * e - pairs[i].clearance_coast_m, 0.0).force_N;
      if (out) (*out)[i] = fd - fc;
      torque += fd * a - fc * b;
    }
    return torque;
  };
  if (pairs.empty()) throw InputError("dynamics: no tooth pair in the engagement zones; widen the engagement zone");
  // Σ F_i(e)·a_i is non-decreasing in e: bracket M, then bisect to the last bit.
  double lo = 0.0, hi = 0.0, step = 1e-9;
  for (int it = 0; it < 200 && forces(M >= 0 ? hi : lo, nullptr) * (M >= 0 ? 1 : -1) < std::abs(M); ++it) {
    if (M >= 0) { lo = hi; hi += step; } else { hi = lo; lo -= step; }
    step *= 2.0;
  }
  for (int it = 0; it < 200 && hi - lo > 0.0; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (forces(mid, nullptr) < M ? lo : hi) = mid;
  }
  LoadSharing r;
  r.deflection_rad = 0.5 * (lo + hi);
  r.force_N.resize(pairs.size());
  forces(r.deflection_rad, &r.force_N);
  return r;
}

namespace {
template <class T>
void require(bool ok, const std::string& where, const char* key, T value, const char* constraint) {
  if (ok) return;
  std::ostringstream os;
  if (!where.empty()) os << where << ": ";
  os << "dynamics." << key << " = " << value << "; " << constraint;
  throw InputError(os.str());
}
}  // namespace

void validate(const DynamicsParams& p, const std::string& w) {
  check_key_ranges(p, dynamics_keys(), "dynamics", w.empty() ? "" : w + ": ");
  require(p.drive_ramp_end_s > p.drive_ramp_start_s, w, "drive_ramp_end_s", p.drive_ramp_end_s,
          "must be > drive_ramp_start_s");
  require(p.load_ramp_end_s > p.load_ramp_start_s, w, "load_ramp_end_s", p.load_ramp_end_s,
          "must be > load_ramp_start_s");
  require(p.stiffness_variation_N_per_m < p.stiffness_N_per_m, w, "stiffness_variation_N_per_m",
          p.stiffness_variation_N_per_m, "must be >= 0 and < stiffness_N_per_m");
  require(p.output_step_s * 16 <= p.duration_s, w, "output_step_s", p.output_step_s,
          "must be > 0 and at most duration_s/16");
  require(p.steady_from_s + 8 * p.output_step_s <= p.duration_s, w, "steady_from_s", p.steady_from_s,
          "must leave at least 8 samples before duration_s");
}

void validate_moving(const DynamicsParams& p, const std::string& w) {
  if (p.rim == RimCoupling::Fem) {
    require(p.flexspline_compliance_rad_per_Nm == 0, w, "flexspline_compliance_rad_per_Nm",
            p.flexspline_compliance_rad_per_Nm,
            "must be 0 with rim = \"fem\" (the body's torsion is in the rim's compliance; it would count twice)");
    require(p.exponent_stiffness == 1, w, "exponent_stiffness", p.exponent_stiffness,
            "must be 1 with rim = \"fem\" (pairs coupled through the rim form a linear complementarity problem)");
  }
  if (p.pair_stiffness == PairStiffness::Teeth)
    require(p.exponent_stiffness == 1, w, "exponent_stiffness", p.exponent_stiffness,
            "must be 1 with pair_stiffness = \"teeth\" (the tooth-pair compliance is linear)");
}

DynamicsModel make_model(const GearParams& gear, const FlexsplineParams& fs, bool cup, const Material& mat,
                         const DynamicsParams& p, std::vector<ToothPair> pairs, const std::string& where) {
  validate(p, where);
  DynamicsModel m;
  m.params = p;
  m.teeth_flexspline = gear.teeth_flexspline;
  m.teeth_circular = gear.teeth_circular;
  if (!(gear.teeth_circular > gear.teeth_flexspline && gear.teeth_flexspline > 0))
    throw InputError(where + ": gear.teeth_circular = " + std::to_string(gear.teeth_circular) +
                     "; must exceed gear.teeth_flexspline = " + std::to_string(gear.teeth_flexspline));
  m.inertia = body_inertias(gear, fs, cup, mat, p);
  m.pairs = std::move(pairs);
  if (m.pairs.empty())
    throw InputError(where + ": no engaged tooth pair at the wave-generator position 0; check [gear] and [wave_generator]");
  steady_state(m);  // throws for an all_free brake too weak for the load
  return m;
}

BodyInertias body_inertias(const GearParams& g, const FlexsplineParams& fs, bool cup, const Material& mat,
                           const DynamicsParams& p) {
  const double rho = mat.density_kg_m3, m = g.module_m;
  const double ri = fs.inner_radius_m;
  const double wall = ring_inertia(rho, std::max(0.0, fs.length_m - fs.rim_width_m), ri, ri + fs.wall_thickness_m);
  const double rim = ring_inertia(rho, fs.rim_width_m, ri, ri + fs.rim_thickness_m);
  const double teeth = 0.5 * ring_inertia(rho, fs.rim_width_m, ri + fs.rim_thickness_m,
                                          ri + fs.rim_thickness_m + 2.25 * m);
  const double diaphragm = cup ? ring_inertia(rho, fs.diaphragm_thickness_m, 0.0, ri) : 0.0;
  const double rc = m * g.teeth_circular / 2.0;
  const double cs_outer = p.circular_spline_outer_radius_m > 0 ? p.circular_spline_outer_radius_m
                                                               : rc + 2.25 * m + 0.15 * rc;
  const double cs_width = p.circular_spline_width_m > 0 ? p.circular_spline_width_m : fs.rim_width_m;
  BodyInertias J;
  J[BodyId::WaveGenerator] = ring_inertia(rho, fs.rim_width_m, 0.0, ri);
  J[BodyId::FlexsplineRim] = rim + teeth + 0.5 * wall;
  J[BodyId::FlexsplineFlange] = diaphragm + 0.5 * wall;
  J[BodyId::CircularSpline] = 0.5 * ring_inertia(rho, cs_width, rc - m, rc + 1.25 * m) +
                              ring_inertia(rho, cs_width, rc + 1.25 * m, cs_outer);
  return J;
}

std::vector<ToothPair> approximate_tooth_pairs(const GearParams& g, double w0, double half_angle, double base) {
  std::vector<ToothPair> pairs;
  const double alpha = g.pressure_angle_rad, rf = g.module_m * g.teeth_flexspline / 2.0;
  for (int i = 0; i < g.teeth_flexspline; ++i) {
    const double phi = std::remainder(2.0 * kPi * i / g.teeth_flexspline, 2.0 * kPi);  // (−π, π]
    const double from_axis = std::min(std::abs(phi), kPi - std::abs(phi));           // to the nearer end
    if (from_axis > half_angle + 1e-12) continue;
    ToothPair t;
    t.angle_rad = phi;
    const double c = base + w0 * (1.0 - std::cos(2.0 * phi)) * std::sin(alpha);
    t.clearance_drive_m = c;
    t.clearance_coast_m = c;
    t.lever_arm_m = rf + w0 * std::cos(2.0 * phi);
    t.normal_projection = std::cos(alpha);
    pairs.push_back(t);
  }
  return pairs;
}

}  // namespace sw
