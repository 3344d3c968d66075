// Coulomb friction on the moving pairs' flanks: the kinematics' relative velocity at a flank (its normal part is the
// clearance's rate), a hand solution of the pairs' friction power and efficiency, the frictionless run unchanged, the
// energy and power balances with friction, the efficiency falling with μ and not depending on the friction's
// smoothing.
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <numbers>

#include <gtest/gtest.h>

#include "dynamics/analysis.hpp"
#include "dynamics/kinematic_pairs.hpp"
#include "dynamics/moving_mesh_build.hpp"
#include "dynamics/simulate.hpp"
#include "io/case.hpp"
#include "kinematics/backlash.hpp"
#include "kinematics/neutral_curve.hpp"
#include "tests/dynamics/seed_models.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEnergyTolerance = 5e-3;  // the dynamics' energy-balance limit (test_moving, test_run)
constexpr double kTorqueTolerance = 1e-3;  // its torque-balance limit

/// The generator curve of cases/mbd_26_28.toml.
NeutralCurve curve_of(const Case& c) {
  return generator_neutral_curve(rim_mean_radius(c.flexspline), radial_deformation_m(flexspline_model(c)),
                                 *c.wave_generator);
}

/// cases/mbd_26_28.toml shortened to 0.03 s (steady window from 0.022 s, after the load's ramp: 3.7 mesh periods), its
/// moving pairs on the rigid rim with the flank table every pitch/64 as the tool builds it, flanks with friction μ.
/// The 26/28 case's run, shortened, with friction coefficient mu on the flanks; its load torque scaled by load_scale.
DynamicsModel short_small_gear(double mu, double load_scale = 1.0) {
  const Case c = load_case("cases/mbd_26_28.toml");
  DynamicsParams p = *c.dynamics;
  p.load_torque_Nm *= load_scale;
  p.duration_s = 0.03;
  p.steady_from_s = 0.022;
  DynamicsModel m = make_model(*c.gear, c.flexspline, true, c.material, p, pairs_from_kinematics(flexspline_model(c)),
                               c.path);
  m.moving = std::make_shared<MovingMesh>(rigid_rim_mesh(*c.gear, curve_of(c), {}, 64));
  m.friction_coefficient = mu;
  return m;
}

// Along the flank normal the flanks' relative velocity is the clearance's rate d(clearance)/dφ, which the backlash
// module gives independently (its clearance at φ ± h): this checks the flexspline point's motion along the deformed
// curve and the circular spline's turn, the two terms the sliding along the profile is made of. The 26/28 gear
// (w0 = 1 mm), every engaged flank every 2° over ±60°. Tolerance: the clearance is solved to 1e-12 m, so its
// difference over 2h = 2e-5 rad is good to 1e-7 m/rad; the rates are 1e-5 to 1e-3 m/rad.
TEST(FlankVelocity, NormalPartIsTheClearancesRate) {
  const Case c = load_case("cases/mbd_26_28.toml");
  const BacklashModel model = make_backlash_model(*c.gear, curve_of(c));
  constexpr double h = 1e-5, kRateTolerance_m_per_rad = 1e-7;
  double worst = 0, largest_sliding = 0;
  int checked = 0;
  for (double deg = -60; deg <= 60; deg += 2) {
    const double phi = deg * kPi / 180;
    const PairClearance pc = pair_clearance(model, phi, 0.0);
    if (!pc.engaged) continue;
    const PairClearance ahead = pair_clearance(model, phi + h, 0.0), behind = pair_clearance(model, phi - h, 0.0);
    for (int side = 0; side < 2; ++side) {
      const auto flank = [side](const PairClearance& p) { return side == 0 ? p.ccw : p.cw; };
      const FlankVelocity v = flank_velocity(model, flank(pc), phi);
      const double rate = (flank(ahead).clearance_m - flank(behind).clearance_m) / (2 * h);
      worst = std::max(worst, std::abs(v.normal_m_per_rad - rate));
      largest_sliding = std::max(largest_sliding, std::abs(v.sliding_m_per_rad));
      ++checked;
    }
  }
  std::printf("%d flanks: normal part against the clearance's rate within %.2e m/rad; largest sliding %.3e m/rad\n",
              checked, worst, largest_sliding);
  EXPECT_GT(checked, 40);
  EXPECT_LT(worst, kRateTolerance_m_per_rad);
  EXPECT_GT(largest_sliding, 1e-3);  // w0 = 1 mm: the teeth slide millimetres per radian
}

// Without friction the run is the frictionless model's: the figures the code gave before the flanks had friction
// (this run, x86-64 Release), to 1e-12, with the same integrator steps, and an efficiency of exactly 1.
TEST(DynamicsFriction, WithoutFrictionEveryFigureIsUnchangedAndTheEfficiencyIsOne) {
  const DynamicsModel m = short_small_gear(0.0);
  const DynamicsSeries s = simulate(m);
  const DynamicsSummary r = summarize(m, s);
  constexpr double kSame = 1e-12;
  const double before[] = {0x1.9f18a6c4a5702p+3, 0x1.80122bf3eabeap+3, 0x1.cb49cc3122253p-1, 0x1.05515a844dbc4p-7,
                           0x1.0844eb792f6c3p-4, 0x1.f700953cb686p-11, 0x1.df4d52a0a83f6p+12, 0x1.1776145bcaf69p+7,
                           0x1.54640b7461bd8p-12, 0x1.9000a0bf6629cp+6, 0x1.22845f4c24a75p-8, 0x1.616471f3bb78p-8};
  const double now[] = {s.energy.input_J, s.energy.output_J, s.energy.dissipated_J, s.energy.kinetic_J,
                        s.energy.potential_J, r.te_peak_to_peak_rad, r.mean_total_force_N, r.lines.at(0).amplitude_N,
                        r.te_lines.at(0).amplitude_N, r.mesh_torque_Nm, r.deflection_min_rad, r.deflection_max_rad};
  for (std::size_t i = 0; i < std::size(now); ++i) EXPECT_NEAR(now[i], before[i], kSame * std::abs(before[i])) << i;
  EXPECT_EQ(s.stats.steps, 29375);
  EXPECT_EQ(s.energy.friction_J, 0.0);
  EXPECT_EQ(r.power.friction_W, 0.0);
  EXPECT_EQ(s.energy.bearing_J, 0.0);
  EXPECT_EQ(r.power.bearing_W, 0.0);
  EXPECT_EQ(r.power.efficiency, 1.0);
  EXPECT_FALSE(r.power.damping_exceeds_output);  // the contact's damping takes a few per cent of the output here
}

// The run says when the contact's damper takes more than the output delivers. The 26/28 gear at its load (100 N·m)
// delivers 13 times what its damping takes (805 W against 60 W); without load it delivers nothing while the damper
// still takes a little (5e-4 W: the mesh's stiffness variation keeps it vibrating); both printed.
TEST(DynamicsPower, TheContactDampingIsFlaggedWhenItTakesMoreThanTheOutput) {
  for (const double load_scale : {1.0, 0.0}) {
    const DynamicsModel m = short_small_gear(0.0, load_scale);
    const DynamicsSummary r = summarize(m, simulate(m));
    std::printf("load %g N·m: output %.4g W, contact damping %.4g W\n", m.params.load_torque_Nm, r.power.output_W,
                r.power.dissipated_W);
    EXPECT_EQ(r.power.damping_exceeds_output, load_scale < 1.0) << load_scale;
  }
}

// The generator bearing's friction moment M between the generator and the flexspline's rim (cs_fixed: the generator
// driven, the flexspline the output). A constant M: at steady speed its power is M·|ω_w − ω_f| with the mean speeds
// kinematic, M·ω_w·(1 + (z_c − z_f)/z_f) (tanh of the relative speed over the smoothing, 1e-3 rad/s against 113 rad/s,
// is 1 to round-off), and the output's power is the load's, so the efficiency is output / (output + M·|ω_w − ω_f|):
// to 1e-5 (measured 1.3e-6; the window's means come from the integrated works). A moment that grows with the speed
// (Palmgren's viscous term, M0 ∝ ω^(2/3)) is read at the instantaneous relative speed, which the small gear's light
// output swings between 100 and 165 rad/s: its power is then the window's mean of M(ω)·ω, checked against the sampled
// speeds to 1e-4 (the output samples' trapezoid over the window against the integrator's quadrature: measured 9e-6). Both close the
// energy and power balances within the dynamics' limits.
double bearing_power_W(const std::function<double(double)>& moment, double& sampled_W, double& output_W,
                       double& efficiency) {
  DynamicsModel m = short_small_gear(0.0);
  m.generator_moment_Nm = moment;
  const DynamicsSeries s = simulate(m);
  const DynamicsSummary r = summarize(m, s);
  const int w = static_cast<int>(BodyId::WaveGenerator), f = static_cast<int>(BodyId::FlexsplineFlange);
  double sum = 0;
  int n = 0;
  for (std::size_t i = 1; i < s.time_s.size(); ++i) {
    if (s.time_s[i - 1] < r.window_start_s) continue;
    const auto p = [&](std::size_t k) {
      const double rel = s.speed_rad_s[w][k] - s.speed_rad_s[f][k];
      return moment(std::abs(rel)) * rel;
    };
    sum += 0.5 * (p(i - 1) + p(i));
    ++n;
  }
  sampled_W = sum / n;
  output_W = r.power.output_W;
  efficiency = r.power.efficiency;
  std::printf("generator bearing: %.9g W (sampled %.9g W), efficiency %.9f; balances: energy %.2e, power %.2e\n",
              r.power.bearing_W, sampled_W, r.power.efficiency, r.energy_error_rel, r.power.balance_error_rel);
  EXPECT_LT(r.energy_error_rel, kEnergyTolerance);
  EXPECT_LT(r.power.balance_error_rel, kEnergyTolerance);
  EXPECT_EQ(s.energy.friction_J, 0.0);
  EXPECT_GT(s.energy.bearing_J, 0.0);
  return r.power.bearing_W;
}

TEST(DynamicsFriction, TheGeneratorBearingsMomentTakesItsPowerFromTheInput) {
  const DynamicsModel m = short_small_gear(0.0);
  const double w_w = m.params.drive_speed_rpm * kPi / 30;
  const double relative = w_w * (1.0 + double(m.teeth_circular - m.teeth_flexspline) / m.teeth_flexspline);
  constexpr double M = 0.2;  // N·m
  double sampled = 0, output = 0, efficiency = 0;
  const double constant_W = bearing_power_W([](double) { return M; }, sampled, output, efficiency);
  EXPECT_NEAR(constant_W, M * relative, 1e-5 * M * relative);
  EXPECT_NEAR(efficiency, output / (output + M * relative), 1e-5);
  const double viscous_W = bearing_power_W([](double v) { return M + 0.01 * std::cbrt(v * v); }, sampled, output,
                                           efficiency);
  EXPECT_NEAR(viscous_W, sampled, 1e-4 * sampled);
  EXPECT_NEAR(efficiency, output / (output + viscous_W), 1e-12);
}

/// Every tooth of a 26-tooth flexspline on the same flank geometry all the way round, ccw flanks only: gap 0, arm ℓ,
/// sliding s per unit σ̇ and the profile's arm t (per tooth).
MovingMesh uniform_mesh(int teeth, double lever_m, double sliding_m_per_rad, double tangent_arm_m) {
  MovingMesh m;
  m.teeth_flexspline = teeth;
  m.teeth_per_unknown = 2;
  m.pitch_rad = 2 * kPi / teeth;
  const double step = m.pitch_rad / 8;
  m.table = make_flank_table(-kPi / 2 - 2 * step, kPi / 2 + 2 * step, step, 2, [&](double, int side, FlankSample& f) {
    f.lever_m = lever_m;
    f.sliding_m_per_rad = sliding_m_per_rad;
    f.tangent_arm_m = tangent_arm_m;
    return side == 0;
  }, {});
  return m;
}

// A hand solution: the 26/28 gear (cs_fixed, 1000 rpm, 100 N·m) with every tooth on the same flank, so each of the
// K = 13 unknowns (a tooth and its half-turn partner, n = 2) carries the same normal force x and slides at
// v = s·σ̇, σ̇ = (z_c/z_f)·ω_w, ė = 0 at steady state. Friction F_t = −μ·x per tooth (v ≫ the smoothing); the
// flexspline's balance n·K·x·(ℓ − μ·(s − t)) = T gives x, the friction power is n·K·μ·x·v and the efficiency
// T·|ω_f| / (T·|ω_f| + n·K·μ·x·v). Tolerance 1e-9: the contact oscillation left from the load's ramp is damped out
// long before the window (0.03–0.04 s) and the window's means come from the integrated works (measured ≤ 5e-12).
TEST(DynamicsFriction, OnePairsFrictionPowerAtAKnownSlidingSpeedAndNormalForce) {
  constexpr double mu = 0.1, lever = 12.2e-3, sliding = 2.0e-3, arm = 4.0e-3, kHand = 1e-9;
  DynamicsModel m = test::small_model();
  m.params.pair_stiffness = PairStiffness::Constant;
  m.params.duration_s = 0.04;
  m.params.steady_from_s = 0.03;
  m.moving = std::make_shared<MovingMesh>(uniform_mesh(26, lever, sliding, arm));
  m.friction_coefficient = mu;
  const DynamicsSummary r = summarize(m, simulate(m));
  const double w_w = 1000 * 2 * kPi / 60, w_f = -2.0 / 26 * w_w, sigma_rate = 28.0 / 26 * w_w;
  const double n = 2, K = 13, T = 100;
  const double x = T / (n * K * (lever - mu * (sliding - arm)));
  const double v = sliding * sigma_rate;
  const double friction_W = n * K * mu * x * v;
  const double efficiency = T * std::abs(w_f) / (T * std::abs(w_f) + friction_W);
  std::printf("hand: x = %.6f N per tooth at %.6f m/s, friction %.6f W, efficiency %.8f; run: total force %.6f N, "
              "friction %.6f W, efficiency %.8f\n", x, v, friction_W, efficiency, r.mean_total_force_N,
              r.power.friction_W, r.power.efficiency);
  EXPECT_NEAR(r.mean_total_force_N, n * K * x, kHand * n * K * x);
  EXPECT_NEAR(r.power.friction_W, friction_W, kHand * friction_W);
  EXPECT_NEAR(r.power.efficiency, efficiency, kHand);
  EXPECT_NEAR(r.power.output_W, T * std::abs(w_f), kHand * T * std::abs(w_f));
}

/// The 26/28 gear's efficiency over its steady window at friction μ (smoothing v_s m/s), with its balances checked.
double efficiency_at(double mu, double smoothing_m_per_s) {
  DynamicsModel m = short_small_gear(mu);
  m.friction_smoothing_m_per_s = smoothing_m_per_s;
  const DynamicsSeries s = simulate(m);
  const DynamicsSummary r = summarize(m, s);
  std::printf("mu %.2f, smoothing %.0e m/s: efficiency %.8f (%.5g W in, %.5g W out, %.5g W friction, %.5g W damping); "
              "balances: energy %.2e, power %.2e, torque %.2e; %ld steps\n", mu, smoothing_m_per_s, r.power.efficiency,
              r.power.input_W, r.power.output_W, r.power.friction_W, r.power.dissipated_W, r.energy_error_rel,
              r.power.balance_error_rel, r.torque_balance_error_rel, s.stats.steps);
  EXPECT_LT(r.energy_error_rel, kEnergyTolerance);
  EXPECT_LT(r.power.balance_error_rel, kEnergyTolerance);
  EXPECT_LT(r.torque_balance_error_rel, kTorqueTolerance);
  EXPECT_GT(s.energy.friction_J, 0.0);
  return r.power.efficiency;
}

// The 26/28 case with friction on its flanks: the energy balance (input = output + damping + friction + kinetic +
// potential), the steady window's power balance and the torque balance close within the dynamics' limits; the
// efficiency falls with μ (1 at μ = 0, above); and it does not depend on the friction's smoothing: ten times finer
// (1e-4 m/s against the flanks' 0.1–0.5 m/s) moves it by less than 1e-6.
TEST(DynamicsFriction, BalancesCloseAndTheEfficiencyFallsWithMuNotWithTheSmoothing) {
  constexpr double kSmoothing = 1e-6;
  const double at_005 = efficiency_at(0.05, 1e-3), at_01 = efficiency_at(0.1, 1e-3);
  EXPECT_LT(at_005, 1.0);
  EXPECT_LT(at_01, at_005);
  EXPECT_NEAR(efficiency_at(0.1, 1e-4), at_01, kSmoothing);
}

}  // namespace
}  // namespace sw
