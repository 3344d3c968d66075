// Unit tests of the dynamics model's parts: ramps, kinematic relations, mesh frequency, contact law, quasi-static load
// sharing, inertias and the stand-in clearances. Each is checked against a closed form.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "dynamics/model.hpp"
#include "dynamics/run_summary.hpp"
#include "dynamics/simulate.hpp"
#include "tests/dynamics/seed_models.hpp"

using namespace sw;

namespace {
constexpr double kPi = std::numbers::pi;
constexpr double kRoundoff = 1e-12;        // closed forms evaluated in double: a few ulps, scaled
constexpr double kFiniteDifference = 1e-6; // central differences with h = 1e-6 of the ramp time: O(h²) + roundoff/h
}  // namespace

TEST(DynamicsRamp, PaperStepIsContinuousWithContinuousSlopeAndReachesOne) {
  const double t0 = 0.002, t1 = 0.012, mid = 0.007, h = 1e-9;
  for (RampShape shape : {RampShape::Paper, RampShape::Cubic}) {
    EXPECT_EQ(ramp(shape, t0 - 1e-3, t0, t1), 0.0);
    EXPECT_EQ(ramp(shape, t1 + 1e-3, t0, t1), 1.0);
    EXPECT_NEAR(ramp(shape, mid, t0, t1), 0.5, kRoundoff);
    EXPECT_NEAR(ramp(shape, mid - h, t0, t1), ramp(shape, mid + h, t0, t1), 1e-6);
    EXPECT_NEAR(ramp_rate(shape, mid - h, t0, t1), ramp_rate(shape, mid + h, t0, t1), 1e-3);
  }
  // The printed formula's second half, 1 − ½((t − t1)/(t2 − t1))², would jump from ½ to 1 at the midpoint: ours does not.
  EXPECT_NEAR(ramp(RampShape::Paper, mid + 1e-7, t0, t1), 0.5, 1e-4);
}

TEST(DynamicsRamp, RateAndIntegralAreTheDerivativeAndTheIntegralOfTheValue) {
  const double t0 = 0.0, t1 = 0.01;
  for (RampShape shape : {RampShape::Paper, RampShape::Cubic}) {
    double integral = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const double t = (i + 0.5) * 0.015 / n;
      integral += ramp(shape, t, t0, t1) * 0.015 / n;
      const double h = 1e-6 * (t1 - t0);
      if (std::abs(t - 0.005) > 2 * h)  // skip the paper ramp's kink in the second derivative
        EXPECT_NEAR(ramp_rate(shape, t, t0, t1),
                    (ramp(shape, t + h, t0, t1) - ramp(shape, t - h, t0, t1)) / (2 * h), kFiniteDifference / (t1 - t0) * 10);
    }
    EXPECT_NEAR(ramp_integral(shape, 0.015, t0, t1), integral, 1e-9);  // midpoint rule, n = 20000
    EXPECT_NEAR(ramp_integral(shape, 0.015, t0, t1), 0.5 * (t1 - t0) + 0.005, kRoundoff);
  }
}

TEST(DynamicsKinematics, EveryConfigurationSatisfiesTheMeshRelationAndTheTextbookRatios) {
  const double n = 1000.0, w = n * 2 * kPi / 60;
  for (auto cfg : {DynamicsConfiguration::CsFixed, DynamicsConfiguration::FsFixed, DynamicsConfiguration::WgFixed,
                   DynamicsConfiguration::AllFree}) {
    const auto m = test::seed_model(cfg);
    const SteadyState s = steady_state(m);
    const double ww = s.speed_rad_s[0], wf = s.speed_rad_s[2], wc = s.speed_rad_s[3];
    EXPECT_NEAR(190 * (wf - ww), 192 * (wc - ww), kRoundoff * w) << to_string(cfg);
    EXPECT_NEAR(s.mesh_frequency_Hz, 190 * std::abs(wf - ww) / (2 * kPi), kRoundoff * 1e4);
  }
  // cs_fixed: reduction z_f/(z_c − z_f) = 95, reversed; f_m = z_c·n/60.
  auto s = steady_state(test::seed_model(DynamicsConfiguration::CsFixed));
  EXPECT_NEAR(s.speed_rad_s[2], -w / 95.0, kRoundoff);
  EXPECT_NEAR(s.mesh_frequency_Hz, 192 * n / 60, 1e-9);
  EXPECT_GT(s.load_torque_Nm, 0.0);  // resists the backward-turning flexspline
  EXPECT_NEAR(s.mesh_torque_Nm, 100.0, kRoundoff);
  // fs_fixed: reduction z_c/(z_c − z_f) = 96, same sense; f_m = z_f·n/60; the CS output sees M·z_c/z_f.
  s = steady_state(test::seed_model(DynamicsConfiguration::FsFixed));
  EXPECT_NEAR(s.speed_rad_s[3], w / 96.0, kRoundoff);
  EXPECT_NEAR(s.mesh_frequency_Hz, 190 * n / 60, 1e-9);
  EXPECT_NEAR(s.mesh_torque_Nm * 192.0 / 190.0, 100.0, kRoundoff * 100);
  // wg_fixed: internal gear pair, ω_c = ω_f·z_f/z_c.
  s = steady_state(test::seed_model(DynamicsConfiguration::WgFixed));
  EXPECT_NEAR(s.speed_rad_s[3], w * 190.0 / 192.0, kRoundoff * w);
  // all_free: the brake creeps at ω_c = (z_c/z_f)·T/b.
  s = steady_state(test::seed_model(DynamicsConfiguration::AllFree));
  EXPECT_NEAR(s.speed_rad_s[3], 192.0 / 190.0 * 100.0 / 1000.0, kRoundoff);
  EXPECT_LT(s.speed_rad_s[2], 0.0);
}

TEST(DynamicsKinematics, AllFreeRejectsABrakeTooWeakForTheLoadToResist) {
  auto m = test::seed_model(DynamicsConfiguration::AllFree);
  m.params.circular_spline_drag_Nms_per_rad = 10.0;  // bound is (192/190)²·100/(104.7·2/190) ≈ 92.6
  try {
    steady_state(m);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("circular_spline_drag_Nms_per_rad = 10"), std::string::npos) << e.what();
  }
}

TEST(DynamicsContact, FollowsThePaperLawAndNeverPulls) {
  DynamicsParams p;
  p.damping_Ns_per_m = 1e3;
  EXPECT_EQ(flank_force(p, 8e7, -1e-6, 1.0).force_N, 0.0);
  EXPECT_NEAR(flank_force(p, 8e7, 2e-6, 0.01).force_N, 8e7 * 2e-6 + 1e3 * 0.01, kRoundoff);
  EXPECT_EQ(flank_force(p, 8e7, 2e-6, -1.0).force_N, 0.0);  // damping would pull: clamped
  p.exponent_stiffness = 1.5;
  p.exponent_damping = 1.0;
  p.exponent_indentation = 2.0;
  const double d = 3e-6, r = -0.02;
  EXPECT_NEAR(flank_force(p, 1e10, d, r).force_N, 1e10 * std::pow(d, 1.5) + 1e3 * r * std::abs(r) * d * d, 1e-12);
}

TEST(DynamicsLoadSharing, MatchesClosedFormsForOneAndTwoPairs) {
  DynamicsParams p;  // k = 8e7, m1 = 1
  std::vector<ToothPair> one{{0.0, 0.0, 0.0, 0.02, 0.9}};
  auto r = quasi_static_load_sharing(one, p, 36.0);
  EXPECT_NEAR(r.force_N[0], 36.0 / 0.018, 1e-9);
  // Two pairs, clearances 0 and j: the second takes load once a·e > j. k·a·(a e) + k·a·(a e − j) = M.
  const double a = 0.018, j = 5e-6, M = 100.0, k = 8e7;
  std::vector<ToothPair> two{{0.0, 0.0, 0.0, 0.02, 0.9}, {0.1, j, j, 0.02, 0.9}};
  r = quasi_static_load_sharing(two, p, M);
  const double e = (M / (k * a) + j) / (2 * a);
  EXPECT_NEAR(r.force_N[0], k * a * e, 1e-9);
  EXPECT_NEAR(r.force_N[1], k * (a * e - j), 1e-9);
  // Reversed torque loads the coast flanks.
  r = quasi_static_load_sharing(two, p, -M);
  EXPECT_NEAR(r.force_N[0], -k * a * -r.deflection_rad, 1e-9);
  EXPECT_LT(r.force_N[1], 0.0);
}

TEST(DynamicsLoadSharing, NonlinearLawBalancesTheTorque) {
  auto m = test::seed_model();
  m.params.exponent_stiffness = 1.5;
  m.params.stiffness_N_per_m = 8e7 / std::sqrt(5e-6);  // same force as the linear law at δ = 5 µm
  const auto r = quasi_static_load_sharing(m.pairs, m.params, 100.0);
  double torque = 0.0;
  for (std::size_t i = 0; i < m.pairs.size(); ++i) torque += r.force_N[i] * m.pairs[i].arm_m();
  EXPECT_NEAR(torque, 100.0, 1e-9);
}

TEST(DynamicsInertia, TubeWallMatchesTheThickRingFormula) {
  GearParams g;
  FlexsplineParams fs;
  fs.length_m = 0.03;
  fs.rim_width_m = 0.0;  // no rim, no teeth: only the wall remains
  Material mat;
  const auto J = body_inertias(g, fs, false, mat, DynamicsParams{});
  const double r1 = fs.inner_radius_m, r2 = r1 + fs.wall_thickness_m;
  const double exact = mat.density_kg_m3 * kPi * 0.03 * (std::pow(r2, 4) - std::pow(r1, 4)) / 2;
  EXPECT_NEAR(J[BodyId::FlexsplineRim] + J[BodyId::FlexsplineFlange], exact, 1e-12 * exact);
  EXPECT_NEAR(J[BodyId::FlexsplineRim], J[BodyId::FlexsplineFlange], 1e-12 * exact);
}

TEST(DynamicsInertia, SeedGearInertiasMatchThinWalledEstimates) {
  // Independent estimates: each wall a thin cylinder (ρ·2π·r̄³·t·length, r̄ its mid radius; exact to (t/2r̄)²/… ≈
  // 0.03 % here), the diaphragm a disc (ρ·π·t·r⁴/2), the generator a solid disc over the rim width, the teeth a half-
  // density layer 2.25·m deep. 1 %: the thin-wall error plus the teeth layer's radial spread.
  const auto m = test::seed_model();
  const GearParams g;
  const FlexsplineParams fs;
  const double rho = Material{}.density_kg_m3, pi = kPi;
  auto thin = [&](double r_in, double t, double len) { const double r = r_in + t / 2; return rho * 2 * pi * r * r * r * t * len; };
  const double wall = thin(fs.inner_radius_m, fs.wall_thickness_m, fs.length_m - fs.rim_width_m);
  const double rim = thin(fs.inner_radius_m, fs.rim_thickness_m, fs.rim_width_m);
  const double teeth = 0.5 * thin(fs.inner_radius_m + fs.rim_thickness_m, 2.25 * g.module_m, fs.rim_width_m);
  const double diaphragm = rho * pi * fs.diaphragm_thickness_m * std::pow(fs.inner_radius_m, 4) / 2;
  EXPECT_NEAR(m.inertia[BodyId::FlexsplineRim] / (rim + teeth + wall / 2), 1.0, 0.01);
  EXPECT_NEAR(m.inertia[BodyId::FlexsplineFlange] / (diaphragm + wall / 2), 1.0, 0.01);
  EXPECT_NEAR(m.inertia[BodyId::WaveGenerator] / (rho * pi * fs.rim_width_m * std::pow(fs.inner_radius_m, 4) / 2), 1.0, 1e-12);
}

TEST(DynamicsStandInClearances, SmallGearHasThreePairsPerZoneAndNoClearanceOnTheMajorAxis) {
  const auto m = test::small_model();
  ASSERT_EQ(m.pairs.size(), 6u);  // teeth every 13.85°: 0, ±13.85° within ±20°, at both ends
  int on_axis = 0;
  for (const auto& p : m.pairs) {
    if (std::abs(std::sin(p.angle_rad)) < 1e-12) {
      ++on_axis;
      EXPECT_NEAR(p.clearance_drive_m, 0.0, 1e-15);
      EXPECT_NEAR(p.lever_arm_m, 14e-3, 1e-15);  // deformed pitch radius m·z_f/2 + w0 = m·z_c/2
    } else {
      EXPECT_GT(p.clearance_drive_m, 30e-6);
    }
  }
  EXPECT_EQ(on_axis, 2);
}

TEST(DynamicsValidation, RejectsOutOfRangeKeysWithFileKeyValueAndConstraint) {
  DynamicsParams p;
  p.damping_Ns_per_m = -1.0;
  try {
    validate(p, "cases/x.toml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "cases/x.toml: dynamics.damping_Ns_per_m = -1; must be >= 0");
  }
  p = DynamicsParams{};
  p.stiffness_variation_N_per_m = p.stiffness_N_per_m;  // k(t) would reach 0
  EXPECT_THROW(validate(p, "c.toml"), InputError);
  p = DynamicsParams{};
  p.drive_ramp_end_s = p.drive_ramp_start_s;
  EXPECT_THROW(validate(p, "c.toml"), InputError);
  EXPECT_NO_THROW(validate(DynamicsParams{}, "c.toml"));
}

TEST(DynamicsParamsText, TheSchemaWritesEveryKeyAndTheEnumSpellingsRoundTrip) {
  const std::string text = keys_toml(DynamicsParams{}, dynamics_keys());
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 35) << text;  // one line per key of [dynamics]
  for (const char* key : {"configuration = \"cs_fixed\"", "ramp = \"paper\"", "drive_speed_rpm = 1000",
                          "stiffness_N_per_m = 8e+07", "damping_Ns_per_m = 1000", "output_step_s = 1e-05",
                          "circular_spline_drag_Nms_per_rad = 1000", "base_clearance_mm = 0"})
    EXPECT_NE(text.find(key), std::string::npos) << key << "\n" << text;
  for (auto c : {DynamicsConfiguration::CsFixed, DynamicsConfiguration::FsFixed, DynamicsConfiguration::WgFixed,
                 DynamicsConfiguration::AllFree})
    EXPECT_EQ(parse_configuration(to_string(c)), c);
  EXPECT_FALSE(parse_configuration("CS fixed").has_value());
  EXPECT_EQ(parse_ramp_shape("cubic"), RampShape::Cubic);
  EXPECT_FALSE(parse_ramp_shape("linear").has_value());
}

TEST(DynamicsRecording, HasTheSpecHeaderColumnsAndOneRowPerSample) {
  auto m = test::small_model();
  m.params.duration_s = 0.002;
  m.params.steady_from_s = 0.001;
  const auto s = simulate(m);
  const std::string rec = dynamics_recording(m, s, {"note: test"});
  EXPECT_EQ(rec.rfind("# strainwave-recording: 1\n# kind: dynamics\n", 0), 0u) << rec.substr(0, 200);
  EXPECT_NE(rec.find("# note: test\n"), std::string::npos);
  EXPECT_NE(rec.find("\ntime_s,wg_speed_rpm,output_speed_rpm,mesh_force_N\n"), std::string::npos);
  EXPECT_EQ(std::count(rec.begin(), rec.end(), '\n'), 6 + 1 + 1 + 201);  // metadata, note, header, 0…0.002 s
}
