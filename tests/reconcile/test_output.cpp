// reconcile.json: the report of an analysis has exactly SPEC.md's keys, and what io writes reads back to the same
// report (every field, the optional ones present and absent).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "common/progress.hpp"
#include "io/reconcile_output.hpp"
#include "reconcile/verdict.hpp"

using namespace sw::reconcile;

namespace {

/// A result with every part of the report filled: a located and an unexplained signature, a harmonic (its order) and
/// an effect with intervals, one refitted on re-runs of the model, a rejected effect, a baseline source and the catalog block with the catalog's row.
Result full_result() {
  Result r;
  r.kind = Kind::Torsion;
  r.samples = 4000;
  r.baseline_model = "contact";
  r.baseline_source = "out/case/contact.json";
  r.baseline_rms = 1.25e-3;
  r.baseline_heldout_rms = 1.5e-3;
  r.final_rms = 5.1e-6;
  r.final_heldout_rms = 4.9e-6;
  r.significant = true;
  r.locations.push_back({.domain = "torque", .description = "residual bends with torque", .p_value = 1e-40});
  r.unexplained.push_back({.domain = "time", .description = "slow drift", .p_value = 2e-3});
  r.effects.push_back({"wg_harmonic", "a line", {{"order", 2, 2, 2}, {"amplitude_rad", 3e-5, 2.9e-5, 3.1e-5}},
                       -120.5, 1e-9, "F"});
  r.effects.push_back({"hysteresis", "friction", {{"loss_rad", 1.75e-4, 1.7e-4, 1.8e-4}}, -3104.3, 3.6e-84, "F"});
  r.effects.push_back({"stiffness_nonlinearity", "soft start",
                       {{"K1_Nm_per_rad", 1.0e4, 0.9e4, 1.1e4}, {"T1_Nm", 3.9, 3.5, 4.3},
                        {"K2_Nm_per_rad", 2.0e4, 2.0e4, 2.0e4, "1/C_tau, the baseline's compliance"}},
                       -500.0, 1e-20, "F"});
  // A part the data do not bound: its interval is what it can be at all, [0, inf) (the end written null).
  AcceptedEffect drag{"drag_torque", "drag",
                      {{"torque_at_speed_Nm", 2.0, 1.9, 2.1}, {"coulomb_Nm", 1.0, 0.0, INFINITY}}, -80.0, 1e-12, "F"};
  drag.model_discrepancy = 0.19;  // refitted on re-runs of the model
  drag.model_runs = 9;
  r.effects.push_back(drag);
  r.rejected.push_back({"lost_motion", "lost_motion: BIC changes by 2.0"});
  r.catalog = CatalogFigures{.segments = 3, .k1 = 1.0e4, .k2 = 1.4e4, .k3 = 1.6e4, .t1 = 3.9, .t2 = 12.0,
                             .rated_torque_Nm = 31.0, .rated_from = "metadata rated_torque_Nm",
                             .hysteresis_loss_arcmin = 0.6, .play_arcmin = 0.12, .catalog_lost_motion_arcmin = 0.97,
                             .reference = catalog_stiffness(17)};
  r.verdict = "partly_explained";
  return r;
}

}  // namespace

TEST(Report, JsonHasExactlyTheSpecKeys) {
  Result r;
  r.verdict = "no_significant_mismatch";
  Location l;
  l.domain = "torque";
  r.locations.push_back(l);
  AcceptedEffect e;
  e.name = "hysteresis";
  e.params = {{"loss_rad", 1e-4, 0.9e-4, 1.1e-4}};
  r.effects.push_back(e);
  r.rejected.push_back({"lost_motion", "x"});
  const auto j = nlohmann::json::parse(sw::reconcile_json(report_of(r)));
  std::vector<std::string> keys;
  for (const auto& [k, v] : j.items()) keys.push_back(k);
  EXPECT_EQ(keys, (std::vector<std::string>{"baseline", "effects", "final", "kind", "mismatch", "rejected", "samples",
                                            "verdict"}));
  EXPECT_TRUE(j["baseline"].contains("heldout_rms"));
  EXPECT_FALSE(j["baseline"].contains("source"));
  EXPECT_TRUE(j["mismatch"]["locations"][0].contains("p_value"));
  for (const char* k : {"name", "physics", "params", "ci95", "fixed", "delta_bic", "p_value"})
    EXPECT_TRUE(j["effects"][0].contains(k)) << k;
  EXPECT_EQ(j["effects"][0]["ci95"]["loss_rad"].size(), 2u);
}

TEST(Report, WritesTheOrderAsAnIntegerWithoutAnIntervalAndTheUnexplainedAsLocations) {
  const auto j = nlohmann::json::parse(sw::reconcile_json(report_of(full_result())));
  EXPECT_TRUE(j["effects"][0]["params"]["order"].is_number_integer());
  EXPECT_FALSE(j["effects"][0]["ci95"].contains("order"));
  ASSERT_EQ(j["mismatch"]["locations"].size(), 2u);
  EXPECT_EQ(j["mismatch"]["locations"][1]["description"], "unexplained after the final model: slow drift");
  EXPECT_EQ(j["baseline"]["source"], "out/case/contact.json");
  EXPECT_EQ(j["catalog"]["reference"]["size"], 17);
  // T1 / K1 over the final RMS: 3.9e-4 rad over 5.1e-6 rad.
  EXPECT_DOUBLE_EQ(j["catalog"]["K1_segment_twist_over_noise"].get<double>(), 3.9 / 1.0e4 / 5.1e-6);
}

TEST(Report, AHeldParameterIsWrittenAsFixedWithWhereItIsReadNotAsAZeroWidthInterval) {
  const Result r = full_result();
  const auto j = nlohmann::json::parse(sw::reconcile_json(report_of(r)));
  const auto& law = j["effects"][2];
  ASSERT_EQ(law["name"], "stiffness_nonlinearity");
  EXPECT_FALSE(law["ci95"].contains("K2_Nm_per_rad"));
  EXPECT_EQ(law["fixed"]["K2_Nm_per_rad"]["from"], "1/C_tau, the baseline's compliance");
  EXPECT_EQ(law["params"]["K2_Nm_per_rad"], 2.0e4);
  EXPECT_EQ(law["ci95"]["K1_Nm_per_rad"].size(), 2u);
  EXPECT_FALSE(law["fixed"].contains("K1_Nm_per_rad"));
  const std::string summary = report_summary(r);
  EXPECT_NE(summary.find("K2_Nm_per_rad = 2e+04 fixed (from 1/C_tau, the baseline's compliance)"), std::string::npos)
      << summary;
  EXPECT_EQ(summary.find("[2e+04, 2e+04]"), std::string::npos) << summary;
}

TEST(ReconcileJson, ReadsBackEveryFieldItWrote) {
  const Report written = report_of(full_result());
  ASSERT_TRUE(written.catalog && written.catalog->reference && written.catalog->k1_segment_twist_over_noise);
  const std::string text = sw::reconcile_json(written);
  const Report read = sw::parse_reconcile_json(text, "reconcile.json");
  EXPECT_EQ(read, written);
  EXPECT_EQ(sw::reconcile_json(read), text);
  EXPECT_EQ(read.effects[3].ci95.at("coulomb_Nm").second, INFINITY);
  EXPECT_NE(text.find("null"), std::string::npos);  // JSON has no inf
}

TEST(ReconcileJson, ReadsBackAReportWithoutTheOptionalParts) {
  Result r;
  r.kind = Kind::Transmission;
  r.samples = 4000;
  r.baseline_model = "ideal_ratio";
  r.verdict = "no_significant_mismatch";
  const Report written = report_of(r);
  ASSERT_FALSE(written.catalog.has_value());
  EXPECT_EQ(sw::parse_reconcile_json(sw::reconcile_json(written), "reconcile.json"), written);
}

TEST(ReconcileJson, ReadsBackTheAnalysisOfTheShippedSize17Recording) {
  sw::quiet_progress() = true;
  const Recording rec = load_recording("cases/recordings/size17_torsion.csv");
  Baseline base;
  base.prediction = TorsionPrediction{.compliance_rad_per_Nm = 1.89e-5};
  const Report written = report_of(reconcile(make_experiment(rec, base)));
  ASSERT_FALSE(written.effects.empty());
  ASSERT_TRUE(written.catalog.has_value());
  EXPECT_EQ(sw::parse_reconcile_json(sw::reconcile_json(written), "reconcile.json"), written);
}

TEST(ReconcileJson, AMissingKeyIsOneInputErrorNamingTheFile) {
  nlohmann::json j = nlohmann::json::parse(sw::reconcile_json(report_of(full_result())));
  j.erase("verdict");
  try {
    sw::parse_reconcile_json(j.dump(), "out/x/reconcile.json");
    FAIL() << "expected InputError";
  } catch (const sw::InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("out/x/reconcile.json: ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("verdict"), std::string::npos) << e.what();
  }
}
