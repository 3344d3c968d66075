#include "dynamics/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>
#include <type_traits>

#include <Eigen/Core>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "common/error.hpp"

namespace sw {
namespace {

constexpr int kWorkQuadratures = 4;  // input, output, dissipated, parametric work; then friction, the bearing's, when there
constexpr double kSpeedScale_per_s = 1.0e5;  // absolute tolerance on speed deviations = atol_rad · this (contact modes)
constexpr double kWorkTolerance_J = 1.0e-10;

int idx(BodyId b) { return static_cast<int>(b); }

/// Low-pass FIR for decimation by `ov`: Blackman-windowed sinc, cutoff 0.45 of the output rate (its transition
/// 0.4…0.5 of the output rate is 5.5/length of the fine rate wide: length 55·ov + 1), normalised to unit DC gain.
/// Blackman: passband ripple ~2e-4, stopband ≥ 74 dB.
std::vector<double> lowpass_fir(int ov) {
  const int M = 55 * ov / 2;
  const int L = 2 * M + 1;
  const double fc = 0.45 / ov;  // cycles per fine sample
  std::vector<double> h(L);
  double sum = 0.0;
  for (int k = 0; k < L; ++k) {
    const double x = k - M;
    const double sinc = x == 0 ? 2 * fc : std::sin(2 * std::numbers::pi * fc * x) / (std::numbers::pi * x);
    const double a = 2 * std::numbers::pi * k / (L - 1);
    h[k] = sinc * (0.42 - 0.5 * std::cos(a) + 0.08 * std::cos(2 * a));
    sum += h[k];
  }
  for (double& v : h) v /= sum;
  return h;
}

/// Everything computed from (t, y): used by the right-hand side and by the output sampling alike.
struct Snapshot {
  std::array<double, kBodyCount> theta{}, omega{};
  double travel_torque = 0.0;  ///< M_σ: torque of the teeth's travel (moving pairs)
  double mesh_torque = 0.0, total_force = 0.0, drive_torque = 0.0, load_torque = 0.0, stiffness = 0.0;
  double kinetic = 0.0, potential = 0.0;
  double p_in = 0.0, p_out = 0.0, p_diss = 0.0, p_param = 0.0, p_friction = 0.0, p_bearing = 0.0;
  std::array<double, kBodyCount> accel_dev{};  ///< v̇ of free bodies
  std::vector<double> pair_force;   ///< frozen: per pair; moving: per tooth (signed, ccw flank positive)
  double deflection = 0.0;          ///< mesh deflection e [rad]
  double in_contact = 0.0;          ///< moving: tooth flanks carrying force (both teeth of a half-turn pair)
  double max_force = 0.0;           ///< largest flank force [N]
  // moving pairs: scratch reused between evaluations
  MeshInstant inst;
  Eigen::VectorXd b, x_el;
  Eigen::VectorXd x_flank;           ///< per flank of inst: its normal force with the damping (N per tooth)
  std::vector<char> active;          ///< warm start, by (tooth, side) then station
  std::vector<char> local_active;
};

/// The driven body's prescribed motion at one instant: angle Θ, speed Ω and acceleration of the drive ramp.
struct DriveMotion {
  double angle = 0.0, speed = 0.0, accel = 0.0;
};

/// The bodies' deviations from the kinematic reference motion: angle x and speed v, per BodyId.
struct Deviations {
  std::array<double, kBodyCount> x{}, v{};
};

/// The mesh at one instant: deflection e [rad] and its rate, stiffness k(t) [N/m] and its rate.
struct MeshStep {
  double e = 0.0, e_rate = 0.0, k = 0.0, k_rate = 0.0;
};

/// What the contacts add up to at one instant: the flank torque M = Σ F_i·arm_i, the teeth's travel torque M_σ
/// (moving pairs), the total force Σ|F_i|, the potential U, the dissipated power and the parametric power of k(t);
/// the flanks' friction (moving pairs): its generalized forces on σ and on e (N·m) and its power (W, ≥ 0).
struct MeshLoad {
  double M = 0.0, M_sigma = 0.0, total = 0.0, U = 0.0, p_diss = 0.0, p_param = 0.0;
  double friction_sigma = 0.0, friction_e = 0.0, p_friction = 0.0;
};

class Evaluator {
public:
  explicit Evaluator(const DynamicsModel& m) : m_(m), p_(m.params), ss_(steady_state(m)) {
    const double w = p_.drive_speed_rpm * 2.0 * std::numbers::pi / 60.0;
    for (int b = 0; b < kBodyCount; ++b) ratio_[b] = ss_.speed_rad_s[b] / ss_.speed_rad_s[idx(ss_.driven)];
    drive_speed_ = w;
    rho_ = double(m.teeth_circular) / m.teeth_flexspline;
    compliant_ = p_.flexspline_compliance_rad_per_Nm > 0.0;
    fs_ = compliant_ ? BodyId::FlexsplineRim : BodyId::FlexsplineFlange;
    for (int b = 0; b < kBodyCount; ++b) inertia_[b] = m.inertia.kgm2[b];
    if (!compliant_) {
      inertia_[idx(BodyId::FlexsplineFlange)] += inertia_[idx(BodyId::FlexsplineRim)];
      inertia_[idx(BodyId::FlexsplineRim)] = 0.0;
    }
    inertia_[idx(ss_.output)] += p_.load_inertia_kgm2;
    for (int b = 0; b < kBodyCount; ++b)
      if (ss_.role[b] == BodyRole::Free) free_.push_back(b);
    kinematic_residual_ = (ratio_[idx(fs_)] - ratio_[idx(BodyId::WaveGenerator)]) -
                          rho_ * (ratio_[idx(BodyId::CircularSpline)] - ratio_[idx(BodyId::WaveGenerator)]);
    mesh_phase_rate_ = m.teeth_flexspline * std::abs(ratio_[idx(fs_)] - ratio_[idx(BodyId::WaveGenerator)]);
    friction_ = m.moving && m.friction_coefficient > 0.0;
    bearing_ = static_cast<bool>(m.generator_moment_Nm);
  }
  /// The work quadratures: input, output, dissipated, parametric, then the friction's when the flanks have friction
  /// and the generator bearing's when it has a friction moment.
  int quadratures() const { return kWorkQuadratures + (friction_ ? 1 : 0) + (bearing_ ? 1 : 0); }
  bool flank_friction() const { return friction_; }
  bool bearing_friction() const { return bearing_; }
  int size() const { return 2 * int(free_.size()) + quadratures(); }
  const std::vector<int>& free_bodies() const { return free_; }
  const SteadyState& steady() const { return ss_; }
  /// Kinematic reference angle of body b at t: R_b·Θ(t).
  double reference_angle(int b, double t) const {
    return ratio_[b] * drive_speed_ * ramp_integral(p_.ramp_shape, t, p_.drive_ramp_start_s, p_.drive_ramp_end_s);
  }

  void evaluate(double t, const double* y, Snapshot& s) const {
    const DriveMotion d = drive_at(t);
    const Deviations dev = deviations(y);
    for (int b = 0; b < kBodyCount; ++b) {
      s.theta[b] = ratio_[b] * d.angle + dev.x[b];
      s.omega[b] = ratio_[b] * d.speed + dev.v[b];
    }
    const MeshStep ms = mesh_state(d, dev);
    MeshLoad load;
    s.deflection = ms.e;
    if (m_.moving) {
      const int w = idx(BodyId::WaveGenerator), f = idx(fs_);
      moving_forces(s, ms, s.theta[w] - s.theta[f], s.omega[w] - s.omega[f], load);
    } else {
      frozen_forces(s, ms, load);
    }
    std::array<double, kBodyCount> Q = internal_torques(dev, load);
    s.p_bearing = bearing_ ? add_bearing_friction(s, Q) : 0.0;
    const std::array<double, kBodyCount> T = applied_torques(t, s);
    balance(d, Q, T, s);
    // what the mesh takes off the flexspline (Q_f = −M − M_σ − friction_σ + friction_e)
    s.mesh_torque = load.M + load.M_sigma + (load.friction_sigma - load.friction_e);
    s.travel_torque = load.M_sigma;
    s.total_force = load.total;
    s.stiffness = ms.k;
    s.potential = load.U;
    s.p_diss = load.p_diss;
    s.p_param = load.p_param;
    s.p_friction = load.p_friction;
  }

  void rhs(double t, const double* y, double* ydot, Snapshot& s) const {
    evaluate(t, y, s);
    for (std::size_t k = 0; k < free_.size(); ++k) {
      ydot[2 * k] = y[2 * k + 1];
      ydot[2 * k + 1] = s.accel_dev[free_[k]];
    }
    const std::size_t q = 2 * free_.size();
    ydot[q] = s.p_in;
    ydot[q + 1] = s.p_out;
    ydot[q + 2] = s.p_diss;
    ydot[q + 3] = s.p_param;
    if (friction_) ydot[q + 4] = s.p_friction;
    if (bearing_) ydot[q + 4 + (friction_ ? 1 : 0)] = s.p_bearing;
  }

  Snapshot make_snapshot() const {
    Snapshot s;
    s.pair_force.resize(m_.moving ? m_.moving->key_period() : m_.pairs.size());
    if (m_.moving) s.active.assign(2 * m_.moving->key_period() + m_.moving->station_q.size(), 0);
    return s;
  }

private:
  DriveMotion drive_at(double t) const {
    const double t0 = p_.drive_ramp_start_s, t1 = p_.drive_ramp_end_s;
    return {drive_speed_ * ramp_integral(p_.ramp_shape, t, t0, t1), drive_speed_ * ramp(p_.ramp_shape, t, t0, t1),
            drive_speed_ * ramp_rate(p_.ramp_shape, t, t0, t1)};
  }

  /// The free bodies' deviations from the state y; a rigid flexspline's rim moves with its flange.
  Deviations deviations(const double* y) const {
    Deviations d;
    for (std::size_t k = 0; k < free_.size(); ++k) { d.x[free_[k]] = y[2 * k]; d.v[free_[k]] = y[2 * k + 1]; }
    if (!compliant_) {
      d.x[idx(BodyId::FlexsplineRim)] = d.x[idx(BodyId::FlexsplineFlange)];
      d.v[idx(BodyId::FlexsplineRim)] = d.v[idx(BodyId::FlexsplineFlange)];
    }
    return d;
  }

  /// Mesh deflection and stiffness. The reference motion is kinematic when steady_state() is right, so its share κ·Θ
  /// of e is zero to rounding; it is kept so that a wrong speed ratio shows up as a slipping body instead of being
  /// assumed away.
  MeshStep mesh_state(const DriveMotion& d, const Deviations& dev) const {
    const int w = idx(BodyId::WaveGenerator), c = idx(BodyId::CircularSpline), f = idx(fs_);
    const auto& x = dev.x;
    const auto& v = dev.v;
    MeshStep ms;
    ms.e = kinematic_residual_ * d.angle + (x[f] - x[w]) - rho_ * (x[c] - x[w]);
    ms.e_rate = kinematic_residual_ * d.speed + (v[f] - v[w]) - rho_ * (v[c] - v[w]);
    const double psi = mesh_phase_rate_ * d.angle + p_.stiffness_phase_deg * std::numbers::pi / 180.0;
    ms.k = p_.stiffness_N_per_m + p_.stiffness_variation_N_per_m * std::sin(psi);
    ms.k_rate = p_.stiffness_variation_N_per_m * std::cos(psi) * mesh_phase_rate_ * d.speed;
    return ms;
  }

  /// Frozen pairs: the drive and the coast flank of each pair under the contact law.
  void frozen_forces(Snapshot& s, const MeshStep& ms, MeshLoad& load) const {
    const double m1 = p_.exponent_stiffness;
    for (std::size_t i = 0; i < m_.pairs.size(); ++i) {
      double F = 0.0;
      for (int flank = 0; flank < 2; ++flank) {
        const double sgn = flank == 0 ? 1.0 : -1.0;
        const double a = flank == 0 ? m_.pairs[i].arm_m() : m_.pairs[i].coast_arm();
        const double j = flank == 0 ? m_.pairs[i].clearance_drive_m : m_.pairs[i].clearance_coast_m;
        const double delta = sgn * a * ms.e - j;
        if (delta <= 0.0) continue;
        const double rate = sgn * a * ms.e_rate;
        const FlankForce ff = flank_force(p_, ms.k, delta, rate);
        F += sgn * ff.force_N;
        load.M += sgn * a * ff.force_N;
        load.p_diss += (ff.force_N - ff.elastic_N) * rate;
        const double u = (m1 == 1.0 ? delta * delta : std::pow(delta, m1 + 1.0)) / (m1 + 1.0);
        load.U += ms.k * u;
        load.p_param += ms.k_rate * u;
      }
      s.pair_force[i] = F;
      load.total += std::abs(F);
    }
    s.max_force = 0.0;
    for (double F : s.pair_force) s.max_force = std::max(s.max_force, std::abs(F));
  }

  /// Forces of the moving pairs at mesh deflection e (rate ė) and generator angle σ = θ_w − θ_f relative to the
  /// flexspline (rate σ̇). Adds to M = Σ λ_i x_i (through e) and M_σ = Σ x_i ∂(q − λe)_i/∂σ + ½ x_elᵀ ∂A/∂σ x_el, the
  /// torque of the teeth's travel (Q_w += M_σ, Q_f −= M_σ: U(e, σ) = −min_x ½xᵀAx + (q − λe)ᵀx depends on σ).
  void moving_forces(Snapshot& s, const MeshStep& ms, double sigma, double sigma_rate, MeshLoad& load) const {
    const MovingMesh& mm = *m_.moving;
    mesh_instant(mm, sigma, s.inst, friction_);
    const MeshInstant& in = s.inst;
    const int nf = in.flanks();
    const int nb = mm.coupled() ? static_cast<int>(mm.station_q.size()) : 0;
    std::fill(s.pair_force.begin(), s.pair_force.end(), 0.0);
    s.x_el.setZero(nf + nb);
    s.b.resize(nf + nb);
    for (int i = 0; i < nf; ++i) s.b[i] = in.q[i] - in.lambda[i] * ms.e;
    if (mm.coupled()) coupled_elastic_forces(s, ms, load);
    else independent_elastic_forces(s, ms, load);
    const bool constant = p_.pair_stiffness == PairStiffness::Constant;
    const double n = mm.teeth_per_unknown;
    if (constant && mm.coupled())
      for (int i = 0; i < nf; ++i) load.p_param += 0.5 * s.x_el[i] * s.x_el[i] * n * ms.k_rate / (ms.k * ms.k);
    // the tooth compliance's own variation with σ (the contact point moves along the flank): ½ x² ∂c/∂σ
    if (!constant)
      for (int i = 0; i < nf; ++i) load.M_sigma += 0.5 * s.x_el[i] * s.x_el[i] * in.dcompliance[i];
    damped_flank_forces(s, ms, sigma_rate, load);
    if (friction_) flank_friction(s, ms, sigma_rate, load);
  }

  /// Series compliance of flank unknown i (n teeth): n/k for the constant law, else the tooth pairs'.
  double series_compliance(const MeshInstant& in, int i, double k) const {
    return p_.pair_stiffness == PairStiffness::Constant ? m_.moving->teeth_per_unknown / k : in.compliance[i];
  }

  /// Rim coupled through the body: the tooth pairs' series compliance on the body's diagonal, the contact problem
  /// solved from the last instant's contact set, its potential ½xᵀAx and the body's share of the travel torque.
  void coupled_elastic_forces(Snapshot& s, const MeshStep& ms, MeshLoad& load) const {
    const MovingMesh& mm = *m_.moving;
    MeshInstant& inst = s.inst;
    const int nf = inst.flanks(), nb = static_cast<int>(mm.station_q.size());
    for (int i = 0; i < nf; ++i) inst.series[i] = series_compliance(inst, i, ms.k);
    s.b.tail(nb) = mm.station_q;
    s.local_active.resize(nf + nb);
    const int period = mm.key_period();
    for (int i = 0; i < nf; ++i) s.local_active[i] = s.active[2 * inst.tooth[i] + inst.side[i]];
    for (int j = 0; j < nb; ++j) s.local_active[nf + j] = s.active[2 * period + j];
    solve_lcp([&inst](int j) { return inst.column(j); }, s.b, s.x_el, s.local_active);
    for (int i = 0; i < nf; ++i) s.active[2 * inst.tooth[i] + inst.side[i]] = s.x_el[i] > 0;
    for (int j = 0; j < nb; ++j) s.active[2 * period + j] = s.local_active[nf + j];
    load.U -= 0.5 * s.x_el.dot(s.b);  // ½xᵀAx = −½xᵀb: x·(Ax + b) = 0 at the solution
    load.M_sigma += body_travel_torque_Nm(inst, s.x_el);
  }

  /// Rigid rim: each flank alone, under the constant law (k per tooth) or its tooth pair's compliance.
  void independent_elastic_forces(Snapshot& s, const MeshStep& ms, MeshLoad& load) const {
    const MeshInstant& in = s.inst;
    const double n = m_.moving->teeth_per_unknown;
    const bool constant = p_.pair_stiffness == PairStiffness::Constant;
    const double m1 = p_.exponent_stiffness, k = ms.k;
    for (int i = 0; i < in.flanks(); ++i) {
      const double d = -s.b[i] / n;  // approach per tooth
      if (d <= 0) continue;
      if (constant) {
        const double u = m1 == 1.0 ? d * d / 2 : std::pow(d, m1 + 1) / (m1 + 1);
        s.x_el[i] = k * (m1 == 1.0 ? d : std::pow(d, m1));
        load.U += n * k * u;
        load.p_param += n * ms.k_rate * u;
      } else {
        s.x_el[i] = -s.b[i] / in.compliance[i];
        load.U += 0.5 * s.x_el[i] * s.x_el[i] * in.compliance[i];
      }
    }
  }

  /// Damping acts on the rigid approach rate δ̇ = λė − ∂(q − λe)/∂σ·σ̇ (per tooth), in parallel with the pair's
  /// series chain (tooth, and the rim when coupled), only where the elastic force is positive; the total is clamped
  /// at 0. The flanks' forces make the pair forces, M, M_σ, the total and the flanks in contact.
  void damped_flank_forces(Snapshot& s, const MeshStep& ms, double sigma_rate, MeshLoad& load) const {
    const MeshInstant& in = s.inst;
    const double n = m_.moving->teeth_per_unknown;
    const bool constant = p_.pair_stiffness == PairStiffness::Constant;
    const double m1 = p_.exponent_stiffness, k = ms.k;
    s.in_contact = 0.0;
    s.max_force = 0.0;
    s.x_flank.setZero(in.flanks());
    for (int i = 0; i < in.flanks(); ++i) {
      if (!(s.x_el[i] > 0)) continue;
      const double g_sigma = in.dq[i] - in.dlambda[i] * ms.e;  // ∂(q − λe)/∂σ
      const double rate = in.lambda[i] * ms.e_rate - g_sigma * sigma_rate;  // d(λe − q)/dt, n teeth
      double x = s.x_el[i];
      if (p_.damping_Ns_per_m > 0) {
        const double r1 = rate / n;
        const double local =
            constant ? (m1 == 1.0 ? x / k : std::pow(x / k, 1.0 / m1)) : x * series_compliance(in, i, k) / n;
        double fd = p_.damping_Ns_per_m * r1;
        if (p_.exponent_damping != 0) fd *= std::pow(std::abs(r1), p_.exponent_damping);
        if (p_.exponent_indentation != 0) fd *= std::pow(local, p_.exponent_indentation);
        x = std::max(0.0, x + fd);
      }
      load.p_diss += (x - s.x_el[i]) * rate;
      s.x_flank[i] = x;
      load.M += in.lambda[i] * x;
      load.M_sigma += x * g_sigma;
      const double sgn = in.side[i] == 0 ? 1.0 : -1.0;
      s.pair_force[in.tooth[i]] += sgn * x;
      load.total += n * x;
      if (x > 0) s.in_contact += n;
      s.max_force = std::max(s.max_force, x);
    }
  }

  /// Coulomb friction on the loaded flanks, each tooth's F_t = −μ·x·tanh(v/v_s) along the profile against its
  /// sliding v = (s·σ̇ + t·ė)/n (n teeth per unknown; s, t and the normal force x from the flank problem). Its virtual
  /// power Σ n·F_t·v = Σ F_t·(s·σ̇ + t·ė) gives its generalized forces on σ (Σ F_t·s) and on e (Σ F_t·t); it dissipates
  /// Σ n·|F_t·v|.
  void flank_friction(const Snapshot& s, const MeshStep& ms, double sigma_rate, MeshLoad& load) const {
    const MeshInstant& in = s.inst;
    const double n = m_.moving->teeth_per_unknown, mu = m_.friction_coefficient;
    for (int i = 0; i < in.flanks(); ++i) {
      if (!(s.x_flank[i] > 0)) continue;
      const double v = (in.sliding[i] * sigma_rate + in.tangent_arm[i] * ms.e_rate) / n;
      const double force = -mu * s.x_flank[i] * std::tanh(v / m_.friction_smoothing_m_per_s);
      load.friction_sigma += force * in.sliding[i];
      load.friction_e += force * in.tangent_arm[i];
      load.p_friction -= n * force * v;
    }
  }

  /// Generalized torques of the mesh (virtual work of M, of M_σ, which depends on σ = θ_w − θ_f, and of the flanks'
  /// friction on σ and e) and of the compliant flexspline's torsion spring, whose damping and energy join the load's.
  std::array<double, kBodyCount> internal_torques(const Deviations& dev, MeshLoad& load) const {
    const int w = idx(BodyId::WaveGenerator), c = idx(BodyId::CircularSpline), f = idx(fs_);
    std::array<double, kBodyCount> Q{};
    Q[f] -= load.M;
    Q[c] += rho_ * load.M;
    Q[w] += (1.0 - rho_) * load.M;
    Q[w] += load.M_sigma;
    Q[f] -= load.M_sigma;
    if (friction_) {  // σ = θ_w − θ_f, e = (θ_f − θ_w) − ρ(θ_c − θ_w)
      Q[w] += load.friction_sigma + (rho_ - 1.0) * load.friction_e;
      Q[f] += load.friction_e - load.friction_sigma;
      Q[c] -= rho_ * load.friction_e;
    }
    if (compliant_) {
      const auto& x = dev.x;
      const auto& v = dev.v;
      const int r = idx(BodyId::FlexsplineRim), o = idx(BodyId::FlexsplineFlange);
      const double K = 1.0 / p_.flexspline_compliance_rad_per_Nm, D = p_.flexspline_torsion_damping_Nms_per_rad;
      const double tau = K * (x[o] - x[r]) + D * (v[o] - v[r]);
      Q[r] += tau;
      Q[o] -= tau;
      load.p_diss += D * (v[o] - v[r]) * (v[o] - v[r]);
      load.U += 0.5 * K * (x[o] - x[r]) * (x[o] - x[r]);
    }
    return Q;
  }

  /// The generator bearing's friction moment between the generator and the flexspline's rim, against their relative
  /// turn (smoothed over drag_smoothing_rad_per_s): added to Q; its power (≥ 0) returned.
  double add_bearing_friction(const Snapshot& s, std::array<double, kBodyCount>& Q) const {
    const int w = idx(BodyId::WaveGenerator), f = idx(fs_);
    const double relative = s.omega[w] - s.omega[f];
    const double M = m_.generator_moment_Nm(std::abs(relative)) *
                     std::tanh(relative / p_.drag_smoothing_rad_per_s);
    Q[w] -= M;
    Q[f] += M;
    return M * relative;
  }

  /// The applied torques: the ramped load and the drag on the output body, the brake on a free circular spline.
  std::array<double, kBodyCount> applied_torques(double t, Snapshot& s) const {
    std::array<double, kBodyCount> T{};
    s.load_torque = ss_.load_torque_Nm * ramp(p_.ramp_shape, t, p_.load_ramp_start_s, p_.load_ramp_end_s);
    T[idx(ss_.output)] += s.load_torque + output_drag_Nm(p_, s.omega[idx(ss_.output)]);
    if (p_.configuration == DynamicsConfiguration::AllFree) {
      const int c = idx(BodyId::CircularSpline);
      T[c] -= p_.circular_spline_drag_Nms_per_rad * s.omega[c];
    }
    return T;
  }

  /// The drive torque that keeps the driven body on its prescribed motion, the powers in and out, the kinetic energy
  /// and the free bodies' accelerations as deviations from the reference's.
  void balance(const DriveMotion& d, const std::array<double, kBodyCount>& Q, const std::array<double, kBodyCount>& T,
               Snapshot& s) const {
    const int dr = idx(ss_.driven);
    s.drive_torque = inertia_[dr] * ratio_[dr] * d.accel - (Q[dr] + T[dr]);
    s.p_in = s.drive_torque * s.omega[dr];
    s.p_out = 0.0;
    s.kinetic = 0.0;
    for (int b = 0; b < kBodyCount; ++b) {
      s.p_out -= T[b] * s.omega[b];
      s.kinetic += 0.5 * inertia_[b] * s.omega[b] * s.omega[b];  // merged rim has zero inertia here
    }
    for (int b : free_) s.accel_dev[b] = (Q[b] + T[b]) / inertia_[b] - ratio_[b] * d.accel;
  }

  const DynamicsModel& m_;
  const DynamicsParams& p_;
  SteadyState ss_;
  std::array<double, kBodyCount> ratio_{}, inertia_{};
  double drive_speed_ = 0.0, rho_ = 1.0, mesh_phase_rate_ = 0.0;
  double kinematic_residual_ = 0.0;  ///< de/dΘ of the reference motion: 0 up to rounding
  bool compliant_ = false;
  bool friction_ = false;  ///< moving pairs with μ > 0
  bool bearing_ = false;   ///< the generator bearing has a friction moment
  BodyId fs_ = BodyId::FlexsplineFlange;
  std::vector<int> free_;
};

struct RhsData {
  const Evaluator* ev;
  Snapshot scratch;
};

int cvode_rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto* d = static_cast<RhsData*>(user);
  d->ev->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), d->scratch);
  return 0;
}

// RAII owners of the SUNDIALS objects.
struct ContextDeleter { void operator()(SUNContext c) const { SUNContext_Free(&c); } };
struct VectorDeleter { void operator()(_generic_N_Vector* v) const { N_VDestroy(v); } };
struct MatrixDeleter { void operator()(_generic_SUNMatrix* A) const { SUNMatDestroy(A); } };
struct SolverDeleter { void operator()(_generic_SUNLinearSolver* s) const { SUNLinSolFree(s); } };
struct CvodeDeleter { void operator()(void* mem) const { CVodeFree(&mem); } };

void check(int flag, const char* what) {
  if (flag < 0) {
    std::ostringstream os;
    os << "dynamics: CVODE " << what << " failed with flag " << flag << " (" << CVodeGetReturnFlagName(flag) << ")";
    throw InputError(os.str());
  }
}

/// CVODE's BDF with dense Newton on the evaluator's right-hand side, from rest on the kinematic reference: absolute
/// tolerances absolute_tolerance_rad on the angles, kSpeedScale_per_s times it on the speeds, kWorkTolerance_J on the
/// work quadratures.
class Integrator {
public:
  Integrator(const Evaluator& ev, const DynamicsParams& p) : data_{&ev, ev.make_snapshot()} {
    const int n = ev.size();
    const int nfree = int(ev.free_bodies().size());
    SUNContext raw_ctx = nullptr;
    if (SUNContext_Create(nullptr, &raw_ctx) != 0) throw InputError("dynamics: SUNDIALS context creation failed");
    ctx_.reset(raw_ctx);
    y_.reset(N_VNew_Serial(n, raw_ctx));
    atol_.reset(N_VNew_Serial(n, raw_ctx));
    double* yv = N_VGetArrayPointer(y_.get());
    double* av = N_VGetArrayPointer(atol_.get());
    for (int i = 0; i < n; ++i) yv[i] = 0.0;  // from rest, on the kinematic reference
    for (int k = 0; k < nfree; ++k) {
      av[2 * k] = p.absolute_tolerance_rad;
      av[2 * k + 1] = p.absolute_tolerance_rad * kSpeedScale_per_s;
    }
    for (int q = 0; q < ev.quadratures(); ++q) av[2 * nfree + q] = kWorkTolerance_J;
    mem_.reset(CVodeCreate(CV_BDF, raw_ctx));
    if (!mem_) throw InputError("dynamics: CVodeCreate failed");
    check(CVodeInit(mem_.get(), cvode_rhs, 0.0, y_.get()), "init");
    check(CVodeSVtolerances(mem_.get(), p.relative_tolerance, atol_.get()), "tolerances");
    check(CVodeSetUserData(mem_.get(), &data_), "user data");
    A_.reset(SUNDenseMatrix(n, n, raw_ctx));
    solver_.reset(SUNLinSol_Dense(y_.get(), A_.get(), raw_ctx));
    check(CVodeSetLinearSolver(mem_.get(), solver_.get(), A_.get()), "linear solver");
    check(CVodeSetMaxNumSteps(mem_.get(), 5'000'000), "max steps");
    check(CVodeSetMaxStep(mem_.get(), 10.0 * p.output_step_s), "max step");
  }
  Integrator(const Integrator&) = delete;
  Integrator& operator=(const Integrator&) = delete;

  /// Integrates on to t_out_s. Throws InputError naming the time reached and CVODE's flag when it fails.
  void advance_to(double t_out_s) {
    double t = 0.0;
    const int flag = CVode(mem_.get(), t_out_s, y_.get(), &t, CV_NORMAL);
    if (flag < 0) {
      std::ostringstream os;
      os << "dynamics: the integrator failed at t = " << t << " s with " << CVodeGetReturnFlagName(flag)
         << "; loosen [dynamics] relative_tolerance or check the contact stiffness and damping";
      throw InputError(os.str());
    }
  }

  /// The state at the last time reached: each free body's angle and speed deviation, then the work quadratures.
  const double* state() const { return N_VGetArrayPointer(y_.get()); }

  SolverStats stats() const {
    SolverStats out;
    long v = 0;
    CVodeGetNumSteps(mem_.get(), &v); out.steps = v;
    CVodeGetNumRhsEvals(mem_.get(), &v); out.rhs_evals = v;
    CVodeGetNumJacEvals(mem_.get(), &v); out.jac_evals = v;
    CVodeGetNumErrTestFails(mem_.get(), &v); out.error_test_fails = v;
    CVodeGetNumNonlinSolvConvFails(mem_.get(), &v); out.newton_fails = v;
    return out;
  }

private:
  RhsData data_;
  std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter> ctx_;
  std::unique_ptr<_generic_N_Vector, VectorDeleter> y_, atol_;
  std::unique_ptr<void, CvodeDeleter> mem_;
  std::unique_ptr<_generic_SUNMatrix, MatrixDeleter> A_;
  std::unique_ptr<_generic_SUNLinearSolver, SolverDeleter> solver_;
};

/// The sampling of a run: `samples` outputs every output_step_s from 0 to duration_s, `ov` fine steps apart (fine
/// index `last` at duration_s); the integration goes on to fine index `end` − 1, half the filter's length beyond.
struct OutputGrid {
  long samples = 0;
  int ov = 1;
  std::vector<double> fir;  ///< the low-pass filter, {1} without oversampling
  long half = 0, last = 0, end = 0;
  double dt = 0.0;          ///< fine step [s]
};

OutputGrid output_grid(const DynamicsParams& p) {
  OutputGrid g;
  g.samples = std::lround(p.duration_s / p.output_step_s) + 1;
  g.ov = p.oversampling;
  g.fir = g.ov > 1 ? lowpass_fir(g.ov) : std::vector<double>{1.0};
  g.half = static_cast<long>(g.fir.size() / 2);
  g.last = (g.samples - 1) * g.ov;
  g.end = g.last + g.half + 1;
  g.dt = p.output_step_s / g.ov;
  return g;
}

/// Low-pass and decimate a fine record: output j is Σ h_k·x[j·ov + k − half], the record held at its first value
/// before t = 0.
std::vector<double> decimate(const std::vector<double>& x, const OutputGrid& g) {
  std::vector<double> y(g.samples);
  for (long j = 0; j < g.samples; ++j) {
    double acc = 0.0;
    for (long k = 0; k < static_cast<long>(g.fir.size()); ++k) acc += g.fir[k] * x[std::max(0L, j * g.ov + k - g.half)];
    y[j] = acc;
  }
  return y;
}

/// The energy terms from the start to one instant: the work quadratures of the state `quadratures` (input, output,
/// dissipated, parametric, then friction when `with_friction`, the bearing's when `with_bearing`), the kinetic energy
/// and the change of the potential since the start.
EnergyBalance energy_at(const double* quadratures, bool with_friction, bool with_bearing, const Snapshot& now,
                        double potential_at_start_J) {
  EnergyBalance e;
  e.input_J = quadratures[0];
  e.output_J = quadratures[1];
  e.dissipated_J = quadratures[2];
  e.parametric_J = quadratures[3];
  if (with_friction) e.friction_J = quadratures[4];
  if (with_bearing) e.bearing_J = quadratures[4 + (with_friction ? 1 : 0)];
  e.kinetic_J = now.kinetic;
  e.potential_J = now.potential - potential_at_start_J;
  return e;
}

/// What a run records at each fine step: the force-like signals in full (filtered at the end), the plain samples
/// (angles, speeds, load, k(t), flanks in contact, largest force, the energy terms) at the output steps.
class Recorder {
public:
  Recorder(const Evaluator& ev, const DynamicsModel& m, const OutputGrid& g)
      : ev_(ev), grid_(g), snapshot_(ev.make_snapshot()), output_(idx(ev.steady().output)) {
    const std::size_t np = m.moving ? static_cast<std::size_t>(m.moving->key_period()) : m.pairs.size();
    pair_.resize(np);
    series_.per_tooth = static_cast<bool>(m.moving);
  }

  /// Evaluates the state y at fine step i, time t (the first call at step 0, the start).
  void record(long i, double t, const double* y) {
    Snapshot& s = snapshot_;
    ev_.evaluate(t, y, s);
    if (i == 0) potential_at_start_J_ = s.potential;
    for (std::size_t k = 0; k < pair_.size(); ++k) pair_[k].push_back(s.pair_force[k]);
    torque_.push_back(s.mesh_torque);
    travel_.push_back(s.travel_torque);
    total_.push_back(s.total_force);
    drive_.push_back(s.drive_torque);
    deflection_.push_back(s.deflection);
    te_.push_back(s.theta[output_] - ev_.reference_angle(output_, t));
    if (i % grid_.ov != 0 || i > grid_.last) return;
    DynamicsSeries& out = series_;
    out.time_s.push_back(t);
    for (int b = 0; b < kBodyCount; ++b) {
      out.angle_rad[b].push_back(s.theta[b]);
      out.speed_rad_s[b].push_back(s.omega[b]);
    }
    out.load_torque_Nm.push_back(s.load_torque);
    out.stiffness_N_per_m.push_back(s.stiffness);
    out.flanks_in_contact.push_back(s.in_contact);
    out.max_pair_force_N.push_back(s.max_force);
    out.energy_to_sample.push_back(energy_at(y + 2 * ev_.free_bodies().size(), ev_.flank_friction(),
                                             ev_.bearing_friction(), s, potential_at_start_J_));
  }

  /// The series with the filtered signals decimated to the output steps.
  DynamicsSeries finish() && {
    DynamicsSeries out = std::move(series_);
    out.pair_force_N.resize(pair_.size());
    for (std::size_t k = 0; k < pair_.size(); ++k) out.pair_force_N[k] = decimate(pair_[k], grid_);
    out.mesh_torque_Nm = decimate(torque_, grid_);
    out.travel_torque_Nm = decimate(travel_, grid_);
    out.total_force_N = decimate(total_, grid_);
    out.drive_torque_Nm = decimate(drive_, grid_);
    out.deflection_rad = decimate(deflection_, grid_);
    out.transmission_error_rad = decimate(te_, grid_);
    return out;
  }

private:
  const Evaluator& ev_;
  const OutputGrid& grid_;
  Snapshot snapshot_;
  int output_;  ///< the output body, whose transmission error is recorded
  double potential_at_start_J_ = 0.0;
  DynamicsSeries series_;
  std::vector<std::vector<double>> pair_;
  std::vector<double> torque_, travel_, total_, drive_, deflection_, te_;
};

}  // namespace

double EnergyBalance::error_rel() const {
  const double lhs = input_J + parametric_J,
               rhs = output_J + dissipated_J + friction_J + bearing_J + kinetic_J + potential_J;
  return std::abs(lhs - rhs) / std::max(std::abs(input_J), 1e-300);
}

DynamicsSeries simulate(const DynamicsModel& m) {
  const auto& p = m.params;
  const Evaluator ev(m);
  Integrator cvode(ev, p);
  const OutputGrid grid = output_grid(p);
  Recorder recorder(ev, m, grid);
  recorder.record(0, 0.0, cvode.state());
  for (long i = 1; i < grid.end; ++i) {
    const double tout = i == grid.last ? p.duration_s : i * grid.dt;
    cvode.advance_to(tout);
    recorder.record(i, tout, cvode.state());
  }
  DynamicsSeries out = std::move(recorder).finish();
  out.energy = out.energy_to_sample.back();  // at duration_s
  out.stats = cvode.stats();
  return out;
}

}  // namespace sw
