// The dynamics cases run through the CLI (as a user runs them) and their headline numbers are checked in dynamics.json.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace {

namespace fs = std::filesystem;

std::string binary() {
  const char* dir = std::getenv("SW_BUILD_DIR");
  return (fs::path(dir ? dir : "build") / "strainwave").string();
}

/// Runs a command, returns its exit code; stdout+stderr into `log`.
int run(const std::string& cmd, const fs::path& log) {
  const int rc = std::system((cmd + " > " + log.string() + " 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  return {std::istreambuf_iterator<char>(in), {}};
}

constexpr double kSpeedTolerance = 1e-4;      // issue 6: 0.01 %
constexpr double kPairForceTolerance = 1e-2;  // issue 6: 1 %
constexpr double kTorqueTolerance = 1e-3;     // issue 6: 0.1 %
constexpr double kEnergyTolerance = 5e-3;     // issue 6: 0.5 %

}  // namespace

TEST(DynamicsCli, SmallGearCaseRunsAndMeetsTheIssueTolerances) {
  const fs::path out = fs::temp_directory_path() / "sw_test_dynamics_cli";
  fs::remove_all(out);
  const int rc = run(binary() + " --quiet dynamics cases/mbd_26_28.toml --out " + out.string(), out.string() + ".log");
  const std::string log = slurp(out.string() + ".log");
  if (rc != 0 && log.find("[dynamics] is not a known table") != std::string::npos)
    GTEST_SKIP() << "the case parser does not read [dynamics] yet: " << log;
  ASSERT_EQ(rc, 0) << log;
  for (const char* f : {"dynamics.csv", "dynamics.json", "dynamics.svg"}) EXPECT_TRUE(fs::exists(out / f)) << f;
  const auto j = nlohmann::json::parse(slurp(out / "dynamics.json"));
  for (const auto& s : j.at("speeds")) EXPECT_LT(s.at("error_rel").get<double>(), kSpeedTolerance) << s.dump();
  EXPECT_LT(j.at("max_pair_force_error_rel").get<double>(), kPairForceTolerance);
  EXPECT_LT(j.at("torque_balance_error_rel").get<double>(), kTorqueTolerance);
  EXPECT_LT(j.at("energy_error_rel").get<double>(), kEnergyTolerance);
  EXPECT_NEAR(j.at("mesh_frequency_Hz").get<double>(), 28 * 1000.0 / 60.0, 1e-9);  // cs_fixed: z_c·n_w/60
  // Flexspline: −(z_c − z_f)/z_f · 1000 rpm.
  EXPECT_NEAR(j.at("speeds").at(1).at("theory_rpm").get<double>(), -2.0 / 26.0 * 1000.0, 1e-9);
  // The CSV has one row per 1e-5 s over 0.1 s plus its header.
  const std::string csv = slurp(out / "dynamics.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 10002);
  fs::remove_all(out);
}

TEST(DynamicsCli, BadCaseFailsWithOneLineAndWritesNothing) {
  const fs::path dir = fs::temp_directory_path() / "sw_test_dynamics_bad";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "nogear.toml") << "[flexspline]\nshape = \"tube\"\nteeth = \"none\"\n";
  const int rc = run(binary() + " --quiet dynamics " + (dir / "nogear.toml").string() + " --out " +
                         (dir / "out").string(), dir / "log");
  const std::string log = slurp(dir / "log");
  EXPECT_NE(rc, 0);
  EXPECT_NE(log.find("[gear]"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir / "out" / "dynamics.json"));
  fs::remove_all(dir);
}
