// `strainwave sweep` through the CLI: a 3 × 3 sweep gives the numbers of the 9 single runs, an interrupted sweep
// (shards, a lost point) resumes without rerunning finished points, bad --set / --shard give one line and exit 2.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/cli.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sw::testing;

// A small tube with a cam generator on the harmonic solver: a fraction of a second a point.
std::string tube_case(double wall_mm, double torque_Nm) {
  std::ostringstream s;
  s << "[flexspline]\nshape = \"tube\"\ninner_radius_mm = 18.4\nwall_thickness_mm = " << wall_mm
    << "\nlength_mm = 30.0\nteeth = \"none\"\nrim_width_mm = 6.0\n"
    << "[wave_generator]\nmodel = \"cam\"\nradial_deformation_mm = 0.1\n"
    << "[load]\ntorque_Nm = " << torque_Nm << "\n"
    << "[mesh]\nsize_mm = 1.5\nwall_layers = 1\n"
    << "[solver]\nmethod = \"fourier\"\nharmonics = 8\n";
  return s.str();
}

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("sw_sweep_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// Every point equals its single run to the last printed digit (the same solver on the same case: 1e-12), and the
// table holds them in the documented order (first key slowest).
TEST(Sweep, GridEqualsSingleRuns) {
  const fs::path d = fresh_dir("grid");
  write(d / "base.toml", tube_case(1.0, 10.0));
  const CommandRun r = run_strainwave("sweep --quiet " + (d / "base.toml").string() +
                       " --set flexspline.wall_thickness_mm=0.8:1.2:3 --set load.torque_Nm=10:30:3 --out " +
                       (d / "sweep").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::ifstream csv(d / "sweep" / "sweep.csv");
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("point,flexspline.wall_thickness_mm,load.torque_Nm,phi0_rad,", 0), 0u) << header;
  int i = 0;
  for (double wall : {0.8, 1.0, 1.2})
    for (double torque : {10.0, 20.0, 30.0}) {
      ASSERT_TRUE(std::getline(csv, line));
      const std::string single = "single_" + std::to_string(i);
      write(d / (single + ".toml"), tube_case(wall, torque));
      const CommandRun s = run_strainwave("fem --quiet --no-vtk " + (d / (single + ".toml")).string() + " --out " + (d / single).string());
      ASSERT_EQ(s.exit_code, 0) << s.output;
      const auto a = read_json(d / single / "result.json");
      char point[32];
      std::snprintf(point, sizeof point, "point_%04d", i);
      const auto b = read_json(d / "sweep" / point / "result.json");
      for (const char* key : {"phi0_rad", "max_hoop_stress_Pa"})
        EXPECT_NEAR(b[key].get<double>(), a[key].get<double>(), 1e-12 * std::abs(a[key].get<double>())) << point;
      std::stringstream fields(line);
      std::string idx, w, t, phi0;
      std::getline(fields, idx, ',');
      std::getline(fields, w, ',');
      std::getline(fields, t, ',');
      std::getline(fields, phi0, ',');
      EXPECT_EQ(std::stoi(idx), i);
      EXPECT_DOUBLE_EQ(std::stod(w), wall);
      EXPECT_DOUBLE_EQ(std::stod(t), torque);
      EXPECT_NEAR(std::stod(phi0), a["phi0_rad"].get<double>(), 1e-9 * std::abs(a["phi0_rad"].get<double>()));
      ++i;
    }
  EXPECT_TRUE(fs::exists(d / "sweep" / "sweep.svg"));
  fs::remove_all(d);
}

// Shard 1/2 runs the even points and writes no table; the merging call runs only the odd ones; a point whose result
// is lost (an interrupted run) is the only one run again; a point whose case changed is rerun.
TEST(Sweep, ResumesAndMergesShards) {
  const fs::path d = fresh_dir("resume");
  write(d / "base.toml", tube_case(1.0, 10.0));
  const std::string sweep =
      "sweep " + (d / "base.toml").string() + " --set flexspline.wall_thickness_mm=0.8:1.2:5 --out " + (d / "s").string();
  CommandRun r = run_strainwave(sweep + " --shard 1/2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("3 points run"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(d / "s" / "sweep.csv"));
  r = run_strainwave(sweep);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 points run"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3 finished before"), std::string::npos) << r.output;
  const auto before = read_json(d / "s" / "point_0002" / "result.json");
  fs::remove(d / "s" / "point_0002" / "result.json");
  r = run_strainwave(sweep);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 points run"), std::string::npos) << r.output;
  EXPECT_EQ(read_json(d / "s" / "point_0002" / "result.json")["phi0_rad"], before["phi0_rad"]);
  write(d / "base.toml", tube_case(1.0, 20.0));  // every point's case changes
  r = run_strainwave(sweep);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("5 points run"), std::string::npos) << r.output;
  fs::remove_all(d);
}

TEST(Sweep, BadInputIsOneLine) {
  const fs::path d = fresh_dir("bad");
  write(d / "base.toml", tube_case(1.0, 10.0));
  const std::string base = "sweep " + (d / "base.toml").string() + " --out " + (d / "s").string();
  for (const auto& [args, expect] :
       {std::pair<std::string, std::string>{" --set flexspline.wall_thickness_mm=0.8:1.2", "expected TABLE.KEY=FROM:TO:N"},
        {" --set wall_thickness_mm=0.8:1.2:3", "expected TABLE.KEY=FROM:TO:N"},
        {" --set flexspline.wall_thicknes_mm=0.8:1.2:3", "wall_thicknes_mm"},
        {" --set flexspline.wall_thickness_mm=-1:1.2:3", "wall_thickness_mm"},
        {" --set flexspline.wall_thickness_mm=0.8:1.2:3 --shard 3/2", "--shard 3/2"}}) {
    const CommandRun r = run_strainwave(base + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(expect), std::string::npos) << args << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(d / "s" / "sweep.csv"));
  }
  fs::remove_all(d);
}

}  // namespace
