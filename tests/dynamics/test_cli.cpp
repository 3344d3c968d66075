// The dynamics cases run through the CLI (as a user runs them) and their headline numbers are checked in dynamics.json.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "io/dynamics_output.hpp"
#include "tests/cli.hpp"

namespace {

namespace fs = std::filesystem;

using namespace sw::testing;

constexpr double kSpeedTolerance = 1e-4;      // 0.01 %: steady speeds against the kinematic ratios
constexpr double kPairForceTolerance = 1e-2;  // 1 %: mean pair forces against quasi-static sharing
constexpr double kTorqueTolerance = 1e-3;     // 0.1 %: torque balance
constexpr double kEnergyTolerance = 5e-3;     // 0.5 %: energy balance

}  // namespace

TEST(DynamicsCli, SmallGearCaseRunsAndMeetsItsTolerances) {
  const fs::path out = fs::temp_directory_path() / "sw_test_dynamics_cli";
  fs::remove_all(out);
  const CommandRun r = run_strainwave("--quiet dynamics cases/mbd_26_28.toml --pairs frozen --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"dynamics.csv", "dynamics.json", "dynamics.svg"}) EXPECT_TRUE(fs::exists(out / f)) << f;
  const sw::DynamicsResult j = sw::read_dynamics_json(out / "dynamics.json");
  ASSERT_EQ(j.speeds.size(), 3u);  // wave generator, flexspline, circular spline
  for (const auto& s : j.speeds) EXPECT_LT(s.error_rel, kSpeedTolerance) << s.body;
  ASSERT_TRUE(j.max_pair_force_error_rel.has_value());
  EXPECT_LT(*j.max_pair_force_error_rel, kPairForceTolerance);
  EXPECT_LT(j.torque_balance_error_rel, kTorqueTolerance);
  EXPECT_LT(j.energy_error_rel, kEnergyTolerance);
  ASSERT_TRUE(j.steady_power.has_value());
  EXPECT_EQ(j.steady_power->efficiency, 1.0);  // no friction
  EXPECT_LT(j.steady_power->balance_error_rel, kEnergyTolerance);
  EXPECT_NEAR(j.mesh_frequency_Hz, 28 * 1000.0 / 60.0, 1e-9);  // cs_fixed: z_c·n_w/60
  // Flexspline: −(z_c − z_f)/z_f · 1000 rpm.
  EXPECT_EQ(j.speeds[1].body, "flexspline");
  EXPECT_NEAR(j.speeds[1].theory_rpm, -2.0 / 26.0 * 1000.0, 1e-9);
  // The CSV has one row per 1e-5 s over 0.1 s plus its header.
  const std::string csv = read_text(out / "dynamics.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 10002);
  fs::remove_all(out);
}

TEST(DynamicsCli, BadCaseFailsWithOneLineAndWritesNothing) {
  const fs::path dir = fs::temp_directory_path() / "sw_test_dynamics_bad";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "nogear.toml") << "[flexspline]\nshape = \"tube\"\nteeth = \"none\"\n";
  const CommandRun r =
      run_strainwave("--quiet dynamics " + (dir / "nogear.toml").string() + " --out " + (dir / "out").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("[gear]"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out" / "dynamics.json"));
  fs::remove_all(dir);
}

// The flanks' friction acts on the moving pairs: a case with friction and the pairs frozen is refused in one line
// naming the key, its value and the fix.
TEST(DynamicsCli, FrictionWithFrozenPairsFailsWithOneLine) {
  const fs::path dir = fs::temp_directory_path() / "sw_test_dynamics_friction_frozen";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "friction.toml") << read_text("cases/mbd_26_28.toml") << "\n[contact]\nfriction_coefficient = 0.05\n";
  const CommandRun r = run_strainwave("--quiet dynamics " + (dir / "friction.toml").string() + " --pairs frozen --out " +
                                      (dir / "out").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("friction.toml: contact.friction_coefficient = 0.05; the flanks' friction acts on moving pairs "
                       "only"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "dynamics.json"));
  fs::remove_all(dir);
}

// End to end on the SPEC example gear (190/192) with the backlash module's clearances and the [dynamics] defaults
// (the paper's drive, load and contact), independent of whether the case parser reads [dynamics] yet.
TEST(DynamicsCli, SeedGearRunsEndToEndOnKinematicClearances) {
  const fs::path dir = fs::temp_directory_path() / "sw_test_dynamics_seed";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "seed.toml")
      << "[gear]\nmodule_mm = 0.2\nteeth_flexspline = 190\nteeth_circular = 192\npressure_angle_deg = 20.0\n"
         "profile_shift_flexspline = 1.52\nprofile_shift_circular = 1.57\ncutter_teeth = 80\n"
         "[flexspline]\nshape = \"cup\"\ninner_radius_mm = 18.4\nwall_thickness_mm = 0.6\nlength_mm = 20.0\n"
         "rim_width_mm = 6.0\nrim_thickness_mm = 0.7\nteeth = \"ring\"\ndiaphragm_thickness_mm = 1.0\n"
         "boss_radius_mm = 8.0\nfillet_radius_mm = 1.0\n"
         "[material]\nyoungs_modulus_Pa = 210e9\npoisson_ratio = 0.3\ndensity_kg_m3 = 7850\n"
         "[wave_generator]\nmodel = \"four_force\"\nbeta_deg = 30.0\nradial_deformation_mm = 0.2\n"
         "axial_position_mm = 3.0\n[load]\ntorque_Nm = 44.1\n";
  for (const std::string policy : {"preload", "drop"}) {
    const fs::path out = dir / policy;
    const CommandRun r = run_strainwave("--quiet dynamics " + (dir / "seed.toml").string() + " --pairs frozen --interference " +
                                        policy + " --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const sw::DynamicsResult j = sw::read_dynamics_json(out / "dynamics.json");
    ASSERT_EQ(j.speeds.size(), 3u) << policy;
    for (const auto& s : j.speeds) EXPECT_LT(s.error_rel, kSpeedTolerance) << policy << " " << s.body;
    ASSERT_TRUE(j.max_pair_force_error_rel.has_value()) << policy;
    EXPECT_LT(*j.max_pair_force_error_rel, kPairForceTolerance) << policy;
    EXPECT_LT(j.torque_balance_error_rel, kTorqueTolerance) << policy;
    EXPECT_LT(j.energy_error_rel, kEnergyTolerance) << policy;
    EXPECT_NEAR(j.mesh_torque_Nm, 100.0, 100.0 * kTorqueTolerance);  // cs_fixed: Σ F·a = load
    EXPECT_NEAR(j.mesh_frequency_Hz, 3200.0, 1e-9);
    EXPECT_LT(j.simulate_time_s, 10.0);  // performance bound
    if (policy == "drop") EXPECT_EQ(j.total_force_at_rest_N, 0.0);
    std::printf("  %s: %zu pairs, %d in interference, simulate %.3f s\n", policy.c_str(), j.pair_forces.size(),
                j.pairs_in_interference, j.simulate_time_s);
  }
  fs::remove_all(dir);
}
