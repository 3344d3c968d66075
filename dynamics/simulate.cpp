#include "dynamics/simulate.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

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

/// Everything computed from (t, y): used by the right-hand side and by the output sampling alike.
struct Snapshot {
  std::array<double, kBodyCount> theta{}, omega{};
  double mesh_torque = 0.0, total_force = 0.0, drive_torque = 0.0, load_torque = 0.0, stiffness = 0.0;
  double kinetic = 0.0, potential = 0.0;
  double p_in = 0.0, p_out = 0.0, p_diss = 0.0, p_param = 0.0;
  std::array<double, kBodyCount> accel_dev{};  ///< v̇ of free bodies
  std::vector<double> pair_force;
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
    std::array<double, kBodyCount> Q{}, T{};
    Q[f] -= M;
    Q[c] += rho_ * M;
    Q[w] += (1.0 - rho_) * M;
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
    s.mesh_torque = M;
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
    s.pair_force.resize(m_.pairs.size());
    return s;
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
  const std::size_t np = m.pairs.size();
  out.pair_force_N.assign(np, {});
  for (auto& v : out.pair_force_N) v.reserve(samples);
  Snapshot s = ev.make_snapshot();
  auto record = [&](double t) {
    ev.evaluate(t, yv, s);
    out.time_s.push_back(t);
    for (int b = 0; b < kBodyCount; ++b) {
      out.angle_rad[b].push_back(s.theta[b]);
      out.speed_rad_s[b].push_back(s.omega[b]);
    }
    for (std::size_t i = 0; i < np; ++i) out.pair_force_N[i].push_back(s.pair_force[i]);
    out.mesh_torque_Nm.push_back(s.mesh_torque);
    out.total_force_N.push_back(s.total_force);
    out.drive_torque_Nm.push_back(s.drive_torque);
    out.load_torque_Nm.push_back(s.load_torque);
    out.stiffness_N_per_m.push_back(s.stiffness);
  };
  record(0.0);
  const double potential0 = s.potential;
  for (long i = 1; i < samples; ++i) {
    const double tout = i * p.output_step_s;
    double t = 0.0;
    const int flag = CVode(mem.get(), tout, y.get(), &t, CV_NORMAL);
    if (flag < 0) {
      std::ostringstream os;
      os << "dynamics: the integrator failed at t = " << t << " s with " << CVodeGetReturnFlagName(flag)
         << "; loosen [dynamics] relative_tolerance or check the contact stiffness and damping";
      throw InputError(os.str());
    }
    record(tout);
  }
  const double* q = yv + 2 * nfree;
  out.energy.input_J = q[0];
  out.energy.output_J = q[1];
  out.energy.dissipated_J = q[2];
  out.energy.parametric_J = q[3];
  out.energy.kinetic_J = s.kinetic;
  out.energy.potential_J = s.potential - potential0;
  long v = 0;
  CVodeGetNumSteps(mem.get(), &v); out.stats.steps = v;
  CVodeGetNumRhsEvals(mem.get(), &v); out.stats.rhs_evals = v;
  CVodeGetNumJacEvals(mem.get(), &v); out.stats.jac_evals = v;
  CVodeGetNumErrTestFails(mem.get(), &v); out.stats.error_test_fails = v;
  CVodeGetNumNonlinSolvConvFails(mem.get(), &v); out.stats.newton_fails = v;
  return out;
}

}  // namespace sw
