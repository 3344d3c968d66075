// The reconcile and synth commands through the CLI: synth writes a recording and its truth, reconcile names the hidden
// effect and writes reconcile.json/html; a bad recording gives one line with the line number, a non-zero exit and
// no output files.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {

/// The strainwave binary of this build tree (compiled in, as in every CLI test: never a stale build/ elsewhere).
std::string binary() { return SW_STRAINWAVE_BINARY; }

int sh(const std::string& cmd) { return WEXITSTATUS(std::system(cmd.c_str())); }

std::string slurp(const fs::path& p) {
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("sw_reconcile_cli_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

const char* kCase =
    "[gear]\nmodule_mm = 0.2\nteeth_flexspline = 190\nteeth_circular = 192\npressure_angle_deg = 20.0\n"
    "profile_shift_flexspline = 1.52\nprofile_shift_circular = 1.57\ncutter_teeth = 80\n[flexspline]\nshape = \"cup\"\n";

}  // namespace

TEST(ReconcileCli, SynthThenReconcileNamesTheHiddenHarmonic) {
  ASSERT_TRUE(fs::exists(binary())) << binary();
  const fs::path d = scratch("harmonic");
  std::ofstream(d / "case.toml") << kCase;
  ASSERT_EQ(sh(binary() + " --quiet synth --kind transmission --case " + (d / "case.toml").string() +
               " --effect wg_harmonic:order=2 --concealment 1 --seed 5 --out " + (d / "rec.csv").string() +
               " > /dev/null"), 0);
  ASSERT_TRUE(fs::exists(d / "rec.truth.json"));
  ASSERT_EQ(sh(binary() + " --quiet reconcile " + (d / "case.toml").string() + " " + (d / "rec.csv").string() +
               " --out " + (d / "out").string() + " > /dev/null"), 0);
  const auto j = nlohmann::json::parse(slurp(d / "out" / "reconcile.json"));
  EXPECT_EQ(j["verdict"], "explained");
  ASSERT_EQ(j["effects"].size(), 1u);
  EXPECT_EQ(j["effects"][0]["name"], "wg_harmonic");
  EXPECT_EQ(j["effects"][0]["params"]["order"], 2);
  const std::string html = slurp(d / "out" / "reconcile.html");
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);  // self-contained
}

TEST(ReconcileCli, SynthDynamicsThenReconcileNamesTheDragTorque) {
  ASSERT_TRUE(fs::exists(binary())) << binary();
  const fs::path d = scratch("dynamics");
  std::ofstream(d / "case.toml") << kCase << "[dynamics]\nduration_s = 0.04\nsteady_from_s = 0.02\n";
  ASSERT_EQ(sh(binary() + " --quiet synth --kind dynamics --case " + (d / "case.toml").string() +
               " --effect drag_torque:coulomb_Nm=2 --concealment 2 --seed 5 --out " + (d / "rec.csv").string() +
               " > /dev/null"), 0);
  const auto truth = nlohmann::json::parse(slurp(d / "rec.truth.json"));
  ASSERT_EQ(sh(binary() + " --quiet reconcile " + (d / "case.toml").string() + " " + (d / "rec.csv").string() +
               " --out " + (d / "out").string() + " > /dev/null"), 0);
  const auto j = nlohmann::json::parse(slurp(d / "out" / "reconcile.json"));
  EXPECT_EQ(j["kind"], "dynamics");
  ASSERT_EQ(j["effects"].size(), 1u);
  EXPECT_EQ(j["effects"][0]["name"], "drag_torque");
  const double want = truth["effects"][0]["params"]["torque_at_speed_Nm"].get<double>();
  const double got = j["effects"][0]["params"]["torque_at_speed_Nm"].get<double>();
  EXPECT_NEAR(got, want, 0.25 * want);
}

TEST(ReconcileCli, ShippedSize17RecordingGivesTheCatalogBlockBesideTheCatalogRow) {
  ASSERT_TRUE(fs::exists(binary())) << binary();
  const fs::path d = scratch("size17");
  ASSERT_EQ(sh(binary() + " --quiet reconcile cases/cup_size17.toml cases/recordings/size17_torsion.csv "
               "--compliance 1.89e-5 --out " + (d / "out").string() + " > /dev/null"), 0);
  const auto j = nlohmann::json::parse(slurp(d / "out" / "reconcile.json"));
  EXPECT_EQ(j["verdict"], "explained");
  ASSERT_TRUE(j.contains("catalog"));
  const auto& c = j["catalog"];
  EXPECT_EQ(c["segments"], 3);
  EXPECT_EQ(c["reference"]["size"], 17);
  EXPECT_EQ(c["rated_torque_Nm"], 31.0);
  // The truth (the recording's metadata): K1 1.0e4, K2 1.4e4, K3 1.6e4 N*m/rad, 0.6 arcmin loss, 0.12 arcmin play.
  EXPECT_NEAR(c["K1_Nm_per_rad"].get<double>(), 1.0e4, 0.15 * 1.0e4);
  EXPECT_NEAR(c["K3_Nm_per_rad"].get<double>(), 1.6e4, 0.15 * 1.6e4);
  EXPECT_NEAR(c["hysteresis_loss_arcmin"].get<double>(), 0.6, 0.2 * 0.6);
  EXPECT_NEAR(c["play_width_arcmin"].get<double>(), 0.12, 0.2 * 0.12);
  EXPECT_GT(c["catalog_lost_motion_arcmin"].get<double>(), c["play_width_arcmin"].get<double>());
  EXPECT_NE(slurp(d / "out" / "reconcile.html").find("In catalog terms"), std::string::npos);
}

TEST(ReconcileCli, SynthEffectsWritesSeveralEffectsWithTheirTruth) {
  ASSERT_TRUE(fs::exists(binary())) << binary();
  const fs::path d = scratch("effects");
  ASSERT_EQ(sh(binary() + " --quiet synth --kind torsion --effects "
               "series_compliance,hysteresis:loss_rad=2e-4,transition_Nm=2,lost_motion --meta size=17 --out " +
               (d / "rec.csv").string() + " > /dev/null"), 0);
  const auto truth = nlohmann::json::parse(slurp(d / "rec.truth.json"));
  ASSERT_EQ(truth["effects"].size(), 3u);
  EXPECT_EQ(truth["effects"][1]["name"], "hysteresis");
  EXPECT_EQ(truth["effects"][1]["params"]["transition_Nm"], 2.0);
  EXPECT_NE(slurp(d / "rec.csv").find("# size: 17\n"), std::string::npos);
}

TEST(ReconcileCli, BadRecordingFailsWithTheLineAndWritesNothing) {
  ASSERT_TRUE(fs::exists(binary())) << binary();
  const fs::path d = scratch("bad");
  std::ofstream(d / "case.toml") << kCase;
  std::ofstream(d / "bad.csv") << "# strainwave-recording: 1\n# kind: transmission\ntime_s,wg_angle_rad,output_angle_rad\n"
                                  "0,0,0\n0.1,0.1,x\n";
  const int rc = sh(binary() + " reconcile " + (d / "case.toml").string() + " " + (d / "bad.csv").string() +
                    " --out " + (d / "out").string() + " 2> " + (d / "err.txt").string() + " > /dev/null");
  EXPECT_NE(rc, 0);
  const std::string err = slurp(d / "err.txt");
  EXPECT_NE(err.find("bad.csv:5: output_angle_rad = 'x'; expected a finite number"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(d / "out" / "reconcile.json"));
}
