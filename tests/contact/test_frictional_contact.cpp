// Loaded contact with Coulomb friction along a torque history: against closed-form loops, a hand solution, the
// enumeration of every contact set, the energy balance, and the frictionless contact problem.
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "contact/frictional_contact.hpp"
#include "contact/torque_twist.hpp"
#include "tests/input_error.hpp"

namespace sw {
namespace {

/// Closed forms and hand solutions agree with the solver to round-off: 1e-12 on these problems; 1e-9 leaves room for
/// the dense solves' round-off on worse-conditioned compliances.
constexpr double kExact = 1e-9;

/// A problem of n contacts with block-diagonal compliance: per contact a normal compliance a_i, a tangential c_i,
/// their coupling b_i; gaps g_i; arms λ_i, λt_i; one friction coefficient.
struct ContactSpec {
  double a, b, c, gap, lambda_n, lambda_t, mu;
};
FrictionalContactProblem independent_contacts(const std::vector<ContactSpec>& specs) {
  const auto n = static_cast<Eigen::Index>(specs.size());
  FrictionalContactProblem p;
  p.A = p.A_tn = p.A_tt = Eigen::MatrixXd::Zero(n, n);
  p.q.resize(n);
  p.lambda.resize(n);
  p.lambda_t.resize(n);
  p.friction_coefficient.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const ContactSpec& s = specs[i];
    p.A(i, i) = s.a;
    p.A_tn(i, i) = s.b;
    p.A_tt(i, i) = s.c;
    p.q[i] = s.gap;
    p.lambda[i] = s.lambda_n;
    p.lambda_t[i] = s.lambda_t;
    p.friction_coefficient[i] = s.mu;
  }
  return p;
}

/// Both flanks of the teeth of a mesh zone on a rim (radius R, pressure angle α): `teeth` teeth over ±25°, each flank
/// a contact at the tooth's angle θ with its normal n (the circular spline's push, against the turn that closes it)
/// and its tangent t along the profile. The rim's compliance couples them as exp(−|θ_a − θ_b|/w)·(d_a·d_b) (d the
/// force's direction: a positive definite kernel times a Gram matrix, so positive semidefinite), the tooth pair's own
/// in series on each contact's 2 × 2 block. Gaps grow from the zone's middle to its edges (progressive engagement).
FrictionalContactProblem rim_problem(int teeth, double mu, double gap0 = 0.5e-6) {
  constexpr double R = 0.03, alpha = 20 * M_PI / 180, c_rim = 2e-9, width_rad = 0.3;
  constexpr double c_n = 3e-9, c_t = 4e-9, c_nt = 1e-9, gap_edge = 6e-6;
  const int n = 2 * teeth;
  std::vector<double> theta(n);
  std::vector<Eigen::Vector2d> dn(n), dt(n);
  FrictionalContactProblem p;
  p.q.resize(n);
  p.lambda.resize(n);
  p.lambda_t.resize(n);
  for (int i = 0; i < n; ++i) {
    const double th = (25 * M_PI / 180) * (teeth > 1 ? 2.0 * (i / 2) / (teeth - 1) - 1 : 0.0), side = i % 2 ? -1 : 1;
    const Eigen::Vector2d er(std::cos(th), std::sin(th)), et(-std::sin(th), std::cos(th));
    theta[i] = th;
    dn[i] = -side * std::cos(alpha) * et + std::sin(alpha) * er;
    dt[i] = std::sin(alpha) * et + side * std::cos(alpha) * er;
    p.lambda[i] = -R * et.dot(dn[i]);  // a turn ψ moves the point by ψ·R·e_θ: −λψ along n
    p.lambda_t[i] = -R * et.dot(dt[i]);
    p.q[i] = gap0 + gap_edge * std::pow(th / (25 * M_PI / 180), 2) + (i % 2) * 1e-6;
  }
  const auto block = [&](const std::vector<Eigen::Vector2d>& da, const std::vector<Eigen::Vector2d>& db) {
    Eigen::MatrixXd C(n, n);
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        C(a, b) = c_rim * std::exp(-std::abs(theta[a] - theta[b]) / width_rad) * da[a].dot(db[b]);
    return C;
  };
  p.A = block(dn, dn) + c_n * Eigen::MatrixXd::Identity(n, n);
  p.A_tn = block(dt, dn) + c_nt * Eigen::MatrixXd::Identity(n, n);
  p.A_tt = block(dt, dt) + c_t * Eigen::MatrixXd::Identity(n, n);
  p.friction_coefficient = Eigen::VectorXd::Constant(n, mu);
  return p;
}

Eigen::MatrixXd block_compliance(const FrictionalContactProblem& p) {
  const Eigen::Index n = p.q.size();
  Eigen::MatrixXd C(2 * n, 2 * n);
  C << p.A, p.A_tn.transpose(), p.A_tn, p.A_tt;
  return C;
}

/// The worst violation of Coulomb's conditions by `s` after `prev`, relative to the step's scales: equilibrium,
/// p ≥ 0, g ≥ 0, p·g = 0, |q| ≤ μp, stick (|q| < μp ⇒ Δs = 0), slip (q = −μp·sign Δs). Written apart from the solver.
double coulomb_violation(const FrictionalContactProblem& p, const FrictionalStep& prev, const FrictionalStep& s) {
  const Eigen::Index n = p.q.size();
  Eigen::VectorXd f(2 * n);
  f << s.normal_force_N, s.tangential_force_N;
  const Eigen::VectorXd u = block_compliance(p) * f;
  const Eigen::VectorXd gap = p.q + u.head(n) - p.lambda * s.twist_rad;
  const Eigen::VectorXd ds = u.tail(n) - p.lambda_t * s.twist_rad - prev.slip_m;
  const double F = std::abs(s.torque_Nm) / p.lambda.cwiseAbs().maxCoeff() + f.cwiseAbs().maxCoeff();
  const double D = F * block_compliance(p).diagonal().maxCoeff() + p.q.cwiseAbs().maxCoeff();
  double worst = std::abs(p.lambda.dot(s.normal_force_N) + p.lambda_t.dot(s.tangential_force_N) - s.torque_Nm) /
                 std::abs(s.torque_Nm);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double pn = s.normal_force_N[i], qt = s.tangential_force_N[i], bound = p.friction_coefficient[i] * pn;
    worst = std::max({worst, -pn / F, -gap[i] / D, std::min(pn / F, std::abs(gap[i]) / D), (std::abs(qt) - bound) / F});
    if (pn > 0 && std::abs(qt) < bound * (1 - 1e-9)) worst = std::max(worst, std::abs(ds[i]) / D);  // stick
    if (pn > 0 && std::abs(ds[i]) > 1e-12 * D)
      worst = std::max(worst, std::abs(qt + bound * (ds[i] > 0 ? 1 : -1)) / F);  // slip
  }
  return worst;
}

// ---- Two Coulomb sliders with springs: Masing's closed-form loop ------------------------------------------------

/// x ≥ 0 with f(x) = y, f increasing (bisection to round-off).
template <class F>
double inverse(F f, double y) {
  double lo = 0, hi = 1;
  while (f(hi) < y) hi *= 2;
  for (int k = 0; k < 200; ++k) (f(0.5 * (lo + hi)) < y ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

// Two preloaded frictionless contacts of opposite arms are a torsion spring K = 2r²/a; two preloaded contacts with no
// normal arm (their normal force fixed at δ/a) and a tangential arm r are Jenkins elements: a spring k = r²/c in series
// with a Coulomb slider that slips at τ = r·μ·δ/a. In parallel, their loop is Masing's: the virgin curve
// T = Kψ + Σ min(kψ, τ), and from a reversal at (ψ_a, T_a) the branch T_a ∓ [Kx + Σ min(kx, 2τ)] with x = |ψ − ψ_a|.
// Each load step is monotone in ψ and the elements are piecewise linear, so the incremental solution lies on the
// loop to round-off.
TEST(FrictionalContact, TwoCoulombSlidersFollowMasingsLoop) {
  const double r = 0.02, a = 1e-9, mu = 0.1, T_R = 10;
  const double K = 2 * r * r / a;
  const double c = r * r / K;  // each slider's spring as stiff as the torsion spring
  const FrictionalContactProblem p = independent_contacts({{a, 0, c, -1e-6, r, 0, 0},
                                                           {a, 0, c, -1e-6, -r, 0, 0},
                                                           {a, 0, c, -1.00e-6, 0, r, mu},
                                                           {a, 0, c, -1.75e-6, 0, r, mu}});
  const double k = r * r / c, tau[2] = {r * mu * 1.00e-6 / a, r * mu * 1.75e-6 / a};
  const auto virgin = [&](double x) { return K * x + std::min(k * x, tau[0]) + std::min(k * x, tau[1]); };
  const auto swing = [&](double x) { return K * x + std::min(k * x, 2 * tau[0]) + std::min(k * x, 2 * tau[1]); };
  const double psi_a = inverse(virgin, T_R);
  ASSERT_GT(k * psi_a, tau[1]);  // both sliders slip at rated torque (the test's premise)
  const std::vector<double> T = cycle_torque_history(T_R, 8);
  const std::vector<FrictionalStep> h = solve_torque_history(p, T);
  bool down = false, up = false;
  for (std::size_t i = 0; i < T.size(); ++i) {
    down = down || (i > 0 && T[i] < T[i - 1]);
    up = down && (up || T[i] > T[i - 1]);
    const double expected = !down ? inverse(virgin, T[i])
                            : !up ? psi_a - inverse(swing, T_R - T[i])
                                  : -psi_a + inverse(swing, T[i] + T_R);
    EXPECT_NEAR(h[i].twist_rad, expected, kExact * psi_a) << "step " << i << ", " << T[i] << " N·m";
  }
  // Masing's loop dissipates 4τ(ψ_a − τ/k) per slider; the trapezoids cut the corners where a slider starts slipping
  // inside a step, the friction work (q constant while slipping) does not.
  const LoopReading loop = read_loop(h, T_R);
  const double dissipated = 4 * tau[0] * (psi_a - tau[0] / k) + 4 * tau[1] * (psi_a - tau[1] / k);
  EXPECT_NEAR(loop.friction_work_J, dissipated, kExact * dissipated);
  EXPECT_NEAR(loop.dissipated_energy_J, dissipated, 0.05 * dissipated);
  // At zero torque the branches are 2·x apart, swing(x) = T_R.
  EXPECT_NEAR(loop.hysteresis_loss_rad, 2 * (psi_a - inverse(swing, T_R)), kExact * psi_a);
  // No dead band: a rig reads the same gap, less the branches' own twist between the limits at zero torque (±1e-6 of
  // T_R, at a slope below ψ_a/T_R each).
  EXPECT_NEAR(loop.rig_hysteresis_loss_rad, loop.hysteresis_loss_rad, 2 * kZeroTorqueLimit * psi_a);
  // Masing's swing is concave (the sliders soften it) and straight once both slip, so the width is largest, and flat,
  // about zero torque: the loop is as wide there as anywhere, and narrower at the corners' side of the flat.
  EXPECT_NEAR(loop.widest.width_rad, loop.hysteresis_loss_rad, kExact * psi_a);
  EXPECT_GE(loop.widest.torque_Nm, 0.0);
  EXPECT_LT(loop_width_rad(loop.loop, 0.75 * T_R), (1 - 1e-3) * loop.widest.width_rad);
}

// ---- A tooth pair: both flanks of one tooth, with play, against a hand solution ---------------------------------

// One flank carries at a time (the other is open across the play). On the closed flank, with s_prev its slip at the
// step's start: stick solves gap = 0, Δs = 0 and equilibrium (3 × 3); when that needs |q| > μp the flank slips the
// way q pulls: p = T/(λ + σμλt), q = σμp, ψ = (g + (a + bσμ)p)/λ. The open flank moves with the rigid turn: s = −λt·ψ.
TEST(FrictionalContact, ToothPairMatchesHandSolution) {
  const double R = 0.03, alpha = 25 * M_PI / 180, mu = 0.15, T_R = 40;
  const double a = 6e-9, b = 1.5e-9, c = 8e-9, ln = R * std::cos(alpha), lt = -R * std::sin(alpha);
  const double gap[2] = {2e-6, 3e-6}, arm[2] = {ln, -ln};
  const FrictionalContactProblem p =
      independent_contacts({{a, b, c, gap[0], arm[0], lt, mu}, {a, b, c, gap[1], arm[1], lt, mu}});
  const std::vector<double> T = cycle_torque_history(T_R, 3);
  const std::vector<FrictionalStep> h = solve_torque_history(p, T);
  double slip[2] = {0, 0};
  int sticks = 0, slips = 0;
  for (std::size_t i = 0; i < T.size(); ++i) {
    const int f = T[i] > 0 ? 0 : 1;
    Eigen::Matrix3d M;
    M << a, b, -arm[f], b, c, -lt, arm[f], lt, 0;
    const Eigen::Vector3d stick = M.inverse() * Eigen::Vector3d(-gap[f], slip[f], T[i]);
    double pn = stick[0], qt = stick[1], psi = stick[2];
    const double sigma = qt > 0 ? 1 : -1, before = slip[f];
    const bool slipping = std::abs(qt) > mu * pn;
    if (slipping) {
      pn = T[i] / (arm[f] + sigma * mu * lt);
      qt = sigma * mu * pn;
      psi = (gap[f] + (a + b * sigma * mu) * pn) / arm[f];
    }
    slip[f] = b * pn + c * qt - lt * psi;
    if (slipping) EXPECT_LE(sigma * (slip[f] - before), 0.0);  // the hand rule's slip opposes its force
    (slipping ? slips : sticks) += 1;
    slip[1 - f] = -lt * psi;
    ASSERT_GT(gap[1 - f] - arm[1 - f] * psi, 0.0);  // the other flank open (the hand solution's premise)
    EXPECT_NEAR(h[i].twist_rad, psi, kExact * std::abs(psi)) << "step " << i;
    EXPECT_NEAR(h[i].normal_force_N[f], pn, kExact * pn) << "step " << i;
    EXPECT_NEAR(h[i].tangential_force_N[f], qt, kExact * pn) << "step " << i;
    EXPECT_EQ(h[i].normal_force_N[1 - f], 0.0);
    EXPECT_EQ(h[i].state[f], std::abs(qt) < mu * pn ? ContactState::Stick : ContactState::Slip) << "step " << i;
  }
  EXPECT_GT(sticks, 0);  // the history visits both laws
  EXPECT_GT(slips, 0);
}

// ---- Every contact set against the solver ---------------------------------------------------------------------

// Three coupled contacts (a random positive definite block compliance): each of the 4³ assignments of open, stick,
// slip+ and slip− gives a linear system; exactly one of its solutions meets every condition of Coulomb's law on the
// increment (small μ: the increment's solution is unique), and it is the solver's.
TEST(FrictionalContact, StepMatchesEnumerationOfContactSets) {
  const int n = 3;
  std::srand(7);
  const Eigen::MatrixXd B = Eigen::MatrixXd::Random(2 * n, 2 * n);
  const Eigen::MatrixXd C = (B * B.transpose() + 2 * n * Eigen::MatrixXd::Identity(2 * n, 2 * n)) * 1e-9;
  FrictionalContactProblem p;
  p.A = C.topLeftCorner(n, n);
  p.A_tn = C.bottomLeftCorner(n, n);
  p.A_tt = C.bottomRightCorner(n, n);
  p.q = Eigen::Vector3d(0.5e-6, 1e-6, 2e-6);
  p.lambda = Eigen::Vector3d(0.02, 0.025, -0.02);
  p.lambda_t = Eigen::Vector3d(-0.008, 0.01, -0.006);
  p.friction_coefficient = Eigen::Vector3d(0.2, 0.15, 0.2);
  const FrictionalStep first = solve_frictional_step(p, 30.0, unloaded_state(p));
  for (const double T : {20.0, 45.0}) {
    const FrictionalStep s = solve_frictional_step(p, T, first);
    EXPECT_LT(coulomb_violation(p, first, s), 1e-10);
    int valid = 0;
    for (int code = 0; code < 64; ++code) {
      Eigen::MatrixXd K = Eigen::MatrixXd::Zero(2 * n + 1, 2 * n + 1);
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * n + 1);
      for (int i = 0, c = code; i < n; ++i, c /= 4) {
        const int law = c % 4;  // 0 open, 1 stick, 2 slip with q = +μp, 3 slip with q = −μp
        if (law == 0) {
          K(i, i) = K(n + i, n + i) = 1;
          continue;
        }
        K.row(i).head(2 * n) = C.row(i);  // gap = 0
        K(i, 2 * n) = -p.lambda[i];
        rhs[i] = -p.q[i];
        if (law == 1) {  // Δs = 0
          K.row(n + i).head(2 * n) = C.row(n + i);
          K(n + i, 2 * n) = -p.lambda_t[i];
          rhs[n + i] = first.slip_m[i];
        } else {
          K(n + i, n + i) = 1;
          K(n + i, i) = law == 2 ? -p.friction_coefficient[i] : p.friction_coefficient[i];
        }
      }
      K.row(2 * n).head(2 * n) << p.lambda.transpose(), p.lambda_t.transpose();
      rhs[2 * n] = T;
      const Eigen::VectorXd z = K.fullPivLu().solve(rhs);
      FrictionalStep e;
      e.torque_Nm = T;
      e.twist_rad = z[2 * n];
      e.normal_force_N = z.head(n);
      e.tangential_force_N = z.segment(n, n);
      if (!z.allFinite() || coulomb_violation(p, first, e) > 1e-9) continue;
      ++valid;
      EXPECT_NEAR(s.twist_rad, e.twist_rad, kExact * std::abs(e.twist_rad));
      EXPECT_LT((s.normal_force_N - e.normal_force_N).cwiseAbs().maxCoeff(), kExact * T / 0.02);
      EXPECT_LT((s.tangential_force_N - e.tangential_force_N).cwiseAbs().maxCoeff(), kExact * T / 0.02);
    }
    EXPECT_EQ(valid, 1) << "at " << T << " N·m";
  }
}

// ---- The loop of a mesh zone ----------------------------------------------------------------------------------

constexpr double kRated = 30;
/// The zone's middle tooth overlaps its partner by this much at rest: the mesh is preloaded (no play), both flanks of
/// the middle teeth closed at zero torque, as a drive without backlash.
constexpr double kPreloadGap = -1.5e-6;

/// The steady loop of `p` at N steps a quarter.
SteadyLoop steady_loop(const FrictionalContactProblem& p, int N) {
  return run_steady_loop(frictional_step_of(p), unloaded_state(p), kRated, N);
}

// Every step of the loop, for each friction coefficient, with play and preloaded, meets Coulomb's conditions to
// round-off: the fixed point converged, in few passes, from the previous step's sets.
TEST(FrictionalContact, EveryStepOfTheLoopMeetsCoulombsLaw) {
  for (const double gap0 : {0.5e-6, kPreloadGap})
    for (const double mu : {0.02, 0.1, 0.2, 0.4}) {
      const FrictionalContactProblem p = rim_problem(7, mu, gap0);
      const std::vector<FrictionalStep> h = solve_torque_history(p, cycle_torque_history(kRated, 10));
      FrictionalStep prev = unloaded_state(p);
      int most_passes = 0, slipping = 0, sticking = 0;
      for (const FrictionalStep& s : h) {
        EXPECT_LT(coulomb_violation(p, prev, s), 1e-10) << "μ = " << mu << " at " << s.torque_Nm << " N·m";
        most_passes = std::max(most_passes, s.passes);
        slipping += s.count(ContactState::Slip);
        sticking += s.count(ContactState::Stick);
        prev = s;
      }
      EXPECT_LE(most_passes, 6) << "μ = " << mu;
      EXPECT_GT(slipping, 0);
      EXPECT_GT(sticking, 0);
    }
}

// Without friction the step is the frictionless contact problem: solve_contact's twist and forces at every step, to
// round-off of the loop's largest force (the two factorise differently; at the steps next to zero torque the forces
// are themselves of that order).
TEST(FrictionalContact, WithoutFrictionEqualsSolveContact) {
  for (const double gap0 : {0.5e-6, kPreloadGap}) {
    const FrictionalContactProblem p = rim_problem(7, 0.0, gap0);
    const std::vector<double> T = cycle_torque_history(kRated, 10);
    const std::vector<FrictionalStep> h = solve_torque_history(p, T);
    const double force_scale = solve_contact(p, kRated).force_N.maxCoeff();
    for (std::size_t i = 0; i < T.size(); ++i) {
      const ContactSolution s = solve_contact(p, T[i]);
      EXPECT_NEAR(h[i].twist_rad, s.twist_rad, 1e-12 * std::abs(s.twist_rad)) << "step " << i;
      EXPECT_LE((h[i].normal_force_N - s.force_N).cwiseAbs().maxCoeff(), 1e-12 * force_scale) << "step " << i;
      EXPECT_EQ(h[i].tangential_force_N.cwiseAbs().maxCoeff(), 0.0);
    }
    const LoopReading r = read_loop(h, kRated);
    EXPECT_EQ(r.hysteresis_loss_rad, 0.0);
    EXPECT_EQ(r.friction_work_J, 0.0);
    EXPECT_NEAR(r.dissipated_energy_J, 0.0, 1e-12 * kRated * h.back().twist_rad);
  }
}

// The power balance T ψ̇ = d(½fᵀCf)/dt + Σ|q||ṡ|: over a closed (steady) cycle the loop's area is the friction work.
// The discrete loop meets it to O(step): 1 % at 40 steps a quarter.
TEST(FrictionalContact, LoopAreaEqualsFrictionWork) {
  const LoopReading r = steady_loop(rim_problem(7, 0.1, kPreloadGap), 40).reading;
  ASSERT_GT(r.friction_work_J, 0.0);
  EXPECT_NEAR(r.dissipated_energy_J / r.friction_work_J, 1.0, 0.01);
}

// With play the loop is steady after the first loading: the second cycle's states are the first's.
TEST(FrictionalContact, SecondCycleEqualsTheFirst) {
  for (const double mu : {0.05, 0.1, 0.2}) {
    const FrictionalContactProblem p = rim_problem(7, mu);
    const int N = 10;
    const std::vector<FrictionalStep> h = solve_torque_history(p, cycle_torque_history(kRated, N, 2));
    const std::size_t start = N + 1, cycle = 4 * N + 2;  // the first loading's points; a cycle's: two limits at zero
    ASSERT_EQ(h.size(), start + 2 * cycle);
    const double twist_scale = std::abs(h[N].twist_rad);
    for (std::size_t k = 0; k < cycle; ++k) {
      const FrictionalStep &one = h[start + k], &two = h[start + cycle + k];
      ASSERT_EQ(one.torque_Nm, two.torque_Nm);
      EXPECT_NEAR(one.twist_rad, two.twist_rad, 1e-6 * twist_scale) << "μ = " << mu << ", point " << k;
      EXPECT_LE((one.tangential_force_N - two.tangential_force_N).cwiseAbs().maxCoeff(),
                1e-6 * one.normal_force_N.cwiseAbs().maxCoeff());
    }
  }
}

// Preloaded, the middle teeth's flanks both closed, the normal and tangential forces coupled: the cycles shake down
// to a steady one, each changing less than the one before; the first cycle's loss is within 0.1 % of the steady.
TEST(FrictionalContact, CoupledLoopShakesDownToASteadyCycle) {
  const FrictionalContactProblem p = rim_problem(7, 0.1, kPreloadGap);
  const SteadyLoop loop = steady_loop(p, 10);
  EXPECT_LE(loop.top_change_rel, 1e-6);
  EXPECT_GT(loop.cycles, 2);  // the premise: this problem does shake down
  EXPECT_LT(loop.cycles, 10);
  const std::size_t first = 11, cycle = 42;
  double last_change = std::numeric_limits<double>::infinity();
  for (int c = 1; c < loop.cycles; ++c) {
    double change = 0;
    for (std::size_t k = 0; k < cycle; ++k)
      change = std::max(change, std::abs(loop.history[first + c * cycle + k].twist_rad -
                                         loop.history[first + (c - 1) * cycle + k].twist_rad));
    EXPECT_LT(change, 0.5 * last_change) << "cycle " << c;
    last_change = change;
  }
  const std::vector<FrictionalStep> one(loop.history.begin(), loop.history.begin() + first + cycle);
  EXPECT_NEAR(read_loop(one, kRated).hysteresis_loss_rad / loop.reading.hysteresis_loss_rad, 1.0, 1e-3);
}

// More friction, a wider loop at zero torque: the hysteresis loss of the preloaded mesh grows with μ, from zero
// without friction.
TEST(FrictionalContact, LossGrowsWithFriction) {
  double last = -1;
  for (const double mu : {0.0, 0.02, 0.05, 0.1, 0.2}) {
    const double loss = steady_loop(rim_problem(7, mu, kPreloadGap), 10).reading.hysteresis_loss_rad;
    if (mu == 0) EXPECT_EQ(loss, 0.0);
    EXPECT_GT(loss, last) << "μ = " << mu;
    last = loss;
  }
}

// With play, every flank's normal arm outweighs μ times its tangential one (λ > μ|λt|), so the flanks of one side
// cannot hold each other's forces at zero torque: they unload and the loop closes there (its loss is that of the
// limits' ±1e-6·T_R), though it dissipates and is wide between.
TEST(FrictionalContact, LoopWithPlayClosesAtZeroTorque) {
  const FrictionalContactProblem p = rim_problem(7, 0.2);
  ASSERT_GT((p.lambda.cwiseAbs() - 0.2 * p.lambda_t.cwiseAbs()).minCoeff(), 0.0);
  const LoopReading r = steady_loop(p, 10).reading;
  const double width = loop_width_rad(r.loop, 0.5 * kRated);
  EXPECT_GT(width, 0.0);
  EXPECT_GT(r.dissipated_energy_J, 0.0);
  EXPECT_LT(std::abs(r.hysteresis_loss_rad), 1e-5 * width);
  // A lens: widest between zero torque and the corners, and no narrower than at half the rated torque.
  EXPECT_GE(r.widest.width_rad, width);
  EXPECT_GT(r.widest.torque_Nm, 0.0);
  EXPECT_LT(r.widest.torque_Nm, kRated);
  EXPECT_NEAR(r.widest.width_rad, loop_width_rad(r.loop, r.widest.torque_Nm), 1e-15);
}

// Halving the step converges the loop: the friction work's changes shrink by about half per level (first order: a
// contact that closes or opens inside a step), and the loss has settled to 1e-3 at the finest levels.
TEST(FrictionalContact, StepStudyConverges) {
  const FrictionalContactProblem p = rim_problem(7, 0.1, kPreloadGap);
  const std::vector<StepStudyLevel> study = loop_step_study(frictional_step_of(p), unloaded_state(p), kRated, 5, 5);
  ASSERT_EQ(study.size(), 5u);
  std::vector<double> work_change;
  for (std::size_t k = 1; k < study.size(); ++k) {
    EXPECT_EQ(study[k].steps_per_quarter, 5 << k);
    work_change.push_back(std::abs(study[k].loop.reading.friction_work_J - study[k - 1].loop.reading.friction_work_J));
  }
  for (std::size_t k = 1; k < work_change.size(); ++k)
    EXPECT_LT(work_change[k], 0.75 * work_change[k - 1]) << "level " << k;
  const double fine = study[4].loop.reading.hysteresis_loss_rad, coarser = study[3].loop.reading.hysteresis_loss_rad;
  EXPECT_NEAR(coarser / fine, 1.0, 1e-3);
  const int N = converged_steps_per_quarter(study, 1e-3);
  EXPECT_GE(N, 5);
  EXPECT_LE(N, 40);
}

// ---- Bad input ------------------------------------------------------------------------------------------------

using sw::testing::message_of;

TEST(FrictionalContact, NegativeFrictionCoefficientIsRefused) {
  FrictionalContactProblem p = rim_problem(2, 0.1);
  p.friction_coefficient[3] = -0.05;
  const std::string m = message_of([&] { solve_frictional_step(p, 10.0, unloaded_state(p)); });
  EXPECT_NE(m.find("friction_coefficient = -0.05 at contact 3; must be"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos);
}

// A history step of a sign no flank can carry (every normal arm positive): refused, naming the step and its torque.
TEST(FrictionalContact, StepThatCannotBeCarriedIsRefused) {
  FrictionalContactProblem p = rim_problem(3, 0.1);
  p.lambda = p.lambda.cwiseAbs();
  const std::string m = message_of([&] { solve_torque_history(p, {10.0, 5.0, -5.0}); });
  EXPECT_NE(m.find("torque history step 2 (-5 N·m): contact: no tooth flank can carry"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos);
}

// ---- The loop's readings on a hand-made loop ------------------------------------------------------------------

// A loop with a dead band: branches of slope 1/K shifted by ±h/2 in twist, play 2d at zero torque, meeting at the
// corners ±T_R. Its hysteresis loss is h (2d + h as a rig reads it), its middle line the curve without the shift
// (lost motion 2d + 2·0.04·T_R/K).
TEST(TorqueLoop, ParallelogramLoopReadings) {
  const double K = 1e4, h = 2e-4, d = 1e-4, T_R = 20, eps = 1e-6 * T_R;
  std::vector<double> T, psi;
  const auto point = [&](double t, bool unloading) {  // the limits at zero: the twist at T = 0 from either side
    T.push_back(t);
    psi.push_back((std::abs(t) > eps ? t / K : 0.0) + (t > 0 ? d : -d) + (unloading ? h / 2 : -h / 2));
  };
  for (const double t : {T_R, 10.0, eps, -eps, -10.0, -T_R}) point(t, true);
  for (const double t : {-10.0, -eps, eps, 10.0, T_R}) point(t, false);
  psi.front() = T_R / K + d;  // the top and the bottom are both branches' (the loop's corners)
  psi[5] = -T_R / K - d;
  psi.back() = psi.front();
  const LoadCycle c = last_load_cycle(T);
  EXPECT_EQ(c.top, 0u);
  EXPECT_EQ(c.bottom, 5u);
  const TorqueLoop loop = loop_branches(T, psi, c, 1e-3 * T_R);
  EXPECT_EQ(loop.unloading.torque_Nm, (std::vector<double>{-T_R, -10, 0, 0, 10, T_R}));
  EXPECT_NEAR(hysteresis_loss_rad(loop), h, 1e-15);
  // A rig stays at the dead band's edge it arrives at: from +T_R at d + h/2, from −T_R at −d − h/2.
  EXPECT_NEAR(rig_hysteresis_loss_rad(loop), 2 * d + h, 1e-15);
  // A band h wide between ±10 N·m, and a triangle of base h to each corner at ±T_R, where the branches meet.
  EXPECT_NEAR(loop_area_J(loop), 20 * h + 2 * 0.5 * h * (T_R - 10), 1e-12);
  EXPECT_NEAR(lost_motion_rad(middle_line(loop.loading, loop.unloading), T_R), 2 * d + 0.08 * T_R / K, 1e-12);
  // h wide at −10, 0 and +10 N·m (a tie): the widest place named at the largest of them.
  const LoopWidth widest = widest_loop_width(loop);
  EXPECT_NEAR(widest.width_rad, h, 1e-15);
  EXPECT_EQ(widest.torque_Nm, 10.0);
  EXPECT_THROW(last_load_cycle({1.0, -1.0, 0.0, -0.5, 1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace sw
