// Validation of the integrated dynamics: steady speeds vs kinematics, mean pair forces vs quasi-static
// load sharing, torque and energy balances, the spectral line of a varying mesh stiffness, and the damping sweep.
// The thresholds are the acceptance limits; the measured values (printed) are orders of magnitude below them,
// limited by the integrator's tolerances (relative 1e-8, 1e-13 rad on the deviation from kinematic motion).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "dynamics/analysis.hpp"
#include "tests/dynamics/seed_models.hpp"

using namespace sw;

namespace {
constexpr double kSpeedTolerance = 1e-4;        // 0.01 % (the paper reached 0.04 %)
constexpr double kPairForceTolerance = 1e-2;    // 1 % (the paper: 1.04 %)
constexpr double kTorqueBalanceTolerance = 1e-3;// 0.1 %
constexpr double kEnergyTolerance = 5e-3;       // 0.5 % of the input work
constexpr double kStiffnessVariation = 0.2;     // Δk/k0 for the spectral and damping tests

DynamicsSummary run(const DynamicsModel& m, DynamicsSeries* keep = nullptr) {
  DynamicsSeries s = simulate(m);
  DynamicsSummary r = summarize(m, s);
  if (keep) *keep = std::move(s);
  return r;
}

const char* name(DynamicsConfiguration c) { return to_string(c); }

/// Pairs whose quasi-static force is not zero: the ones max_pair_force_error_rel is taken over.
int loaded_pairs(const DynamicsSummary& r) {
  int loaded = 0;
  for (const auto& c : r.pair_forces)
    if (std::abs(c.quasi_static_N) > 0) ++loaded;
  return loaded;
}
}  // namespace

class EveryConfiguration : public ::testing::TestWithParam<DynamicsConfiguration> {};

TEST_P(EveryConfiguration, SteadySpeedsMatchTheKinematicRelations) {
  for (bool compliant : {false, true}) {
    auto m = test::seed_model(GetParam());
    if (compliant) {
      m.params.flexspline_compliance_rad_per_Nm = 2e-5;  // a 190/192 cup's order of magnitude (SPEC φ₀ example)
      m.params.flexspline_torsion_damping_Nms_per_rad = 0.5;
    }
    const auto r = run(m);
    ASSERT_EQ(r.speeds.size(), compliant ? 4u : 3u);  // wave generator, (rim,) flexspline, circular spline
    for (const auto& c : r.speeds) {
      std::printf("  %s%s %-16s simulated %14.8f rpm  theory %14.8f rpm  error %.2e\n", name(GetParam()),
                  compliant ? "+C" : "  ", c.body.c_str(), c.simulated_rpm, c.theory_rpm, c.error_rel);
      if (c.theory_rpm != 0.0) EXPECT_LT(c.error_rel, kSpeedTolerance) << c.body;
      else EXPECT_LT(std::abs(c.simulated_rpm), 1e-9) << c.body;
    }
  }
}

TEST_P(EveryConfiguration, OutputDragAddsToTheMeshTorqueAndKeepsTheBalances) {
  auto m = test::seed_model(GetParam());
  m.params.output_drag_coulomb_Nm = 5.0;
  m.params.output_drag_viscous_Nms_per_rad = 0.5;
  const auto r = run(m);
  const double out = r.theory.speed_rad_s[int(r.theory.output)];
  const double drag = 5.0 * std::tanh(std::abs(out) / 1e-3) + 0.5 * std::abs(out);  // resists: adds to the load
  const double on_output = 100.0 + drag;
  const double expected = r.theory.output == BodyId::FlexsplineFlange ? on_output : on_output * 190.0 / 192.0;
  std::printf("  %s: drag %.4f N m, mesh torque %.6f N m (expected %.6f), speed error %.2e, torque balance %.2e,"
              " energy %.2e\n", name(GetParam()), drag, r.mesh_torque_Nm, expected, r.max_speed_error_rel,
              r.torque_balance_error_rel, r.energy_error_rel);
  EXPECT_NEAR(std::abs(r.mesh_torque_Nm), expected, kTorqueBalanceTolerance * expected);
  EXPECT_LT(r.max_speed_error_rel, kSpeedTolerance);
  EXPECT_GE(loaded_pairs(r), 4);  // the pair-force error is taken over loaded pairs: there are some
  EXPECT_LT(r.max_pair_force_error_rel, kPairForceTolerance);
  EXPECT_LT(r.energy_error_rel, kEnergyTolerance);
}

TEST_P(EveryConfiguration, MeanPairForcesMatchQuasiStaticSharingAndBalanceTheLoad) {
  const auto r = run(test::seed_model(GetParam()));
  const int loaded = loaded_pairs(r);
  std::printf("  %s: %d of %zu pairs loaded, max pair error %.2e, torque balance %.2e, energy %.2e\n", name(GetParam()),
              loaded, r.pair_forces.size(), r.max_pair_force_error_rel, r.torque_balance_error_rel, r.energy_error_rel);
  EXPECT_GE(loaded, 4);  // load sharing is exercised, not a single pair
  EXPECT_LT(r.max_pair_force_error_rel, kPairForceTolerance);
  EXPECT_LT(r.torque_balance_error_rel, kTorqueBalanceTolerance);
  EXPECT_LT(r.energy_error_rel, kEnergyTolerance);
}

INSTANTIATE_TEST_SUITE_P(Dynamics, EveryConfiguration,
                         ::testing::Values(DynamicsConfiguration::CsFixed, DynamicsConfiguration::FsFixed,
                                           DynamicsConfiguration::WgFixed, DynamicsConfiguration::AllFree),
                         [](const auto& info) { return std::string(to_string(info.param)); });

TEST(DynamicsForces, WithoutLoadNoPairCarriesForceAndTheCubicRampReachesTheSameSteadyState) {
  auto m = test::small_model();
  m.params.load_torque_Nm = 0.0;
  m.params.ramp_shape = RampShape::Cubic;
  const auto r = run(m);
  ASSERT_EQ(r.pair_forces.size(), 6u);  // the small gear's three pairs per zone
  std::printf("  no load: max speed error %.2e, mesh torque %.3e N m, largest |mean pair force| ", r.max_speed_error_rel,
              r.mesh_torque_Nm);
  double largest = 0.0;
  for (const auto& c : r.pair_forces) largest = std::max(largest, std::abs(c.mean_N));
  std::printf("%.3e N\n", largest);
  EXPECT_LT(r.max_speed_error_rel, kSpeedTolerance);
  EXPECT_LT(largest, 1e-3);  // N: a millinewton against the kilonewtons of the loaded run
  EXPECT_LT(r.torque_balance_error_rel, kTorqueBalanceTolerance);
}

TEST(DynamicsForces, SmallGearWithNonlinearContactSharesTheLoadAsStaticsSays) {
  auto m = test::small_model();
  m.params.exponent_stiffness = 1.5;
  m.params.stiffness_N_per_m = 8e7 / std::sqrt(50e-6);  // the linear law's force at δ = 50 µm
  m.params.exponent_indentation = 1.0;                     // damping fades in with penetration
  const auto r = run(m);
  for (const auto& c : r.pair_forces)
    std::printf("  pair %d at %7.2f deg: mean %10.3f N, quasi-static %10.3f N, error %.2e\n", c.pair, c.angle_deg,
                c.mean_N, c.quasi_static_N, c.error_rel);
  ASSERT_EQ(r.pair_forces.size(), 6u);  // the small gear's three pairs per zone
  EXPECT_EQ(loaded_pairs(r), 6);        // all carry load: the pair-force error is taken over all six
  EXPECT_LT(r.max_pair_force_error_rel, kPairForceTolerance);
  EXPECT_LT(r.torque_balance_error_rel, kTorqueBalanceTolerance);
  EXPECT_LT(r.energy_error_rel, kEnergyTolerance);
}

TEST(DynamicsEnergy, BalancesWithVaryingStiffnessAndACompliantFlexspline) {
  auto m = test::seed_model(DynamicsConfiguration::CsFixed);
  m.params.stiffness_variation_N_per_m = kStiffnessVariation * m.params.stiffness_N_per_m;
  m.params.flexspline_compliance_rad_per_Nm = 2e-5;
  m.params.flexspline_torsion_damping_Nms_per_rad = 0.5;
  DynamicsSeries s;
  const auto r = run(m, &s);
  const auto& e = s.energy;
  std::printf("  input %.6f J + parametric %.6f J = output %.6f + dissipated %.6f + kinetic %.6f + potential %.6f;"
              " error %.2e\n", e.input_J, e.parametric_J, e.output_J, e.dissipated_J, e.kinetic_J, e.potential_J,
              r.energy_error_rel);
  EXPECT_GT(e.dissipated_J, 0.0);
  EXPECT_NE(e.parametric_J, 0.0);
  EXPECT_LT(r.energy_error_rel, kEnergyTolerance);
}

TEST(DynamicsSpectrum, VaryingStiffnessPutsTheStrongestLineAtTheMeshFrequencyConstantDoesNot) {
  for (bool small : {false, true}) {
    auto m = small ? test::small_model() : test::seed_model();
    const auto constant = run(m);
    m.params.stiffness_variation_N_per_m = kStiffnessVariation * m.params.stiffness_N_per_m;
    const auto varying = run(m);
    const double fm = varying.theory.mesh_frequency_Hz, bin = varying.spectrum.resolution_Hz;
    ASSERT_FALSE(varying.lines.empty());
    std::printf("  %s: f_m = %.1f Hz; varying k: strongest %.1f Hz (%.3g N), next %.1f Hz; constant k: strongest %s"
                " %.1f Hz (%.3g N)\n", small ? "26/28" : "190/192", fm, varying.lines[0].frequency_Hz,
                varying.lines[0].amplitude_N, varying.lines.size() > 1 ? varying.lines[1].frequency_Hz : 0.0,
                constant.lines.empty() ? "none" : "", constant.lines.empty() ? 0.0 : constant.lines[0].frequency_Hz,
                constant.lines.empty() ? 0.0 : constant.lines[0].amplitude_N);
    EXPECT_NEAR(varying.lines[0].frequency_Hz, fm, bin);
    // Over whole mesh periods the mean speeds and pair forces keep to kinematics and statics with k(t) as well.
    std::printf("  %s varying k: speed error %.2e, pair forces vs quasi-static %.2e\n", small ? "26/28" : "190/192",
                varying.max_speed_error_rel, varying.max_pair_force_error_rel);
    EXPECT_LT(varying.max_speed_error_rel, kSpeedTolerance);
    EXPECT_LT(varying.max_pair_force_error_rel, kPairForceTolerance);
    // Harmonics: the second line sits at 2·f_m (the contact law is nonlinear in k·δ with δ ∝ 1/k).
    ASSERT_GE(varying.lines.size(), 2u);
    EXPECT_NEAR(varying.lines[1].frequency_Hz, 2 * fm, bin);
    // Constant k: no line at f_m, and whatever is strongest is below 1e-3 of the varying run's line (numerical noise
    // and the decay of the start-up transient).
    for (const auto& l : constant.lines) {
      EXPECT_LT(l.amplitude_N, 1e-3 * varying.lines[0].amplitude_N) << l.frequency_Hz;
    }
    // The constant run's spectrum at f_m itself (on a bin: the window spans whole mesh periods), with or without lines.
    const std::size_t fm_bin = std::lround(fm / constant.spectrum.resolution_Hz);
    ASSERT_LT(fm_bin, constant.spectrum.amplitude_N.size());
    EXPECT_LT(constant.spectrum.amplitude_N[fm_bin], 1e-3 * varying.lines[0].amplitude_N);
    if (!constant.lines.empty()) EXPECT_GT(std::abs(constant.lines[0].frequency_Hz - fm), bin);
  }
}

TEST(DynamicsDamping, SweepFrom1e2To1e4ReducesTheForceFluctuationMonotonically) {
  std::printf("  c [N s/m]   fluctuation of the total meshing force [N rms]   line at f_m [N]\n");
  double previous = INFINITY;
  for (double c : {1e2, 2e2, 5e2, 1e3, 2e3, 5e3, 1e4}) {
    auto m = test::seed_model();
    m.params.stiffness_variation_N_per_m = kStiffnessVariation * m.params.stiffness_N_per_m;
    m.params.damping_Ns_per_m = c;
    const auto r = run(m);
    std::printf("  %9.0f   %14.6f   %14.6f\n", c, r.force_fluctuation_N, r.lines.empty() ? 0.0 : r.lines[0].amplitude_N);
    EXPECT_LT(r.force_fluctuation_N, previous) << "c = " << c;
    previous = r.force_fluctuation_N;
  }
}

// Independent check of the dynamics: n pairs with zero clearance and equal arms a, circular spline fixed, the
// flexspline of inertia J free, constant load T. Linearized about e0 = T/(n·k0·a²), the deviation ε obeys
//     J·ε̈ + C·ε̇ + K·ε = −(Δk/k0)·T·sin(ωt + φ),   K = n·k0·a²,  C = n·c·a²,  ω = 2π·f_m
// (the product Δk·ε only feeds DC and 2ω, back into ω at order (Δk/k0)²), and the total meshing force Σ F_i = (T − J·ε̈)/a
// fluctuates at f_m with amplitude J·ω²·(Δk/k0)·T / (a·|K − J·ω² + iCω|).
TEST(DynamicsResponse, MeshFrequencyLineMatchesTheLinearizedOscillator) {
  constexpr double kAmplitudeTolerance = 1e-3;  // (Δk/k0)² = 1e-4 nonlinearity + integrator error; on-bin Hann is exact
  for (double J : {1e-5, 2e-4}) {
    DynamicsModel m;
    m.teeth_flexspline = 190;
    m.teeth_circular = 192;
    m.inertia[BodyId::WaveGenerator] = 1e-5;
    m.inertia[BodyId::FlexsplineFlange] = J;
    m.inertia[BodyId::CircularSpline] = 1e-4;
    const int n = 4;
    const double a = 0.018;
    for (int i = 0; i < n; ++i) m.pairs.push_back({0.1 * i, 0.0, 0.0, a, 1.0});
    m.params.stiffness_variation_N_per_m = 0.01 * m.params.stiffness_N_per_m;
    const auto r = run(m);
    const double k0 = m.params.stiffness_N_per_m, c = m.params.damping_Ns_per_m, T = m.params.load_torque_Nm;
    const double w = 2 * std::numbers::pi * r.theory.mesh_frequency_Hz;
    const double K = n * k0 * a * a, C = n * c * a * a;
    const double expected = J * w * w * 0.01 * T / (a * std::hypot(K - J * w * w, C * w));
    ASSERT_FALSE(r.lines.empty());
    std::printf("  J = %g kg m²: line %.2f Hz, amplitude %.6f N, linearized oscillator %.6f N, error %.2e\n", J,
                r.lines[0].frequency_Hz, r.lines[0].amplitude_N, expected, r.lines[0].amplitude_N / expected - 1);
    EXPECT_NEAR(r.lines[0].frequency_Hz, 3200.0, 1e-6 * 3200);
    EXPECT_NEAR(r.lines[0].amplitude_N, expected, kAmplitudeTolerance * expected);
  }
}
