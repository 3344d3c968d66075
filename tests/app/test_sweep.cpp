// `strainwave sweep` through the CLI: a 3 × 3 sweep gives the numbers of the 9 single runs, an interrupted sweep
// (shards, a lost point) resumes without rerunning finished points, bad --set / --shard give one line and exit 2;
// --contact gives each point's drive figures as its contact.json has them and resumes the same way.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

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

// Bad --set / --shard and a case `contact` cannot take under --contact (no [gear]): one line,
// exit 2, before any point's folder is made.
TEST(Sweep, BadInputIsOneLine) {
  const fs::path d = fresh_dir("bad");
  write(d / "base.toml", tube_case(1.0, 10.0));
  const std::string base = "sweep " + (d / "base.toml").string() + " --out " + (d / "s").string();
  for (const auto& [args, expect] :
       {std::pair<std::string, std::string>{" --set flexspline.wall_thickness_mm=0.8:1.2", "expected TABLE.KEY=FROM:TO:N"},
        {" --set wall_thickness_mm=0.8:1.2:3", "expected TABLE.KEY=FROM:TO:N"},
        {" --set flexspline.wall_thicknes_mm=0.8:1.2:3", "wall_thicknes_mm"},
        {" --set flexspline.wall_thickness_mm=-1:1.2:3", "wall_thickness_mm"},
        {" --set flexspline.wall_thickness_mm=0.8:1.2:3 --shard 3/2", "--shard 3/2"},
        {" --set flexspline.wall_thickness_mm=0.8:1.2:3 --contact", "base.toml: contact needs a [gear] table"},
        {" --set flexspline.wall_thickness_mm=0.8:1.2:3 --datasheet --solver tet10",
         "--solver tet10 with --datasheet; the sheet reads the harmonic solver (drop --solver)"}}) {
    const CommandRun r = run_strainwave(base + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(expect), std::string::npos) << args << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_FALSE(fs::exists(d / "s"));  // refused before any point's folder
  }
  fs::remove_all(d);
}

// The designed size-14 cup on a coarse mesh (element size d/20, one layer, no clamp-corner grading, as the robustness
// runs of `contact`): about 10 s a point on one core.
fs::path coarse_cup14(const fs::path& dir) {
  const fs::path designed = dir / "designed.toml", base = dir / "base.toml";
  const CommandRun d = run_strainwave("design --size 14 --out " + designed.string());
  if (d.exit_code != 0) throw std::runtime_error("design --size 14: " + d.output);
  write(base, read_text(designed) + "\n[mesh]\nsize_mm = 1.778\nwall_layers = 1\ncorner_levels = 0\n");
  return base;
}

/// sweep.csv's rows as column name → value.
std::vector<std::map<std::string, double>> csv_rows(const fs::path& csv) {
  std::ifstream in(csv);
  std::string line, cell;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::stringstream h(line); std::getline(h, cell, ',');) names.push_back(cell);
  std::vector<std::map<std::string, double>> rows;
  while (std::getline(in, line)) {
    std::map<std::string, double> row;
    std::stringstream r(line);
    for (const auto& n : names)
      if (std::getline(r, cell, ',')) row[n] = std::stod(cell);
    rows.push_back(row);
  }
  return rows;
}

/// The twist (arcmin) at `torque_Nm` on contact.json's torque_twist, linear between the points around it.
double twist_on_curve_arcmin(const nlohmann::json& torque_twist, double torque_Nm) {
  for (std::size_t i = 1; i < torque_twist.size(); ++i) {
    const double t0 = torque_twist[i - 1]["torque_Nm"], t1 = torque_twist[i]["torque_Nm"];
    if (t0 <= torque_Nm && torque_Nm <= t1 && t0 < t1) {
      const double p0 = torque_twist[i - 1]["twist_rad"], p1 = torque_twist[i]["twist_rad"];
      return (p0 + (p1 - p0) * (torque_Nm - t0) / (t1 - t0)) * 10800 / std::numbers::pi;
    }
  }
  throw std::runtime_error("torque " + std::to_string(torque_Nm) + " outside the curve");
}

// sweep.csv prints 10 significant digits: a figure read back from it equals the file's to 1e-9 of its size.
constexpr double kCsvDigits = 1e-9;

void expect_csv_equals(double csv, double file, const std::string& what) {
  EXPECT_NEAR(csv, file, kCsvDigits * std::max(1e-300, std::abs(file))) << what;
}

// Two wall thicknesses of a coarse designed cup with --contact: every drive column of sweep.csv is the point's
// contact.json figure (the twist at T1 and T2 read on its torque–twist curve at contact.json's catalog T1 and T2, the
// largest flank force at +rated the headline's), the thicker wall twists less, the plot has the drive's panels; a
// second call reruns nothing, and a point that lost its contact.json is the only one run again.
TEST(Sweep, ContactOutputsPerPointAndResume) {
  const fs::path d = fresh_dir("contact");
  const std::string sweep = "sweep " + coarse_cup14(d).string() +
                            " --contact --jobs 2 --set flexspline.wall_thickness_mm=0.30:0.40:2 --out " +
                            (d / "s").string();
  CommandRun r = run_strainwave(sweep);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 points run"), std::string::npos) << r.output;
  const auto rows = csv_rows(d / "s" / "sweep.csv");
  ASSERT_EQ(rows.size(), 2u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const fs::path point = d / "s" / ("point_000" + std::to_string(i));
    const auto k = read_json(point / "contact.json");
    const auto& row = rows[i];
    for (const char* key : {"T1_Nm", "T2_Nm", "K1_Nm_per_rad", "K2_Nm_per_rad", "K3_Nm_per_rad"}) {
      ASSERT_TRUE(row.count(std::string("catalog.") + key)) << key;
      expect_csv_equals(row.at(std::string("catalog.") + key), k["catalog"][key], key);
    }
    for (const char* key : {"twist_at_rated_arcmin", "lost_motion_arcmin", "play_arcmin"}) {
      ASSERT_TRUE(row.count(key)) << key;
      expect_csv_equals(row.at(key), k[key], key);
    }
    for (const char* part : {"body", "teeth", "generator", "circular_spline"}) {
      ASSERT_TRUE(row.count(std::string("compliance_split.") + part)) << part;
      expect_csv_equals(row.at(std::string("compliance_split.") + part), k["compliance_split"][part], part);
    }
    expect_csv_equals(row.at("twist_at_T1_arcmin"), twist_on_curve_arcmin(k["torque_twist"], k["catalog"]["T1_Nm"]),
                      "twist at T1");
    expect_csv_equals(row.at("twist_at_T2_arcmin"), twist_on_curve_arcmin(k["torque_twist"], k["catalog"]["T2_Nm"]),
                      "twist at T2");
    double largest = 0;
    for (const auto& f : k["flanks"]) largest = std::max(largest, f["force_at_plus_rated_N"].get<double>());
    expect_csv_equals(row.at("max_flank_force_at_rated_N"), largest, "largest flank force");
    expect_csv_equals(row.at("max_flank_force_at_rated_N"), k["torque_twist"].back()["max_pair_force_N"],
                      "largest flank force, the last step's");
    expect_csv_equals(row.at("phi0_rad"), read_json(point / "result.json")["phi0_rad"], "phi0");
  }
  EXPECT_LT(rows[1].at("twist_at_rated_arcmin"), rows[0].at("twist_at_rated_arcmin"));
  const std::string svg = read_text(d / "s" / "sweep.svg");
  EXPECT_NE(svg.find("twist at rated torque (arcmin)"), std::string::npos);
  EXPECT_NE(svg.find("K3 (N·m/rad)"), std::string::npos);

  r = run_strainwave(sweep);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("0 points run"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2 finished before"), std::string::npos) << r.output;
  fs::remove(d / "s" / "point_0001" / "contact.json");
  r = run_strainwave(sweep);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 points run"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(d / "s" / "point_0001" / "contact.json"));
  fs::remove_all(d);
}

// Two wall thicknesses of the coarse designed cup with --datasheet: each point's sheet (its datasheet.json), every
// figure a column of sweep.csv under its key, equal to the file's to the csv's digits (not computed: nan); the
// thinner body wall buckles at a lower torque; the plot has the sheet's panels; a second call reruns nothing.
TEST(Sweep, DatasheetPerPointAndResume) {
  const fs::path d = fresh_dir("datasheet");
  const std::string sweep = "sweep " + coarse_cup14(d).string() +
                            " --datasheet --jobs 1 --set flexspline.wall_thickness_mm=0.30:0.40:2 --out " +
                            (d / "s").string();
  CommandRun r = run_strainwave(sweep);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 points run"), std::string::npos) << r.output;
  const auto rows = csv_rows(d / "s" / "sweep.csv");
  ASSERT_EQ(rows.size(), 2u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto sheet = read_json(d / "s" / ("point_000" + std::to_string(i)) / "datasheet.json");
    for (const auto& [name, f] : sheet["figures"].items()) {
      ASSERT_TRUE(rows[i].count(name)) << name;
      if (!f["computed"].get<bool>()) EXPECT_TRUE(std::isnan(rows[i].at(name))) << name;
      else if (f["value"].is_null()) EXPECT_TRUE(std::isinf(rows[i].at(name))) << name;  // beyond the search
      else expect_csv_equals(rows[i].at(name), f["value"], name.c_str());
    }
  }
  EXPECT_LT(rows[0].at("buckling_torque_Nm"), rows[1].at("buckling_torque_Nm"));
  const std::string svg = read_text(d / "s" / "sweep.svg");
  for (const char* panel : {"buckling torque (N·m)", "ratcheting torque (N·m)", "generator bearing L10 (h)"})
    EXPECT_NE(svg.find(panel), std::string::npos) << panel;
  r = run_strainwave(sweep);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("0 points run"), std::string::npos) << r.output;
  fs::remove_all(d);
}

}  // namespace
