#include "dynamics/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include <Eigen/Core>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "common/error.hpp"

namespace sw {
namespace {

constexpr int kQuadratures = 4;  // input, output, dissipated, parametric work
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
  double p_in = 0.0, p_out = 0.0, p_diss = 0.0, p_param = 0.0;
  std::array<double, kBodyCount> accel_dev{};  ///< v̇ of free bodies
  std::vector<double> pair_force;   ///< frozen: per pair; moving: per tooth (signed, ccw flank positive)
  double deflection = 0.0;          ///< mesh deflection e [rad]
  double in_contact = 0.0;          ///< moving: tooth flanks carrying force (both teeth of a half-turn pair)
  double max_force = 0.0;           ///< largest flank force [N]
  // moving pairs: scratch reused between evaluations
  MeshInstant inst;
  Eigen::VectorXd b, x, x_el;
  std::vector<char> active;          ///< warm start, by (tooth, side) then station
  std::vector<char> local_active;
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
  }
  int size() const { return 2 * int(free_.size()) + kQuadratures; }
  const std::vector<int>& free_bodies() const { return free_; }
  const SteadyState& steady() const { return ss_; }
  /// Kinematic reference angle of body b at t: R_b·Θ(t).
  double reference_angle(int b, double t) const {
    return ratio_[b] * drive_speed_ * ramp_integral(p_.ramp_shape, t, p_.drive_ramp_start_s, p_.drive_ramp_end_s);
  }

  void evaluate(double t, const double* y, Snapshot& s) const {
    const double Theta = drive_speed_ * ramp_integral(p_.ramp_shape, t, p_.drive_ramp_start_s, p_.drive_ramp_end_s);
    const double Omega = drive_speed_ * ramp(p_.ramp_shape, t, p_.drive_ramp_start_s, p_.drive_ramp_end_s);
    const double Alpha = drive_speed_ * ramp_rate(p_.ramp_shape, t, p_.drive_ramp_start_s, p_.drive_ramp_end_s);
    std::array<double, kBodyCount> x{}, v{};
    for (std::size_t k = 0; k < free_.size(); ++k) { x[free_[k]] = y[2 * k]; v[free_[k]] = y[2 * k + 1]; }
    if (!compliant_) {
      x[idx(BodyId::FlexsplineRim)] = x[idx(BodyId::FlexsplineFlange)];
      v[idx(BodyId::FlexsplineRim)] = v[idx(BodyId::FlexsplineFlange)];
    }
    for (int b = 0; b < kBodyCount; ++b) {
      s.theta[b] = ratio_[b] * Theta + x[b];
      s.omega[b] = ratio_[b] * Omega + v[b];
    }
    // Mesh deflection. The reference motion is kinematic when steady_state() is right, so its share κ·Θ is zero to
    // rounding; it is kept so that a wrong speed ratio shows up as a slipping body instead of being assumed away.
    const int w = idx(BodyId::WaveGenerator), c = idx(BodyId::CircularSpline), f = idx(fs_);
    const double e = kinematic_residual_ * Theta + (x[f] - x[w]) - rho_ * (x[c] - x[w]);
    const double e_rate = kinematic_residual_ * Omega + (v[f] - v[w]) - rho_ * (v[c] - v[w]);
    const double psi = mesh_phase_rate_ * Theta + p_.stiffness_phase_deg * std::numbers::pi / 180.0;
    const double k = p_.stiffness_N_per_m + p_.stiffness_variation_N_per_m * std::sin(psi);
    const double k_rate = p_.stiffness_variation_N_per_m * std::cos(psi) * mesh_phase_rate_ * Omega;
    const double m1 = p_.exponent_stiffness;
    double M = 0.0, total = 0.0, U = 0.0, p_diss = 0.0, p_param = 0.0;
    double M_sigma = 0.0;  // moving pairs: −∂U/∂θ_f = ∂U/∂θ_w ... see moving_forces()
    s.deflection = e;
    if (m_.moving) {
      moving_forces(s, e, e_rate, s.theta[w] - s.theta[f], s.omega[w] - s.omega[f], k, k_rate, M, M_sigma, total, U, p_diss, p_param);
    } else {
      for (std::size_t i = 0; i < m_.pairs.size(); ++i) {
        double F = 0.0;
        for (int flank = 0; flank < 2; ++flank) {
          const double sgn = flank == 0 ? 1.0 : -1.0;
          const double a = flank == 0 ? m_.pairs[i].arm_m() : m_.pairs[i].coast_arm();
          const double j = flank == 0 ? m_.pairs[i].clearance_drive_m : m_.pairs[i].clearance_coast_m;
          const double delta = sgn * a * e - j;
          if (delta <= 0.0) continue;
          const double rate = sgn * a * e_rate;
          const FlankForce ff = flank_force(p_, k, delta, rate);
          F += sgn * ff.force_N;
          M += sgn * a * ff.force_N;
          p_diss += (ff.force_N - ff.elastic_N) * rate;
          const double u = (m1 == 1.0 ? delta * delta : std::pow(delta, m1 + 1.0)) / (m1 + 1.0);
          U += k * u;
          p_param += k_rate * u;
        }
        s.pair_force[i] = F;
        total += std::abs(F);
      }
    }
    if (!m_.moving) {
      s.max_force = 0.0;
      for (double F : s.pair_force) s.max_force = std::max(s.max_force, std::abs(F));
    }
    std::array<double, kBodyCount> Q{}, T{};
    Q[f] -= M;
    Q[c] += rho_ * M;
    Q[w] += (1.0 - rho_) * M;
    Q[w] += M_sigma;  // the teeth's travel: U depends on σ = θ_w − θ_f
    Q[f] -= M_sigma;
    if (compliant_) {
      const int r = idx(BodyId::FlexsplineRim), o = idx(BodyId::FlexsplineFlange);
      const double K = 1.0 / p_.flexspline_compliance_rad_per_Nm, D = p_.flexspline_torsion_damping_Nms_per_rad;
      const double tau = K * (x[o] - x[r]) + D * (v[o] - v[r]);
      Q[r] += tau;
      Q[o] -= tau;
      p_diss += D * (v[o] - v[r]) * (v[o] - v[r]);
      U += 0.5 * K * (x[o] - x[r]) * (x[o] - x[r]);
    }
    s.load_torque = ss_.load_torque_Nm * ramp(p_.ramp_shape, t, p_.load_ramp_start_s, p_.load_ramp_end_s);
    T[idx(ss_.output)] += s.load_torque + output_drag_Nm(p_, s.omega[idx(ss_.output)]);
    if (p_.configuration == DynamicsConfiguration::AllFree) {
      T[c] -= p_.circular_spline_drag_Nms_per_rad * s.omega[c];
    }
    const int d = idx(ss_.driven);
    s.drive_torque = inertia_[d] * ratio_[d] * Alpha - (Q[d] + T[d]);
    s.p_in = s.drive_torque * s.omega[d];
    s.p_out = 0.0;
    s.kinetic = 0.0;
    for (int b = 0; b < kBodyCount; ++b) {
      s.p_out -= T[b] * s.omega[b];
      s.kinetic += 0.5 * inertia_[b] * s.omega[b] * s.omega[b];  // merged rim has zero inertia here
    }
    for (int b : free_) s.accel_dev[b] = (Q[b] + T[b]) / inertia_[b] - ratio_[b] * Alpha;
    s.mesh_torque = M + M_sigma;  // what the mesh takes off the flexspline (Q_f = −M − M_σ)
    s.travel_torque = M_sigma;
    s.total_force = total;
    s.stiffness = k;
    s.potential = U;
    s.p_diss = p_diss;
    s.p_param = p_param;
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
  }

  Snapshot make_snapshot() const {
    Snapshot s;
    s.pair_force.resize(m_.moving ? m_.moving->key_period() : m_.pairs.size());
    if (m_.moving) s.active.assign(2 * m_.moving->key_period() + m_.moving->station_q.size(), 0);
    return s;
  }

  /// Forces of the moving pairs at mesh deflection e (rate ė) and generator angle σ = θ_w − θ_f relative to the
  /// flexspline (rate σ̇). Adds to M = Σ λ_i x_i (through e) and M_σ = Σ x_i ∂(q − λe)_i/∂σ + ½ x_elᵀ ∂A/∂σ x_el, the
  /// torque of the teeth's travel (Q_w += M_σ, Q_f −= M_σ: U(e, σ) = −min_x ½xᵀAx + (q − λe)ᵀx depends on σ).
  /// Damping acts on the rigid approach rate δ̇ = λė − ∂(q − λe)/∂σ·σ̇ (per tooth), in parallel with the pair's
  /// series chain (tooth, and the rim when coupled), only where the elastic force is positive; the total is clamped at 0.
  void moving_forces(Snapshot& s, double e, double e_rate, double sigma, double sigma_rate, double k, double k_rate,
                     double& M, double& M_sigma, double& total, double& U, double& p_diss, double& p_param) const {
    const MovingMesh& mm = *m_.moving;
    mesh_instant(mm, sigma, s.inst);
    const MeshInstant& in = s.inst;
    const int nf = in.flanks();
    const int nb = mm.coupled() ? static_cast<int>(mm.station_q.size()) : 0;
    const double n = mm.teeth_per_unknown;
    const bool constant = p_.pair_stiffness == PairStiffness::Constant;
    const double m1 = p_.exponent_stiffness;
    std::fill(s.pair_force.begin(), s.pair_force.end(), 0.0);
    s.x_el.setZero(nf + nb);
    s.b.resize(nf + nb);
    for (int i = 0; i < nf; ++i) s.b[i] = in.q[i] - in.lambda[i] * e;
    // series compliance per unknown (n teeth) and its σ-derivative (diagonal of ∂A/∂σ)
    auto series = [&](int i) { return constant ? n / k : in.compliance[i]; };
    if (mm.coupled()) {
      MeshInstant& inst = s.inst;  // the series parts go on the body's diagonal
      for (int i = 0; i < nf; ++i) inst.series[i] = series(i);
      s.b.tail(nb) = mm.station_q;
      s.local_active.resize(nf + nb);
      const int period = mm.key_period();
      for (int i = 0; i < nf; ++i) s.local_active[i] = s.active[2 * in.tooth[i] + in.side[i]];
      for (int j = 0; j < nb; ++j) s.local_active[nf + j] = s.active[2 * period + j];
      solve_lcp([&inst](int j) { return inst.column(j); }, s.b, s.x_el, s.local_active);
      for (int i = 0; i < nf; ++i) s.active[2 * in.tooth[i] + in.side[i]] = s.x_el[i] > 0;
      for (int j = 0; j < nb; ++j) s.active[2 * period + j] = s.local_active[nf + j];
      U -= 0.5 * s.x_el.dot(s.b);  // ½xᵀAx = −½xᵀb: x·(Ax + b) = 0 at the solution
      M_sigma += body_travel_torque_Nm(in, s.x_el);
    } else {
      for (int i = 0; i < nf; ++i) {
        const double d = -s.b[i] / n;  // approach per tooth
        if (d <= 0) continue;
        if (constant) {
          const double u = m1 == 1.0 ? d * d / 2 : std::pow(d, m1 + 1) / (m1 + 1);
          s.x_el[i] = k * (m1 == 1.0 ? d : std::pow(d, m1));
          U += n * k * u;
          p_param += n * k_rate * u;
        } else {
          s.x_el[i] = -s.b[i] / in.compliance[i];
          U += 0.5 * s.x_el[i] * s.x_el[i] * in.compliance[i];
        }
      }
    }
    if (constant && mm.coupled())
      for (int i = 0; i < nf; ++i) p_param += 0.5 * s.x_el[i] * s.x_el[i] * n * k_rate / (k * k);
    // the tooth compliance's own variation with σ (the contact point moves along the flank): ½ x² ∂c/∂σ
    if (!constant)
      for (int i = 0; i < nf; ++i) M_sigma += 0.5 * s.x_el[i] * s.x_el[i] * in.dcompliance[i];
    s.in_contact = 0.0;
    s.max_force = 0.0;
    for (int i = 0; i < nf; ++i) {
      if (!(s.x_el[i] > 0)) continue;
      const double g_sigma = in.dq[i] - in.dlambda[i] * e;  // ∂(q − λe)/∂σ
      const double rate = in.lambda[i] * e_rate - g_sigma * sigma_rate;  // d(λe − q)/dt, n teeth
      double x = s.x_el[i];
      if (p_.damping_Ns_per_m > 0) {
        const double r1 = rate / n;
        const double local = constant ? (m1 == 1.0 ? x / k : std::pow(x / k, 1.0 / m1)) : x * series(i) / n;
        double fd = p_.damping_Ns_per_m * r1;
        if (p_.exponent_damping != 0) fd *= std::pow(std::abs(r1), p_.exponent_damping);
        if (p_.exponent_indentation != 0) fd *= std::pow(local, p_.exponent_indentation);
        x = std::max(0.0, x + fd);
      }
      p_diss += (x - s.x_el[i]) * rate;
      M += in.lambda[i] * x;
      M_sigma += x * g_sigma;
      const double sgn = in.side[i] == 0 ? 1.0 : -1.0;
      s.pair_force[in.tooth[i]] += sgn * x;
      total += n * x;
      if (x > 0) s.in_contact += n;
      s.max_force = std::max(s.max_force, x);
    }
  }

private:
  const DynamicsModel& m_;
  const DynamicsParams& p_;
  SteadyState ss_;
  std::array<double, kBodyCount> ratio_{}, inertia_{};
  double drive_speed_ = 0.0, rho_ = 1.0, mesh_phase_rate_ = 0.0;
  double kinematic_residual_ = 0.0;  ///< de/dΘ of the reference motion: 0 up to rounding
  bool compliant_ = false;
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

}  // namespace

double EnergyBalance::error_rel() const {
  const double lhs = input_J + parametric_J, rhs = output_J + dissipated_J + kinetic_J + potential_J;
  return std::abs(lhs - rhs) / std::max(std::abs(input_J), 1e-300);
}

DynamicsSeries simulate(const DynamicsModel& m) {
  const auto& p = m.params;
  Evaluator ev(m);
  const int n = ev.size();
  const int nfree = int(ev.free_bodies().size());

  SUNContext raw_ctx = nullptr;
  if (SUNContext_Create(nullptr, &raw_ctx) != 0) throw InputError("dynamics: SUNDIALS context creation failed");
  std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter> ctx(raw_ctx);
  std::unique_ptr<_generic_N_Vector, VectorDeleter> y(N_VNew_Serial(n, raw_ctx)), atol(N_VNew_Serial(n, raw_ctx));
  double* yv = N_VGetArrayPointer(y.get());
  double* av = N_VGetArrayPointer(atol.get());
  for (int i = 0; i < n; ++i) yv[i] = 0.0;  // from rest, on the kinematic reference
  for (int k = 0; k < nfree; ++k) {
    av[2 * k] = p.absolute_tolerance_rad;
    av[2 * k + 1] = p.absolute_tolerance_rad * kSpeedScale_per_s;
  }
  for (int q = 0; q < kQuadratures; ++q) av[2 * nfree + q] = kWorkTolerance_J;

  std::unique_ptr<void, CvodeDeleter> mem(CVodeCreate(CV_BDF, raw_ctx));
  if (!mem) throw InputError("dynamics: CVodeCreate failed");
  RhsData data{&ev, ev.make_snapshot()};
  check(CVodeInit(mem.get(), cvode_rhs, 0.0, y.get()), "init");
  check(CVodeSVtolerances(mem.get(), p.relative_tolerance, atol.get()), "tolerances");
  check(CVodeSetUserData(mem.get(), &data), "user data");
  std::unique_ptr<_generic_SUNMatrix, MatrixDeleter> A(SUNDenseMatrix(n, n, raw_ctx));
  std::unique_ptr<_generic_SUNLinearSolver, SolverDeleter> LS(SUNLinSol_Dense(y.get(), A.get(), raw_ctx));
  check(CVodeSetLinearSolver(mem.get(), LS.get(), A.get()), "linear solver");
  check(CVodeSetMaxNumSteps(mem.get(), 5'000'000), "max steps");
  check(CVodeSetMaxStep(mem.get(), 10.0 * p.output_step_s), "max step");

  DynamicsSeries out;
  const long samples = std::lround(p.duration_s / p.output_step_s) + 1;
  const int ov = p.oversampling;
  const std::vector<double> fir = ov > 1 ? lowpass_fir(ov) : std::vector<double>{1.0};
  const long half = static_cast<long>(fir.size() / 2);
  const long last = (samples - 1) * ov;  // fine index of duration_s
  const long fine = last + half + 1;     // the filter reaches half its length beyond the end
  const double dt = p.output_step_s / ov;
  const std::size_t np = m.moving ? static_cast<std::size_t>(m.moving->key_period()) : m.pairs.size();
  out.per_tooth = static_cast<bool>(m.moving);
  // fine records of the filtered signals
  std::vector<std::vector<double>> pair(np);
  std::vector<double> torque, total, drive, deflection, te, travel;
  Snapshot s = ev.make_snapshot();
  const int o = idx(ev.steady().output);
  auto record = [&](long i, double t) {
    ev.evaluate(t, yv, s);
    for (std::size_t k = 0; k < np; ++k) pair[k].push_back(s.pair_force[k]);
    torque.push_back(s.mesh_torque);
    travel.push_back(s.travel_torque);
    total.push_back(s.total_force);
    drive.push_back(s.drive_torque);
    deflection.push_back(s.deflection);
    te.push_back(s.theta[o] - ev.reference_angle(o, t));
    if (i % ov != 0 || i > last) return;
    out.time_s.push_back(t);
    for (int b = 0; b < kBodyCount; ++b) {
      out.angle_rad[b].push_back(s.theta[b]);
      out.speed_rad_s[b].push_back(s.omega[b]);
    }
    out.load_torque_Nm.push_back(s.load_torque);
    out.stiffness_N_per_m.push_back(s.stiffness);
    out.flanks_in_contact.push_back(s.in_contact);
    out.max_pair_force_N.push_back(s.max_force);
  };
  record(0, 0.0);
  const double potential0 = s.potential;
  for (long i = 1; i < fine; ++i) {
    const double tout = i == last ? p.duration_s : i * dt;
    double t = 0.0;
    const int flag = CVode(mem.get(), tout, y.get(), &t, CV_NORMAL);
    if (flag < 0) {
      std::ostringstream os;
      os << "dynamics: the integrator failed at t = " << t << " s with " << CVodeGetReturnFlagName(flag)
         << "; loosen [dynamics] relative_tolerance or check the contact stiffness and damping";
      throw InputError(os.str());
    }
    record(i, tout);
    if (i == last) {
      const double* q = yv + 2 * nfree;
      out.energy.input_J = q[0];
      out.energy.output_J = q[1];
      out.energy.dissipated_J = q[2];
      out.energy.parametric_J = q[3];
      out.energy.kinetic_J = s.kinetic;
      out.energy.potential_J = s.potential - potential0;
    }
  }
  // low-pass and decimate: output j is Σ h_k·x[j·ov + k − half], the record held at its first value before t = 0
  auto decimate = [&](const std::vector<double>& x) {
    std::vector<double> y(samples);
    for (long j = 0; j < samples; ++j) {
      double acc = 0.0;
      for (long k = 0; k < static_cast<long>(fir.size()); ++k) acc += fir[k] * x[std::max(0L, j * ov + k - half)];
      y[j] = acc;
    }
    return y;
  };
  out.pair_force_N.resize(np);
  for (std::size_t k = 0; k < np; ++k) out.pair_force_N[k] = decimate(pair[k]);
  out.mesh_torque_Nm = decimate(torque);
  out.travel_torque_Nm = decimate(travel);
  out.total_force_N = decimate(total);
  out.drive_torque_Nm = decimate(drive);
  out.deflection_rad = decimate(deflection);
  out.transmission_error_rad = decimate(te);
  long v = 0;
  CVodeGetNumSteps(mem.get(), &v); out.stats.steps = v;
  CVodeGetNumRhsEvals(mem.get(), &v); out.stats.rhs_evals = v;
  CVodeGetNumJacEvals(mem.get(), &v); out.stats.jac_evals = v;
  CVodeGetNumErrTestFails(mem.get(), &v); out.stats.error_test_fails = v;
  CVodeGetNumNonlinSolvConvFails(mem.get(), &v); out.stats.newton_fails = v;
  return out;
}

}  // namespace sw
