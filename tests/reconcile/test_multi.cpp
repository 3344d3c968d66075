// Several effects at once, at high signal-to-noise, in catalog terms: the shipped recordings of catalog sizes
// (cases/recordings/, written by `strainwave synth` from the published stiffness laws with friction and play inside
// the catalog's limits and 22-bit encoder noise; two of the three with structures the fitter does not have: rounded
// corners, Bouc-Wen friction), multi-harmonic transmission and backlash recordings, and no invented time drift.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/progress.hpp"
#include "reconcile/effects.hpp"
#include "reconcile/reconcile.hpp"
#include "reconcile/synth.hpp"
#include "tests/reconcile/result_lookup.hpp"

using namespace sw::reconcile;
using namespace sw::reconcile::testing;

namespace {

/// Stiffness of each segment within 15 % (the catalog-figure target; the rounded corners of size 17 move the best straight
/// segments by a few per cent).
constexpr double kStiffnessTol = 0.15;
/// Hysteresis loss and play width within 20 % (friction structures other than the fitter's exponential included).
constexpr double kLossTol = 0.20;
/// Held-out RMS at the noise level within 20 % where the recording's friction is the fitter's law (Dahl); where it is
/// Bouc-Wen (sizes 14 and 20) the Dahl law cannot follow the branches' shape and what it leaves is the law's, not a
/// missing effect: within 70 % (size 14 leaves 1.61x the noise with one Dahl element; it had reached the noise only
/// with two elements of -134785 and +134786 arcmin, a difference of two columns, which is not friction and is now
/// refused as implausible).
constexpr double kNoiseTol = 0.20, kNoiseTolOtherFriction = 0.70;



nlohmann::json read_json(const std::string& path) {
  std::ifstream f(path);
  nlohmann::json j;
  f >> j;
  return j;
}

std::set<std::string> truth_names(const nlohmann::json& truth) {
  std::set<std::string> s;
  for (const auto& e : truth["effects"]) s.insert(e["name"].get<std::string>());
  return s;
}

std::set<std::string> found_names(const Result& r) {
  std::set<std::string> s;
  for (const auto& e : r.effects) s.insert(e.name);
  return s;
}

const nlohmann::json& truth_params(const nlohmann::json& truth, const std::string& name) {
  for (const auto& e : truth["effects"])
    if (e["name"] == name) return e["params"];
  static const nlohmann::json none = nlohmann::json::object();
  ADD_FAILURE() << "truth has no " << name;
  return none;
}

/// A size-17 torsion loop to +-31 N*m (C_tau of cases/cup_size17.toml) under 22-bit encoder noise: AR(1) 1 arcsec
/// (phi 0.9) plus `white_sd`, quantised to 2 pi / 2^22 rad.
SynthOptions size17_loop(double white_sd, std::uint64_t seed) {
  SynthOptions o;
  o.baseline.prediction = TorsionPrediction{.compliance_rad_per_Nm = 1.89e-5};
  o.rows = TorsionRows{.torque_amplitude_Nm = 31.0};
  o.white_sd = white_sd; o.ar1_sd = 4.85e-6; o.ar1_phi = 0.9; o.quantum = 1.498e-6;
  o.seed = seed;
  return o;
}

bool time_flagged(const Result& r) {
  for (const auto& u : r.unexplained)
    if (u.domain == "time") return true;
  return false;
}

}  // namespace

class ShippedRecording : public ::testing::TestWithParam<int> {};

TEST_P(ShippedRecording, IsExplainedByEveryEffectItHoldsWithTheCatalogFiguresRecovered) {
  sw::quiet_progress() = true;
  const int size = GetParam();
  const std::string stem = "cases/recordings/size" + std::to_string(size) + "_torsion";
  const Recording rec = load_recording(stem + ".csv");
  const nlohmann::json truth = read_json(stem + ".truth.json");
  ASSERT_EQ(rec.meta_number("size").value(), size);
  Baseline base;
  base.prediction = TorsionPrediction{.compliance_rad_per_Nm = rec.meta_number("baseline_compliance_rad_per_Nm").value()};
  const Experiment e = make_experiment(rec, base);
  const Result r = reconcile(e);
  SCOPED_TRACE(trace_of(r));
  EXPECT_EQ(r.verdict, "explained");
  EXPECT_EQ(found_names(r), truth_names(truth));
  EXPECT_FALSE(time_flagged(r));

  // Stiffness: the catalog's three segments. The K1 segment spans T1/K1 of twist (0.43, 0.39, 0.44 mrad for sizes
  // 14, 17, 20), 30-90 times the encoder noise: identifiable at this noise.
  const auto& ts = truth_params(truth, "stiffness_nonlinearity");
  ASSERT_TRUE(r.catalog.has_value());
  const CatalogFigures& c = *r.catalog;
  ASSERT_EQ(c.segments, 3);
  std::printf("[catalog] size %d: K1 %.4g (%.4g), K2 %.4g (%.4g), K3 %.4g (%.4g), T1 %.3g (%.3g), T2 %.3g (%.3g); "
              "loss %.3f arcmin (%.3f), play %.3f arcmin (%.3f), catalog lost motion %.3f arcmin; held-out RMS %.3g "
              "(noise %.3g); %.1f s\n",
              size, c.k1, ts["K1_Nm_per_rad"].get<double>(), c.k2, ts["K2_Nm_per_rad"].get<double>(), c.k3,
              ts["K3_Nm_per_rad"].get<double>(), c.t1, ts["T1_Nm"].get<double>(), c.t2, ts["T2_Nm"].get<double>(),
              c.hysteresis_loss_arcmin, truth_params(truth, "hysteresis")["loss_rad"].get<double>() * sw::kArcmin,
              c.play_arcmin, truth_params(truth, "lost_motion")["width_rad"].get<double>() * sw::kArcmin,
              c.catalog_lost_motion_arcmin, r.final_heldout_rms, truth["noise"]["rms"].get<double>(), r.seconds);
  EXPECT_LT(rel_err(c.k1, ts["K1_Nm_per_rad"].get<double>()), kStiffnessTol);
  EXPECT_LT(rel_err(c.k2, ts["K2_Nm_per_rad"].get<double>()), kStiffnessTol);
  EXPECT_LT(rel_err(c.k3, ts["K3_Nm_per_rad"].get<double>()), kStiffnessTol);
  // Hysteresis loss at +-rated (the recording cycles to rated) and the play's width.
  EXPECT_LT(rel_err(c.hysteresis_loss_arcmin,
                    truth_params(truth, "hysteresis")["loss_rad"].get<double>() * sw::kArcmin), kLossTol);
  EXPECT_LT(rel_err(c.play_arcmin, truth_params(truth, "lost_motion")["width_rad"].get<double>() * sw::kArcmin),
            kLossTol);
  // The catalog's lost motion includes the elastic twist over +-4 % of rated: never below 2 * 0.04 * T_R / K1.
  EXPECT_GT(c.catalog_lost_motion_arcmin, 2 * 0.04 * c.rated_torque_Nm / c.k1 * sw::kArcmin);
  bool other_friction = false;
  for (const auto& fx : truth["effects"])
    other_friction = other_friction || fx.value("generator", "") == "friction_bouc_wen";
  EXPECT_LT(rel_err(r.final_heldout_rms, truth["noise"]["rms"].get<double>()),
            other_friction ? kNoiseTolOtherFriction : kNoiseTol);
}

INSTANTIATE_TEST_SUITE_P(Sizes, ShippedRecording, ::testing::Values(14, 17, 20),
                         [](const auto& info) { return "size" + std::to_string(info.param); });

TEST(OtherStructures, RoundedStiffnessCornersStillGiveTheCatalogSlopes) {
  // The size-17 law with every corner rounded over 0.3 T (tanh steps of the compliance), friction and play, at the
  // shipped recordings' noise. Three straight segments cannot follow the rounded corners at 1 arcsec (the verdict
  // is partly_explained, the torque-shape signature left: printed, not asserted), but the slopes are the catalog's.
  sw::quiet_progress() = true;
  SynthOptions o = size17_loop(2.42e-6, 54);
  o.effects = parse_synth_effects("stiffness_smooth:K1_Nm_per_rad=1e4,K2_Nm_per_rad=1.4e4,K3_Nm_per_rad=1.6e4,"
                                  "T1_Nm=3.9,T2_Nm=12,width=0.3,hysteresis:loss_rad=1.745e-4,transition_Nm=1.5,"
                                  "lost_motion:width_rad=5.82e-5,transition_Nm=0.4");
  const SynthResult s = synthesize(o);
  const Result r = reconcile(make_experiment(s.recording, o.baseline));
  ASSERT_TRUE(r.catalog.has_value());
  const CatalogFigures& c = *r.catalog;
  std::printf("[smooth] %s; K1 %.4g K2 %.4g K3 %.4g, loss %.3f arcmin, play %.3f arcmin\n", trace_of(r).c_str(),
              c.k1, c.k2, c.k3, c.hysteresis_loss_arcmin, c.play_arcmin);
  SCOPED_TRACE(trace_of(r));
  ASSERT_EQ(c.segments, 3);
  EXPECT_LT(rel_err(c.k1, 1e4), kStiffnessTol);
  EXPECT_LT(rel_err(c.k2, 1.4e4), kStiffnessTol);
  EXPECT_LT(rel_err(c.k3, 1.6e4), kStiffnessTol);
  EXPECT_LT(rel_err(c.hysteresis_loss_arcmin, 0.6), kLossTol);
  EXPECT_FALSE(time_flagged(r));
}

TEST(CatalogLostMotion, OfALinearDriveIsItsElasticTwistOverEightPercentOfRated) {
  // The reference's check: with no play at all, 2 * 0.04 * T_R / K1 = 0.85 arcmin for size 17.
  SynthOptions o;
  o.baseline.prediction = TorsionPrediction{.compliance_rad_per_Nm = 1e-4};  // K = 1e4 N*m/rad
  o.rows = TorsionRows{.torque_amplitude_Nm = 31.0};
  const SynthResult s = synthesize(o);
  Recording rec = s.recording;
  rec.metadata.push_back({"size", "17"});
  const Experiment e = make_experiment(rec, o.baseline);
  FitResult none;
  none.nuisance_beta = Eigen::VectorXd::Zero(1);
  const std::optional<CatalogFigures> figures = catalog_figures(e, none);
  ASSERT_TRUE(figures.has_value());
  const CatalogFigures& c = *figures;
  EXPECT_NEAR(c.catalog_lost_motion_arcmin, 0.853, 0.001);
  EXPECT_EQ(c.rated_torque_Nm, 31.0);
  EXPECT_EQ(c.play_arcmin, 0.0);
}

TEST(MultiEffect, FourTransmissionHarmonicsAtHighSnrAreAllFoundAndNothingElse) {
  sw::quiet_progress() = true;
  SynthOptions o;
  o.baseline.gear = {.teeth_flexspline = 190, .teeth_circular = 192};
  o.baseline.prediction = TransmissionPrediction{};
  o.rows = TransmissionRows{.output_revolutions = 2.0};
  o.white_sd = 2e-6; o.ar1_sd = 2e-6; o.quantum = 1e-6;
  o.seed = 51;
  o.effects = parse_synth_effects("wg_harmonic:order=1,amplitude_rad=4e-5,wg_harmonic:order=2,amplitude_rad=6e-5,"
                                  "phase_rad=1.1,output_harmonic:order=1,amplitude_rad=5e-5,output_harmonic:order=3,"
                                  "amplitude_rad=3e-5,phase_rad=-0.7");
  const SynthResult s = synthesize(o);
  const Result r = reconcile(make_experiment(s.recording, o.baseline));
  SCOPED_TRACE(trace_of(r));
  EXPECT_EQ(r.verdict, "explained");
  EXPECT_EQ(r.effects.size(), 4u);
  const std::pair<const char*, int> want[] = {{"wg_harmonic", 1}, {"wg_harmonic", 2}, {"output_harmonic", 1},
                                              {"output_harmonic", 3}};
  const double amp[] = {4e-5, 6e-5, 5e-5, 3e-5};
  for (int i = 0; i < 4; ++i) {
    const AcceptedEffect* f = find(r, want[i].first, want[i].second);
    ASSERT_NE(f, nullptr) << want[i].first << " " << want[i].second;
    // 10 %: each line is 10-20 times the noise RMS over 4000 samples; its amplitude's standard error is ~1 %.
    EXPECT_LT(rel_err(param(*f, "amplitude_rad"), amp[i]), 0.10);
  }
}

TEST(MultiEffect, BacklashOffsetTorsionAndTwoHarmonicsAtHighSnrAreAllFound) {
  sw::quiet_progress() = true;
  SynthOptions o;
  o.baseline.gear.pitch_radius_m = 0.019;
  o.baseline.prediction =
      BacklashPrediction{.backlash_um = [](double wg) { return 20.0 + 15.0 * std::cos(2.0 * wg); }};
  o.rows = BacklashRows{};
  o.white_sd = 0.2; o.ar1_sd = 0.2; o.quantum = 0.1;
  o.seed = 52;
  o.effects = parse_synth_effects("uniform_clearance:offset_um=3,load_torsion:compliance_rad_per_Nm=2e-5,"
                                  "wg_harmonic:order=1,amplitude_um=2,wg_harmonic:order=2,amplitude_um=1.5,phase_rad=1");
  const SynthResult s = synthesize(o);
  const Result r = reconcile(make_experiment(s.recording, o.baseline));
  SCOPED_TRACE(trace_of(r));
  EXPECT_EQ(r.verdict, "explained");
  EXPECT_EQ(r.effects.size(), 4u);
  ASSERT_NE(find(r, "uniform_clearance"), nullptr);
  ASSERT_NE(find(r, "load_torsion"), nullptr);
  ASSERT_NE(find(r, "wg_harmonic", 1), nullptr);
  ASSERT_NE(find(r, "wg_harmonic", 2), nullptr);
  EXPECT_LT(rel_err(param(*find(r, "uniform_clearance"), "offset_um"), 3.0), 0.10);
  EXPECT_LT(rel_err(param(*find(r, "load_torsion"), "compliance_rad_per_Nm"), 2e-5), 0.10);
  EXPECT_LT(rel_err(param(*find(r, "wg_harmonic", 2), "amplitude_um"), 1.5), 0.10);
}

TEST(MultiEffect, OverlappingTorsionEffectsAreAdmittedTogetherAndNoDriftIsInvented) {
  // The case single-effect selection failed on: a three-segment law with series compliance and friction at high SNR
  // (each effect alone leaves the others' signatures near zero torque), AR(1) noise of 1 arcsec, 22-bit encoder.
  sw::quiet_progress() = true;
  SynthOptions o = size17_loop(0.0, 53);
  o.effects = parse_synth_effects("stiffness_nonlinearity:K1_Nm_per_rad=1e4,K2_Nm_per_rad=1.4e4,K3_Nm_per_rad=1.6e4,"
                                  "T1_Nm=3.9,T2_Nm=12,hysteresis:loss_rad=1.745e-4,transition_Nm=1.5");
  const SynthResult s = synthesize(o);
  const Result r = reconcile(make_experiment(s.recording, o.baseline));
  SCOPED_TRACE(trace_of(r));
  EXPECT_EQ(r.verdict, "explained");
  EXPECT_EQ(found_names(r), (std::set<std::string>{"series_compliance", "stiffness_nonlinearity", "hysteresis"}));
  EXPECT_FALSE(time_flagged(r));
  ASSERT_TRUE(r.catalog.has_value());
  EXPECT_LT(rel_err(r.catalog->k1, 1e4), kStiffnessTol);
  EXPECT_LT(rel_err(r.catalog->k2, 1.4e4), kStiffnessTol);
  EXPECT_LT(rel_err(r.catalog->k3, 1.6e4), kStiffnessTol);
}
