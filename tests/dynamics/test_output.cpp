// dynamics.json as a typed value: what the writer writes the reader reads back field for field, and files the tool
// wrote before the typed writer existed read and write again to the same text (keys, values and their order).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "io/dynamics_output.hpp"
#include "tests/cli.hpp"

using namespace sw;

namespace {

/// A result with every field set to a value of its own (none the default), so a field the reader leaves out shows
/// up in the text written again.
DynamicsResult every_field_set() {
  DynamicsResult r;
  r.case_path = "cases/x.toml";
  r.configuration = DynamicsConfiguration::AllFree;
  r.teeth_flexspline = 26;
  r.teeth_circular = 28;
  r.pairs = PairMotion::Frozen;
  r.clearance_source = "kinematics";
  r.speeds = {{"wave_generator", 1000.25, 1000.0, 2.5e-4}, {"flexspline", -76.5, -76.9, 5.2e-3}};
  r.max_speed_error_rel = 5.2e-3;
  r.pair_forces = {{1, 12.5, 0.0135, 812.25, 810.5, 2.1e-3}, {2, -13.75, 0.0125, -3.5, 0.0, 4.3e-9}};
  r.max_pair_force_error_rel = 2.1e-3;
  r.pairs_in_interference = 3;
  r.total_force_at_rest_N = 17.5;
  r.mesh_torque_Nm = 100.125;
  r.mesh_torque_theory_Nm = 100.0625;
  r.load_torque_Nm = 99.5;
  r.torque_balance_error_rel = 6.25e-4;
  r.energy_error_rel = 1.5e-6;
  r.energy = {.input_J = 73.5, .output_J = 68.25, .dissipated_J = 5.125, .friction_J = 1.25, .bearing_J = 2.5,
              .parametric_J = 0.75, .kinetic_J = 0.0625, .potential_J = 0.03125};
  r.steady_power = SteadyPower{.input_W = 962.75, .output_W = 805.5, .friction_W = 92.5, .bearing_W = 12.25,
                               .dissipated_W = 64.75, .stored_W = -0.0078125, .efficiency = 0.896875,
                               .balance_error_rel = 1.25e-8};
  r.bearing_source = "a bearing's moment";
  r.mesh_frequency_Hz = 466.5;
  r.generator_frequency_Hz = 17.9375;
  r.mean_total_force_N = 7669.25;
  r.force_fluctuation_N = 611.75;
  r.spectrum_resolution_Hz = 20.25;
  r.spectral_lines = {{466.75, 140.5}, {933.5, 123.25}};
  r.force_noise_floor_N = 0.28125;
  r.transmission_error_noise_floor_rad = 1.5e-9;
  r.force_lines_in_orders = {{466.75, 140.5, 1.0005, 26.01}};
  r.transmission_error_lines_in_orders = {{933.5, 3.25e-4, 2.001, 52.03}, {1400.25, 9.75e-5, 3.0015, 78.04}};
  r.steady_window_start_s = 0.050625;
  r.steady_window_end_s = 0.1;
  r.mesh_deflection_min_rad = 4.4e-3;
  r.mesh_deflection_max_rad = 5.4e-3;
  r.max_pair_force_N = 3413.25;
  r.flanks_in_contact_min = 4.0;
  r.flanks_in_contact_max = 6.0;
  r.transmission_error_peak_to_peak_rad = 9.5e-4;
  r.oversampling = 8;
  r.output_filter = "a filter";
  r.inertia.kgm2 = {1.25e-6, 1.5e-6, 3.75e-7, 7.125e-6};
  DynamicsParams& p = r.parameters;
  p.drive_speed_rpm = 1000.5;
  p.drive_ramp_start_s = 0.0625;
  p.drive_ramp_end_s = 0.01;
  p.load_torque_Nm = 100.25;
  p.load_ramp_start_s = 0.0125;
  p.load_ramp_end_s = 0.02;
  p.ramp_shape = RampShape::Cubic;
  p.stiffness_N_per_m = 8e7;
  p.stiffness_variation_N_per_m = 1.6e7;
  p.damping_Ns_per_m = 1000.0;
  p.exponent_stiffness = 1.5;
  p.exponent_damping = 0.25;
  p.exponent_indentation = 1.125;
  p.flexspline_compliance_rad_per_Nm = 2e-5;
  p.output_step_s = 1e-5;
  p.duration_s = 0.1;
  p.relative_tolerance = 1e-8;
  r.solver_method = "CVODE";
  r.solver = {117938, 174549, 2237, 14932, 96};
  r.simulate_time_s = 0.589;
  r.total_time_s = 0.763;
  r.real_time_factor = 0.1697;
  return r;
}

}  // namespace

TEST(DynamicsOutput, EveryFieldSurvivesWritingAndReadingBack) {
  const DynamicsResult r = every_field_set();
  const std::string text = dynamics_json(r);
  const DynamicsResult back = parse_dynamics_json(text, "written");
  EXPECT_EQ(dynamics_json(back), text);
  // Typed values, not strings: the enums, the optional, the integers and a nested array.
  EXPECT_EQ(back.configuration, DynamicsConfiguration::AllFree);
  EXPECT_EQ(back.pairs, PairMotion::Frozen);
  EXPECT_EQ(back.parameters.ramp_shape, RampShape::Cubic);
  ASSERT_TRUE(back.max_pair_force_error_rel.has_value());
  EXPECT_EQ(*back.max_pair_force_error_rel, 2.1e-3);
  ASSERT_EQ(back.pair_forces.size(), 2u);
  EXPECT_EQ(back.pair_forces[1].pair, 2);
  EXPECT_EQ(back.pair_forces[1].mean_N, -3.5);
  EXPECT_EQ(back.solver.newton_fails, 96);
  EXPECT_EQ(back.inertia[BodyId::FlexsplineFlange], 3.75e-7);
  EXPECT_EQ(back.parameters.exponent_indentation, 1.125);
  ASSERT_EQ(back.transmission_error_lines_in_orders.size(), 2u);
  EXPECT_EQ(back.transmission_error_lines_in_orders[1].generator_order, 78.04);
  ASSERT_TRUE(back.steady_power.has_value());
  EXPECT_EQ(back.steady_power->efficiency, 0.896875);
  EXPECT_EQ(back.steady_power->friction_W, 92.5);
  EXPECT_EQ(back.energy.friction_J, 1.25);
  EXPECT_EQ(back.steady_power->bearing_W, 12.25);
  EXPECT_EQ(back.energy.bearing_J, 2.5);
  EXPECT_EQ(back.bearing_source, "a bearing's moment");
}

TEST(DynamicsOutput, MovingPairsHaveNoPairForceErrorKey) {
  DynamicsResult r = every_field_set();
  r.pairs = PairMotion::Moving;
  r.pair_forces.clear();
  r.max_pair_force_error_rel.reset();
  const std::string text = dynamics_json(r);
  EXPECT_EQ(text.find("max_pair_force_error_rel"), std::string::npos);
  EXPECT_NE(text.find("\"pair_forces\": []"), std::string::npos);
  const DynamicsResult back = parse_dynamics_json(text, "written");
  EXPECT_FALSE(back.max_pair_force_error_rel.has_value());
  EXPECT_EQ(back.pairs, PairMotion::Moving);
  EXPECT_EQ(dynamics_json(back), text);
}

// Files written by `strainwave dynamics` before the typed writer: cases/mbd_26_28.toml as shipped (moving pairs on a
// rigid rim, cs_fixed), and the same case with configuration = "all_free", a compliant flexspline (C_tau 2e-5
// rad/(N m)) and a varying k, pairs frozen (four bodies, every pair's check, the pair-force error key).
TEST(DynamicsOutput, FilesTheToolWroteReadAndWriteAgainToTheSameText) {
  for (const char* name : {"mbd_26_28_moving.json", "mbd_26_28_all_free_compliant_frozen.json"}) {
    const std::filesystem::path path = std::filesystem::path("tests/dynamics/data") / name;
    const std::string text = sw::testing::read_text(path);
    ASSERT_FALSE(text.empty()) << path;
    const DynamicsResult r = read_dynamics_json(path);
    EXPECT_EQ(dynamics_json(r), text) << name;
    EXPECT_EQ(r.teeth_flexspline, 26);
    EXPECT_EQ(r.teeth_circular, 28);
  }
  const DynamicsResult moving = read_dynamics_json("tests/dynamics/data/mbd_26_28_moving.json");
  EXPECT_EQ(moving.pairs, PairMotion::Moving);
  EXPECT_EQ(moving.configuration, DynamicsConfiguration::CsFixed);
  EXPECT_NEAR(moving.mesh_frequency_Hz, 28 * 1000.0 / 60.0, 1e-9);  // cs_fixed: z_c·n_w/60
  EXPECT_EQ(moving.speeds.size(), 3u);
  EXPECT_TRUE(moving.pair_forces.empty());
  EXPECT_FALSE(moving.max_pair_force_error_rel.has_value());
  EXPECT_EQ(moving.solver.steps, 117938);
  EXPECT_FALSE(moving.steady_power.has_value());  // written before the flanks had friction: no efficiency key
  const DynamicsResult frozen = read_dynamics_json("tests/dynamics/data/mbd_26_28_all_free_compliant_frozen.json");
  EXPECT_EQ(frozen.pairs, PairMotion::Frozen);
  EXPECT_EQ(frozen.configuration, DynamicsConfiguration::AllFree);
  EXPECT_EQ(frozen.speeds.size(), 4u);  // the rim is a body of its own
  EXPECT_EQ(frozen.pair_forces.size(), 18u);
  EXPECT_TRUE(frozen.max_pair_force_error_rel.has_value());
  EXPECT_EQ(frozen.parameters.flexspline_compliance_rad_per_Nm, 2e-5);
}

TEST(DynamicsOutput, AMissingKeyOrAnUnknownSpellingIsNamedWithTheFile) {
  std::string text = dynamics_json(every_field_set());
  const auto without = [&](const std::string& key) {
    std::string t = text;
    const std::size_t at = t.find("\"" + key + "\"");
    t.replace(at, key.size() + 2, "\"renamed\"");
    return t;
  };
  try {
    parse_dynamics_json(without("mesh_torque_Nm"), "out/x/dynamics.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("out/x/dynamics.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("mesh_torque_Nm"), std::string::npos) << e.what();
  }
  const std::size_t at = text.find("\"all_free\"");
  text.replace(at, 10, "\"free_all\"");
  try {
    parse_dynamics_json(text, "out/x/dynamics.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("configuration = \"free_all\""), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_dynamics_json("tests/dynamics/data/no_such_file.json"), InputError);
}
