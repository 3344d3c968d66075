// The reconcile and synth commands through the CLI: synth writes a recording and its truth, reconcile names the hidden
// effect and writes reconcile.json/html; a bad recording gives one line with the line number, a non-zero exit and
// no output files; a torsion recording held against the contact stage's torque-twist curve (--baseline contact).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/cli.hpp"

namespace fs = std::filesystem;

namespace {

using namespace sw::testing;

/// Runs `strainwave ARGS`; a test failure showing its output when it does not exit 0.
void expect_success(const std::string& args) {
  const CommandRun r = run_strainwave(args);
  ASSERT_EQ(r.exit_code, 0) << args << "\n" << r.output;
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
  ASSERT_TRUE(fs::exists(strainwave_binary())) << strainwave_binary();
  const fs::path d = scratch("harmonic");
  std::ofstream(d / "case.toml") << kCase;
  ASSERT_NO_FATAL_FAILURE(expect_success("--quiet synth --kind transmission --case " + (d / "case.toml").string() +
               " --effect wg_harmonic:order=2 --concealment 1 --seed 5 --out " + (d / "rec.csv").string()));
  ASSERT_TRUE(fs::exists(d / "rec.truth.json"));
  ASSERT_NO_FATAL_FAILURE(expect_success("--quiet reconcile " + (d / "case.toml").string() + " " + (d / "rec.csv").string() +
               " --out " + (d / "out").string()));
  const auto j = nlohmann::json::parse(read_text(d / "out" / "reconcile.json"));
  EXPECT_EQ(j["verdict"], "explained");
  ASSERT_EQ(j["effects"].size(), 1u);
  EXPECT_EQ(j["effects"][0]["name"], "wg_harmonic");
  EXPECT_EQ(j["effects"][0]["params"]["order"], 2);
  const std::string html = read_text(d / "out" / "reconcile.html");
  EXPECT_NE(html.find("<svg"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);  // self-contained
}

TEST(ReconcileCli, SynthDynamicsThenReconcileNamesTheDragTorque) {
  ASSERT_TRUE(fs::exists(strainwave_binary())) << strainwave_binary();
  const fs::path d = scratch("dynamics");
  // Frozen pairs: the seed gear's 190 moving teeth take 15 s per run and the experiment needs ~40 runs (the moving
  // pairs' proofs are in test_dynamics.cpp, on the 26/28 gear); the default rim = "fem" would also solve the FEM.
  std::ofstream(d / "case.toml") << kCase
                                 << "[dynamics]\npairs = \"frozen\"\nduration_s = 0.04\nsteady_from_s = 0.02\n";
  ASSERT_NO_FATAL_FAILURE(expect_success("--quiet synth --kind dynamics --case " + (d / "case.toml").string() +
               " --effect drag_torque:coulomb_Nm=2 --concealment 2 --seed 5 --out " + (d / "rec.csv").string()));
  const auto truth = nlohmann::json::parse(read_text(d / "rec.truth.json"));
  ASSERT_NO_FATAL_FAILURE(expect_success("--quiet reconcile " + (d / "case.toml").string() + " " + (d / "rec.csv").string() +
               " --out " + (d / "out").string()));
  const auto j = nlohmann::json::parse(read_text(d / "out" / "reconcile.json"));
  EXPECT_EQ(j["kind"], "dynamics");
  ASSERT_EQ(j["effects"].size(), 1u);
  EXPECT_EQ(j["effects"][0]["name"], "drag_torque");
  const double want = truth["effects"][0]["params"]["torque_at_speed_Nm"].get<double>();
  const double got = j["effects"][0]["params"]["torque_at_speed_Nm"].get<double>();
  EXPECT_NEAR(got, want, 0.25 * want);
}

TEST(ReconcileCli, ShippedSize17RecordingGivesTheCatalogBlockBesideTheCatalogRow) {
  ASSERT_TRUE(fs::exists(strainwave_binary())) << strainwave_binary();
  const fs::path d = scratch("size17");
  ASSERT_NO_FATAL_FAILURE(expect_success("--quiet reconcile cases/cup_size17.toml cases/recordings/size17_torsion.csv "
               "--compliance 1.89e-5 --out " + (d / "out").string()));
  const auto j = nlohmann::json::parse(read_text(d / "out" / "reconcile.json"));
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
  EXPECT_NE(read_text(d / "out" / "reconcile.html").find("In catalog terms"), std::string::npos);
}

TEST(ReconcileCli, SynthEffectsWritesSeveralEffectsWithTheirTruth) {
  ASSERT_TRUE(fs::exists(strainwave_binary())) << strainwave_binary();
  const fs::path d = scratch("effects");
  ASSERT_NO_FATAL_FAILURE(expect_success("--quiet synth --kind torsion --effects "
               "series_compliance,hysteresis:loss_rad=2e-4,transition_Nm=2,lost_motion --meta size=17 --out " +
               (d / "rec.csv").string()));
  const auto truth = nlohmann::json::parse(read_text(d / "rec.truth.json"));
  ASSERT_EQ(truth["effects"].size(), 3u);
  EXPECT_EQ(truth["effects"][1]["name"], "hysteresis");
  EXPECT_EQ(truth["effects"][1]["params"]["transition_Nm"], 2.0);
  EXPECT_NE(read_text(d / "rec.csv").find("# size: 17\n"), std::string::npos);
}

TEST(ReconcileCli, BadRecordingFailsWithTheLineAndWritesNothing) {
  ASSERT_TRUE(fs::exists(strainwave_binary())) << strainwave_binary();
  const fs::path d = scratch("bad");
  std::ofstream(d / "case.toml") << kCase;
  std::ofstream(d / "bad.csv") << "# strainwave-recording: 1\n# kind: transmission\ntime_s,wg_angle_rad,output_angle_rad\n"
                                  "0,0,0\n0.1,0.1,x\n";
  const CommandRun r = run_strainwave("reconcile " + (d / "case.toml").string() + " " + (d / "bad.csv").string() +
                                      " --out " + (d / "out").string());
  EXPECT_NE(r.exit_code, 0);
  const std::string& err = r.err;
  EXPECT_NE(err.find("bad.csv:5: output_angle_rad = 'x'; expected a finite number"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(d / "out" / "reconcile.json"));
}

// --baseline contact: a torsion recording held against the drive's torque-twist curve (contact.json) instead of
// C_tau T. The curve here is the size-17 catalog law written by hand as the contact stage writes it (a three-segment
// loop from -rated to +rated and back); the recording is that law plus friction (Dahl-type, 0.6 arcmin loss) under
// the shipped recordings' 22-bit encoder noise.
namespace {

constexpr double kK1 = 1.0e4, kK2 = 1.4e4, kK3 = 1.6e4, kT1 = 3.9, kT2 = 12.0, kRated = 31.0;

double catalog_law(double T) {
  const double a = std::abs(T);
  const double phi = std::min(a, kT1) / kK1 + std::clamp(a - kT1, 0.0, kT2 - kT1) / kK2 + std::max(a - kT2, 0.0) / kK3;
  return T < 0 ? -phi : phi;
}

/// A folder with the case, contact.json (the law, both branches, no friction) and result.json whose C_tau is a third
/// of the drive's last-segment compliance (the flexspline body alone is about 3x stiffer than the whole drive).
fs::path contact_fixture(const std::string& name) {
  const fs::path d = scratch(name);
  std::ofstream(d / "contact_case.toml") << kCase;
  nlohmann::json j;
  j["rated_torque_Nm"] = kRated;
  j["catalog"] = {{"T1_Nm", kT1}, {"T2_Nm", kT2}, {"K1_Nm_per_rad", kK1}, {"K2_Nm_per_rad", kK2}, {"K3_Nm_per_rad", kK3}};
  j["play_arcmin"] = 0.0;
  j["lost_motion_arcmin"] = 2 * catalog_law(0.04 * kRated) * 10800.0 / M_PI;
  j["torque_twist"] = nlohmann::json::array();
  for (double t : {-31.0, -12.0, -3.9, 0.0, 3.9, 12.0, 31.0, 12.0, 3.9, 0.0, -3.9, -12.0, -31.0})
    j["torque_twist"].push_back({{"torque_Nm", t}, {"twist_rad", catalog_law(t)}, {"pairs_in_contact", 8},
                                 {"max_pair_force_N", 40.0 * std::abs(t)}});
  std::ofstream(d / "contact.json") << j.dump(1);
  std::ofstream(d / "result.json") << nlohmann::json{{"compliance_rad_per_Nm", 1.0 / (3.0 * kK3)}}.dump();
  return d;
}

/// `strainwave synth`: the catalog law (stiffness_nonlinearity on C = 1/K3 is the whole law) plus friction, to
/// +-`torque` N*m.
void synth_law_with_friction(const fs::path& d, double torque) {
  char args[640];
  std::snprintf(args, sizeof args,
                "--quiet synth --kind torsion --compliance %.10g --torque %g --effects "
                "stiffness_nonlinearity:K1_Nm_per_rad=%g,K2_Nm_per_rad=%g,K3_Nm_per_rad=%g,T1_Nm=%g,T2_Nm=%g,"
                "hysteresis:loss_rad=1.745e-4,transition_Nm=1.5 --white 2.42e-6 --ar1 4.85e-6 --ar1-phi 0.9 "
                "--quantum 1.498e-6 --seed 23 --meta size=17 --meta rated_torque_Nm=31 --out %s",
                1.0 / kK3, torque, kK1, kK2, kK3, kT1, kT2, (d / "rec.csv").c_str());
  expect_success(args);
}

std::set<std::string> effect_names(const nlohmann::json& j) {
  std::set<std::string> s;
  for (const auto& e : j["effects"]) s.insert(e["name"].get<std::string>());
  return s;
}

}  // namespace

TEST(ReconcileContactBaseline, NamesOnlyTheFrictionTheCurveLacksWhileCTauTNamesTheStiffness) {
  const fs::path d = contact_fixture("contact_baseline");
  ASSERT_NO_FATAL_FAILURE(synth_law_with_friction(d, kRated));
  const std::string common = "--quiet reconcile " + (d / "contact_case.toml").string() + " " + (d / "rec.csv").string();
  ASSERT_NO_FATAL_FAILURE(expect_success(common + " --baseline contact --contact " + (d / "contact.json").string() +
                                         " --out " + (d / "contact").string()));
  const nlohmann::json c = read_json(d / "contact" / "reconcile.json");
  EXPECT_EQ(c["baseline"]["model"], "contact");
  EXPECT_EQ(c["baseline"]["source"], (d / "contact.json").string());
  EXPECT_EQ(c["verdict"], "explained");
  EXPECT_EQ(effect_names(c), std::set<std::string>{"hysteresis"}) << c["effects"].dump(1);
  // In catalog terms: the curve's own segments (secants of its straight segments: exact but for rounding; 1e-3) and
  // the friction loss within the 20 % the shipped recordings are held to.
  const auto& cat = c["catalog"];
  EXPECT_EQ(cat["segments"], 3);
  EXPECT_NEAR(cat["K1_Nm_per_rad"].get<double>(), kK1, 1e-3 * kK1);
  EXPECT_NEAR(cat["K2_Nm_per_rad"].get<double>(), kK2, 1e-3 * kK2);
  EXPECT_NEAR(cat["K3_Nm_per_rad"].get<double>(), kK3, 1e-3 * kK3);
  EXPECT_NEAR(cat["hysteresis_loss_arcmin"].get<double>(), 0.6, 0.2 * 0.6);
  EXPECT_NE(read_text(d / "contact" / "reconcile.html").find("torque-twist curve from the loaded tooth contact"),
            std::string::npos);

  // The same recording against C_tau T of the body alone: the rest of the drive is named as stiffness effects.
  ASSERT_NO_FATAL_FAILURE(expect_success(common + " --fem " + (d / "result.json").string() + " --out " +
                                         (d / "fem").string()));
  const nlohmann::json f = read_json(d / "fem" / "reconcile.json");
  EXPECT_EQ(f["baseline"]["model"], "fem");
  const std::set<std::string> named = effect_names(f);
  EXPECT_TRUE(named.count("series_compliance")) << f["effects"].dump(1);
  EXPECT_TRUE(named.count("stiffness_nonlinearity")) << f["effects"].dump(1);
  EXPECT_TRUE(named.count("hysteresis")) << f["effects"].dump(1);
  EXPECT_NEAR(f["catalog"]["K1_Nm_per_rad"].get<double>(), kK1, 0.15 * kK1);
  EXPECT_NEAR(f["catalog"]["K3_Nm_per_rad"].get<double>(), kK3, 0.15 * kK3);
}

TEST(ReconcileContactBaseline, TheShippedSize17LoopAgainstTheModelsCurveSaysWhatItMeansForTheDrive) {
  // The catalog loop of size 17 against the curve `strainwave contact cases/cup_size17.toml` computes (harmonic
  // solver, a few seconds): the model is stiffer and has more play (its profile shifts leave about 1.2 arcmin, the
  // drive 0.12). The drive's law is one effect, not stacked on series compliance; the play is said as the model's
  // excess with the key that sets it; the law's last slope, which holds the series compliance, has an interval.
  const fs::path d = scratch("size17_contact");
  ASSERT_NO_FATAL_FAILURE(expect_success("--quiet contact cases/cup_size17.toml --out " + (d / "model").string()));
  const CommandRun r = run_strainwave("reconcile cases/cup_size17.toml cases/recordings/size17_torsion.csv --baseline "
                                      "contact --contact " + (d / "model" / "contact.json").string() + " --out " +
                                      (d / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json j = read_json(d / "out" / "reconcile.json");
  EXPECT_EQ(effect_names(j), (std::set<std::string>{"stiffness_nonlinearity", "hysteresis", "lost_motion"}))
      << j["effects"].dump(1);
  for (const auto& e : j["effects"]) {
    if (e["name"] == "lost_motion") {
      EXPECT_LT(e["params"]["width_arcmin"].get<double>(), 0.0);
      const std::string meaning = e.value("meaning", "");
      EXPECT_EQ(meaning.rfind("the model has ", 0), 0u) << meaning;
      EXPECT_NE(meaning.find("gear.profile_shift_circular"), std::string::npos) << meaning;
    }
    if (e["name"] == "stiffness_nonlinearity") {
      EXPECT_TRUE(e["ci95"].contains("K3_Nm_per_rad")) << e.dump(1);
      EXPECT_TRUE(e["fixed"].empty()) << e.dump(1);
    }
  }
  bool held = false;
  for (const auto& x : j["rejected"])
    held = held || (x["name"] == "series_compliance" &&
                    x["reason"].get<std::string>().find("held in the last slope") != std::string::npos);
  EXPECT_TRUE(held) << j["rejected"].dump(1);
  EXPECT_NE(r.output.find("play: the model has "), std::string::npos) << r.output;
  EXPECT_NE(read_text(d / "out" / "reconcile.html").find("For the drive:"), std::string::npos);
}

TEST(ReconcileContactBaseline, MissingCurveOrTorqueBeyondItIsOneLineAndWritesNothing) {
  const fs::path d = contact_fixture("contact_errors");
  ASSERT_NO_FATAL_FAILURE(synth_law_with_friction(d, 40.0));
  const std::string common = "--quiet reconcile " + (d / "contact_case.toml").string() + " " + (d / "rec.csv").string() +
                             " --out " + (d / "out").string() + " --baseline contact";
  // No --contact: the default out/<case stem>/contact.json, which no contact run has written.
  CommandRun r = run_strainwave(common);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("out/contact_case/contact.json: cannot be read; give the contact.json written by `strainwave "
                       "contact"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  // The recording reaches +-40 N*m; the curve covers +-31 N*m.
  r = run_strainwave(common + " --contact " + (d / "contact.json").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("rec.csv: torque_Nm spans [-40, 40] N*m but the torque-twist curve of " +
                       (d / "contact.json").string() + " covers [-31, 31] N*m"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  // A curve given without --baseline contact would be silently unused: refused.
  r = run_strainwave("--quiet reconcile " + (d / "contact_case.toml").string() + " " + (d / "rec.csv").string() +
                     " --contact " + (d / "contact.json").string() + " --out " + (d / "out").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("the torque-twist curve is read only with --baseline contact"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(d / "out" / "reconcile.json"));
  EXPECT_FALSE(fs::exists(d / "out" / "reconcile.html"));
}
