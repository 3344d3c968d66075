// `strainwave datasheet` through the command line: the sheet of the size-17 case carries the loaded contact's
// figures as `contact` computes them, the catalog's published figures for its size and ratio beside them (never in
// place of them), reads back as written, and bad input is one line with nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "tests/cli.hpp"

namespace sw {
namespace {

namespace fs = std::filesystem;
using testing::read_json;
using testing::run_strainwave;

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("sw_datasheet_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}

fs::path sheet_dir() { return scratch("17"); }

// One run of each command serves every check below (ctest runs each test in a process of its own: one datasheet and
// one contact run, not one per check).
TEST(Size17Sheet, CarriesTheContactsFiguresThePublishedRowsAndSaysHowEachWasComputed) {
  const fs::path dir = sheet_dir(), contact_dir = dir.string() + "_c";
  const auto run = run_strainwave("datasheet cases/cup_size17.toml --quiet --out " + dir.string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto contact_run = run_strainwave("contact cases/cup_size17.toml --quiet --no-vtk --out " + contact_dir.string());
  ASSERT_EQ(contact_run.exit_code, 0) << contact_run.output;

  // Its files and the printed table.
  for (const char* f : {"datasheet.json", "datasheet.html", "buckling.vtu"}) EXPECT_TRUE(fs::exists(dir / f)) << f;
  for (const char* label : {"rated torque", "K3", "buckling torque", "torque for infinite life", "generator bearing L10"})
    EXPECT_NE(run.out.find(label), std::string::npos) << label << " in\n" << run.out;

  // The sheet's stiffness and lost motion are the loaded contact's, read from the same analysis: equal to
  // contact.json's to the JSON's precision (a contract between the two commands, not a verification of the figures,
  // which test_loaded_contact and test_torque_twist hold against closed forms).
  const auto sheet = read_json(dir / "datasheet.json");
  const auto contact = read_json(contact_dir / "contact.json");
  const auto& f = sheet["figures"];
  for (const char* k : {"K1_Nm_per_rad", "K2_Nm_per_rad", "K3_Nm_per_rad"})
    EXPECT_NEAR(f[k]["value"].get<double>(), contact["catalog"][k].get<double>(),
                1e-9 * contact["catalog"][k].get<double>())
        << k;
  EXPECT_NEAR(f["lost_motion_arcmin"]["value"].get<double>(), contact["lost_motion_arcmin"].get<double>(), 1e-9);

  // The published figures are the reference's rows for size 17 at ratio 100 (shared/reference), beside the computed.
  EXPECT_EQ(f["K3_Nm_per_rad"]["published"].get<double>(), 1.6e4);
  EXPECT_EQ(f["buckling_torque_Nm"]["published"].get<double>(), 330);
  EXPECT_EQ(f["ratcheting_torque_Nm"]["published"].get<double>(), 160);
  EXPECT_EQ(f["bearing_life_L10_h"]["published"].get<double>(), 7000);
  EXPECT_EQ(f["rated_torque_Nm"]["value"].get<double>(), 31);
  EXPECT_NE(f["K3_Nm_per_rad"]["value"].get<double>(), 1.6e4);  // computed, not copied

  // Every figure says how it was computed or why not; a figure not computed has no value.
  EXPECT_TRUE(sheet.contains("case") && sheet.contains("version"));
  for (const auto& [name, x] : f.items()) {
    EXPECT_FALSE(x["method"].get<std::string>().empty()) << name;
    if (!x["computed"].get<bool>()) EXPECT_TRUE(x["value"].is_null()) << name;
  }
  fs::remove_all(dir);
  fs::remove_all(contact_dir);
}

TEST(DatasheetErrors, ACaseWithoutTeethIsRefusedInOneLineBeforeAnyWork) {
  const fs::path dir = scratch("tube");
  const auto run = run_strainwave("datasheet cases/tube_torsion.toml --quiet --out " + dir.string());
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("cases/tube_torsion.toml"), std::string::npos) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_FALSE(fs::exists(dir / "datasheet.json"));
}

}  // namespace
}  // namespace sw
