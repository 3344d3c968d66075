// Where the power goes (datasheet/losses.hpp): the power balance written out by hand on a small contact, the sources
// apart, the trends the catalogs state (efficiency falls with speed and at low load, rises with temperature), the
// starting torque, and the bad inputs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "datasheet/losses.hpp"
#include "tests/generator/bearings.hpp"
#include "tests/input_error.hpp"

namespace sw {
namespace {

using testing::bearing_6205;
using testing::stribeck_loads;

constexpr double kRadPerS = 2 * std::numbers::pi / 60;

/// Two loaded flanks of a half-turn pair set and one free one, at one step of 20 N·m (forces per tooth).
ContactAnalysis two_flanks(bool half_turn_pairs) {
  ContactAnalysis a;
  a.half_turn_pairs = half_turn_pairs;
  a.flanks.resize(3);
  TorqueStep s;
  s.torque_Nm = 20.0;
  s.flank_force_N = {100.0, 50.0, 0.0};
  a.steps = {s};
  return a;
}

Lubricant vg68(double temperature_C) {
  Lubricant oil;
  oil.kind = "oil";
  oil.viscosity_40C_mm2_s = 68.0;
  oil.viscosity_100C_mm2_s = 8.6;
  oil.temperature_C = temperature_C;
  return oil;
}

// Every term against the hand sum: P_out = T·ω_in/ratio, the bearing at σ̇ = ω_in(1 + 1/ratio) with Palmgren's moment
// of the same balls (generator/bearing_friction.hpp, checked there against a hand evaluation), the flanks
// Σ μ·F·teeth·|s|·σ̇. Float rounding only: 1e-12.
TEST(DriveLosses, PowerBalanceIsTheSumOfItsSourcesWrittenOutByHand) {
  const ContactAnalysis a = two_flanks(true);
  const std::vector<double> sliding = {2e-3, -1e-3, 5e-3};  // m per rad of σ
  const GeneratorBearing b = bearing_6205();
  const std::vector<double> Q = stribeck_loads(9, 1500.0, 0.0);
  LossConditions c;
  c.lubricant = vg68(40.0);
  c.input_speed_rpm = 2000.0;
  c.flank_friction = 0.08;
  const int ratio = 50;
  const LossSplit l = drive_losses(a, 0, sliding, b, Q, ratio, c);

  const double omega_in = 2000.0 * kRadPerS, sigma_rate = omega_in * (1.0 + 1.0 / ratio);
  EXPECT_NEAR(l.output_power_W, 20.0 * omega_in / ratio, 1e-12 * l.output_power_W);
  const BearingFrictionMoment m = palmgren_friction_moment(b, Q, 2000.0 * (1.0 + 1.0 / ratio), 68.0);
  EXPECT_NEAR(l.viscosity_mm2_s, 68.0, 1e-9);  // D341 through its own 40 °C point
  EXPECT_NEAR(l.bearing_viscous_W, m.viscous_Nm * sigma_rate, 1e-9 * l.bearing_viscous_W);
  EXPECT_NEAR(l.bearing_load_W, m.load_Nm * sigma_rate, 1e-9 * l.bearing_load_W);
  const double flanks = 0.08 * (100.0 * 2e-3 + 50.0 * 1e-3) * 2.0 * sigma_rate;  // two teeth per half-turn pair
  EXPECT_NEAR(l.flank_sliding_W, flanks, 1e-12 * flanks);
  EXPECT_NEAR(l.input_power_W(), l.output_power_W + l.bearing_viscous_W + l.bearing_load_W + flanks, 1e-9);
  EXPECT_NEAR(l.efficiency(), l.output_power_W / l.input_power_W(), 1e-15);
  EXPECT_NEAR(l.input_torque_Nm(), l.input_power_W() / omega_in, 1e-12);
  // One tooth per unknown (an odd z_f): half the flanks' loss, the rest unchanged.
  const LossSplit odd = drive_losses(two_flanks(false), 0, sliding, b, Q, ratio, c);
  EXPECT_NEAR(odd.flank_sliding_W, 0.5 * flanks, 1e-12 * flanks);
  EXPECT_EQ(odd.bearing_load_W, l.bearing_load_W);
}

// μ = 0: the flanks lose nothing, the bearing alone sets the efficiency; the output torque's sign does not matter.
TEST(DriveLosses, FrictionlessFlanksLoseNothingAndTheLoadsSenseDoesNotMatter) {
  ContactAnalysis a = two_flanks(true);
  const std::vector<double> sliding = {2e-3, -1e-3, 5e-3};
  LossConditions c;
  c.lubricant = vg68(20.0);
  const LossSplit l = drive_losses(a, 0, sliding, bearing_6205(), stribeck_loads(9, 1500.0, 0.0), 100, c);
  EXPECT_EQ(l.flank_sliding_W, 0.0);
  EXPECT_NEAR(l.efficiency(), l.output_power_W / (l.output_power_W + l.bearing_viscous_W + l.bearing_load_W), 1e-15);
  a.steps[0].torque_Nm = -20.0;
  EXPECT_EQ(drive_losses(a, 0, sliding, bearing_6205(), stribeck_loads(9, 1500.0, 0.0), 100, c).efficiency(),
            l.efficiency());
}

// The catalogs' trends, from the physics of the terms: the viscous moment grows as n^(2/3) (its power as n^(5/3))
// against an output power ∝ n, so the efficiency falls with speed; the bearing's moment does not fall with the load,
// so a lighter load is less efficient; a warmer oil is thinner and drags less.
TEST(DriveLosses, EfficiencyFallsWithSpeedAndAtLowLoadAndRisesWithTemperature) {
  ContactAnalysis a = two_flanks(true);
  TorqueStep half = a.steps[0];
  half.torque_Nm = 10.0;
  half.flank_force_N = {50.0, 25.0, 0.0};
  a.steps.push_back(half);
  const std::vector<double> sliding = {2e-3, -1e-3, 5e-3};
  const GeneratorBearing b = bearing_6205();
  const std::vector<double> Q = stribeck_loads(9, 1500.0, 0.0);
  LossConditions c;
  c.lubricant = vg68(20.0);
  c.flank_friction = 0.1;
  auto eta = [&](std::size_t step, double rpm, double temperature_C) {
    LossConditions at = c;
    at.input_speed_rpm = rpm;
    at.lubricant.temperature_C = temperature_C;
    return drive_losses(a, step, sliding, b, Q, 100, at).efficiency();
  };
  EXPECT_GT(eta(0, 500, 20), eta(0, 1000, 20));
  EXPECT_GT(eta(0, 1000, 20), eta(0, 3500, 20));
  EXPECT_GT(eta(0, 2000, 20), eta(1, 2000, 20));
  EXPECT_GT(eta(0, 2000, 60), eta(0, 2000, 20));
}

// The starting torque is Palmgren's breakaway moment (M1) of the same balls carried to the input by 1 + 1/ratio.
TEST(DriveLosses, StartingTorqueIsTheBreakawayMomentAtTheInput) {
  const GeneratorBearing b = bearing_6205();
  const std::vector<double> Q = stribeck_loads(9, 800.0, 0.0);
  EXPECT_NEAR(starting_torque_Nm(b, Q, 100), palmgren_breakaway_moment_Nm(b, Q) * 1.01, 1e-15);
  EXPECT_NE(sw::testing::message_of([&] { starting_torque_Nm(b, Q, 0); }).find("ratio 0; must be >= 1"),
            std::string::npos);
}

// The flexspline's material damping: harmonic n of the generator's wave strains the turning body at n·σ̇ and a
// travelling wave of energy U_n loses 2·η·n·σ̇·U_n, so P = 2·η·σ̇·Σ n·U_n; harmonic 0 is static in the body and
// loses nothing. Written out for U = (5, 0, 3, 0, 1) mJ, η = 6e-4, ratio 100: the input torque is the same at every
// speed (hysteretic damping is rate-independent), so it is in the starting torque too; η = 0 loses nothing.
TEST(DriveLosses, MaterialDampingIsTwiceEtaTimesTheWavesEnergyWeightedByHarmonic) {
  const ContactAnalysis a = two_flanks(true);
  const std::vector<double> sliding = {0, 0, 0};
  const GeneratorBearing b = bearing_6205();
  const std::vector<double> Q = stribeck_loads(9, 800.0, 0.0);
  LossConditions c;
  c.lubricant = vg68(40.0);
  c.loss_factor = 6e-4;
  c.wave_energy_J = {5e-3, 0.0, 3e-3, 0.0, 1e-3};
  const int ratio = 100;
  const double torque = 2 * 6e-4 * (1 + 1.0 / ratio) * (2 * 3e-3 + 4 * 1e-3);
  EXPECT_NEAR(damping_input_torque_Nm(c.wave_energy_J, c.loss_factor, ratio), torque, 1e-15);
  for (const double rpm : {500.0, 2000.0, 3500.0}) {
    c.input_speed_rpm = rpm;
    const LossSplit l = drive_losses(a, 0, sliding, b, Q, ratio, c);
    EXPECT_NEAR(l.flexspline_damping_W, torque * rpm * kRadPerS, 1e-12) << rpm;
    EXPECT_NEAR(l.loss_W(), l.bearing_viscous_W + l.bearing_load_W + l.flank_sliding_W + l.flexspline_damping_W,
                1e-12);
  }
  EXPECT_NEAR(starting_torque_Nm(b, Q, ratio, {}, torque), starting_torque_Nm(b, Q, ratio) + torque, 1e-15);
  c.loss_factor = 0;
  EXPECT_EQ(drive_losses(a, 0, sliding, b, Q, ratio, c).flexspline_damping_W, 0.0);
  EXPECT_EQ(sw::testing::message_of([&] { damping_input_torque_Nm(c.wave_energy_J, 1.0, ratio); }),
            "material.loss_factor = 1; must be in [0, 1)");
  EXPECT_EQ(sw::testing::message_of([&] { damping_input_torque_Nm({-1.0}, 1e-4, ratio); }),
            "damping torque: the wave's strain energy must be >= 0");
}

// The generator's outer ring on the bore: the stations' forces of the step at their curvatures, the half turn's
// partners alike (twice generator/ring_slip.hpp's torque over the listed stations), rate-independent (the same input
// torque at every speed); no curvatures, nothing counted. Written out for three stations whose middle one sticks.
TEST(DriveLosses, TheRingOnTheBoreSlipsUnderTheStationsForcesAtEverySpeed) {
  ContactAnalysis a = two_flanks(true);
  a.steps[0].station_force_N = {10.0, 30.0, 5.0};
  const std::vector<double> sliding = {0, 0, 0};
  const GeneratorBearing b = bearing_6205();
  const std::vector<double> Q = stribeck_loads(9, 800.0, 0.0);
  LossConditions c;
  c.lubricant = vg68(40.0);
  c.ring.curvature_change_per_m = {1.0, 2.0, 0.5};
  c.ring.bore_radius_m = 0.02;
  c.ring.lever_m = 1e-3;
  c.ring.friction = 0.1;
  const int ratio = 50;
  const double torque = 2 * 0.1 * (1 + 1.0 / ratio) * 0.02 * 1e-3 * (10 * 1.0 + 5 * 1.5);
  for (const double rpm : {500.0, 2000.0, 3500.0}) {
    c.input_speed_rpm = rpm;
    const LossSplit l = drive_losses(a, 0, sliding, b, Q, ratio, c);
    EXPECT_NEAR(l.ring_slip_W, torque * rpm * kRadPerS, 1e-12) << rpm;
    EXPECT_NEAR(l.loss_W(), l.bearing_viscous_W + l.bearing_load_W + l.flank_sliding_W + l.ring_slip_W, 1e-12);
  }
  c.ring.curvature_change_per_m.clear();
  EXPECT_EQ(drive_losses(a, 0, sliding, b, Q, ratio, c).ring_slip_W, 0.0);
  c.ring.curvature_change_per_m = {1.0, 2.0};  // one short of the stations
  EXPECT_EQ(sw::testing::message_of([&] { drive_losses(a, 0, sliding, b, Q, ratio, c); })
                .rfind("ring slip: stations' curvatures 2;", 0),
            0u);
}

// Backdriving: the output's power at breakaway is the input's breakaway plus the flanks' sliding, which grows with the
// torque as it does at the loaded state given. Written out: 10 N·m at 2,000 rpm losing 5 W on the flanks is
// k = 5 / (10 · 209.44 rad/s); at ratio 50 the output needs 50 · T_start / (1 − 50 k). A mesh whose flank loss per
// output torque reaches 1/ratio locks itself against the output (infinite).
TEST(DriveLosses, BackdrivingTorqueIsTheStartingTorqueThroughTheRatioAndTheFlanksInReverse) {
  LossSplit loaded;
  loaded.output_torque_Nm = -10;  // the sense of the load does not matter
  loaded.input_speed_rpm = 2000;
  loaded.flank_sliding_W = 5;
  const double omega = 2000 * 2 * M_PI / 60, k = 5 / (10 * omega);
  EXPECT_NEAR(backdriving_torque_Nm(0.02, loaded, 50), 50 * 0.02 / (1 - 50 * k), 1e-14);
  loaded.flank_sliding_W = 0;
  EXPECT_NEAR(backdriving_torque_Nm(0.02, loaded, 50), 1.0, 1e-15);  // frictionless flanks: ratio × starting
  loaded.flank_sliding_W = 10 * omega / 50;                          // k = 1/ratio
  EXPECT_TRUE(std::isinf(backdriving_torque_Nm(0.02, loaded, 50)));
  EXPECT_NE(sw::testing::message_of([&] { backdriving_torque_Nm(0.02, loaded, 0); }).find("ratio 0; must be >= 1"),
            std::string::npos);
  loaded.output_torque_Nm = 0;
  EXPECT_NE(sw::testing::message_of([&] { backdriving_torque_Nm(0.02, loaded, 50); }).find("output torque"),
            std::string::npos);
}

// The map over speed, load and temperature: each point is drive_losses at the step nearest its load (to round-off),
// and the curves keep the trends the terms make (above): along speed the efficiency falls and the no-load running
// torque rises (M0 ∝ n^(2/3)); along load the efficiency rises; with temperature the oil thins, the efficiency rises
// and the no-load running torque falls.
TEST(DriveLosses, TheMapIsThePowerBalanceAtEachPointAndKeepsTheTrends) {
  ContactAnalysis a = two_flanks(true);
  a.steps.clear();
  for (const double T : {-20.0, -10.0, -1e-6, 1e-6, 2.0, 5.0, 10.0, 15.0, 20.0}) {  // rated 20 N·m
    TorqueStep s;
    s.torque_Nm = T;
    s.flank_force_N = {std::max(T, 0.0) * 5.0, std::max(T, 0.0) * 2.5, 0.0};
    a.steps.push_back(s);
  }
  const std::vector<double> sliding = {2e-3, -1e-3, 5e-3};
  const GeneratorBearing b = bearing_6205();
  const std::vector<double> Q = stribeck_loads(9, 1500.0, 0.0);
  const LossAt at = [&](std::size_t step, const LossConditions& c) {
    return drive_losses(a, step, sliding, b, Q, 100, c);
  };
  LossConditions base;
  base.lubricant = vg68(20.0);
  base.flank_friction = 0.1;
  const LossMap m = loss_map(a, at, base);
  ASSERT_EQ(m.efficiency.size(), m.load_fractions.size());
  ASSERT_EQ(m.no_load_torque_Nm.size(), m.temperatures_C.size());
  EXPECT_EQ(m.temperature_C, 20.0);
  // The points: 10 % of rated is the 2 N·m step, rated the last; no load the 1e-6 N·m limit.
  LossConditions c = base;
  c.input_speed_rpm = 1500;
  EXPECT_NEAR(m.efficiency[0][2], at(4, c).efficiency(), 1e-15);
  EXPECT_NEAR(m.efficiency.back()[2], at(8, c).efficiency(), 1e-15);
  c.lubricant.temperature_C = -10;
  c.input_speed_rpm = 2000;
  EXPECT_NEAR(m.efficiency_at_rated[0], at(8, c).efficiency(), 1e-15);
  c.input_speed_rpm = 3500;
  EXPECT_NEAR(m.no_load_torque_Nm[0].back(), at(3, c).input_torque_Nm(), 1e-15);
  for (std::size_t k = 0; k < m.load_fractions.size(); ++k)
    for (std::size_t j = 1; j < m.speeds_rpm.size(); ++j) {
      EXPECT_LT(m.efficiency[k][j], m.efficiency[k][j - 1]) << k << " " << j;
      if (k > 0) EXPECT_GT(m.efficiency[k][j], m.efficiency[k - 1][j]) << k << " " << j;
    }
  for (std::size_t t = 1; t < m.temperatures_C.size(); ++t) {
    EXPECT_GT(m.efficiency_at_rated[t], m.efficiency_at_rated[t - 1]);
    for (std::size_t j = 0; j < m.speeds_rpm.size(); ++j) {
      EXPECT_LT(m.no_load_torque_Nm[t][j], m.no_load_torque_Nm[t - 1][j]);
      if (j > 0) EXPECT_GT(m.no_load_torque_Nm[t][j], m.no_load_torque_Nm[t][j - 1]);
    }
  }
}

TEST(DriveLosses, BadConditionsAreOneLineNamingTheField) {
  const ContactAnalysis a = two_flanks(true);
  const std::vector<double> sliding = {0, 0, 0};
  LossConditions c;
  c.lubricant = vg68(20.0);
  c.flank_friction = 1.5;
  auto message = [&](const LossConditions& at) {
    return sw::testing::message_of(
        [&] { drive_losses(a, 0, sliding, bearing_6205(), stribeck_loads(9, 800.0, 0.0), 100, at); });
  };
  EXPECT_EQ(message(c), "contact.friction_coefficient = 1.5; must be in [0, 1]");
  c.flank_friction = 0.1;
  c.input_speed_rpm = -5;
  EXPECT_EQ(message(c), "input speed -5 rpm; must be >= 0");
  c.input_speed_rpm = 2000;
  c.lubricant.kind = "butter";
  EXPECT_EQ(message(c).rfind("lubricant.kind = \"butter\"; must be \"grease\" or \"oil\"", 0), 0u) << message(c);
}

}  // namespace
}  // namespace sw
