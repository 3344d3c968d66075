// Proof on concealed effects: synthetic recordings from the baseline plus hidden effects with white + AR(1)
// noise and quantisation; reconcile must name each effect and recover its headline parameter, stay silent on null
// recordings, find a masked harmonic and both effects of a two-effect case.
//
// Fixed noise per kind: tests/reconcile/proof_noise.hpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "common/progress.hpp"
#include "reconcile/reconcile.hpp"
#include "reconcile/synth.hpp"
#include "tests/reconcile/proof_noise.hpp"
#include "tests/reconcile/result_lookup.hpp"

using namespace sw::reconcile;
using namespace sw::reconcile::testing;

namespace {

/// Headline parameters within 25 % at effect-RMS / noise-RMS = 0.5 (the requirement on concealed effects).
constexpr double kParamTol = 0.25;
/// Concealment of the identification cases: effect RMS / noise RMS.
constexpr double kConcealment = 0.5;

SynthOptions options(Kind kind, int seed) { return proof_options(kind, static_cast<std::uint64_t>(seed)); }

struct Outcome {
  Result result;
  nlohmann::json truth;
};

Outcome run(SynthOptions o) {
  sw::quiet_progress() = true;
  const SynthResult s = synthesize(o);
  const Experiment e = make_experiment(s.recording, o.baseline);
  return {reconcile(e), nlohmann::json::parse(s.truth_json)};
}


std::string names(const Result& r) {
  std::string s;
  for (const auto& e : r.effects) s += e.name + " ";
  return s + "| verdict " + r.verdict;
}

struct Case1 {
  Kind kind;
  std::string effect;  // synth spec
  std::string name;
  int order;
  std::string headline;
};

}  // namespace

class IdentifiesEachCatalogEffect : public ::testing::TestWithParam<Case1> {};

TEST_P(IdentifiesEachCatalogEffect, ByNameWithItsHeadlineWithin25PercentAtConcealmentHalf) {
  const Case1 c = GetParam();
  for (int seed : {11, 12}) {
    SynthOptions o = options(c.kind, seed);
    o.concealment = kConcealment;
    o.effects = {parse_synth_effect(c.effect)};
    const Outcome r = run(o);
    SCOPED_TRACE(c.effect + " seed " + std::to_string(seed) + ": " + names(r.result));
    EXPECT_EQ(r.result.verdict, "explained");
    ASSERT_EQ(r.result.effects.size(), 1u);
    const AcceptedEffect* e = find(r.result, c.name, c.order);
    ASSERT_NE(e, nullptr);
    const auto& tp = r.truth["effects"][0]["params"];
    double got = param(*e, c.headline), want = tp[c.headline].get<double>();
    if (c.name == "stiffness_nonlinearity") {
      // K1 differs from K2 by well under 1 % at this concealment, so K1 within 25 % proves nothing: check the
      // compliance step 1/K1 - 1/K2 (what the data constrain) and the breakpoint T1.
      got = 1.0 / got - 1.0 / param(*e, "K2_Nm_per_rad");
      want = 1.0 / want - 1.0 / tp["K2_Nm_per_rad"].get<double>();
      const double t1 = param(*e, "T1_Nm"), t1_true = tp["T1_Nm"].get<double>();
      std::printf("[recovery] %s seed %d: T1 %.4g vs %.4g (%.1f %%)\n", c.name.c_str(), seed, t1, t1_true,
                  100 * rel_err(t1, t1_true));
      EXPECT_LT(rel_err(t1, t1_true), kParamTol);
    }
    std::printf("[recovery] %s seed %d: %s %.4g vs %.4g (%.1f %%), %.2f s\n", c.effect.c_str(), seed,
                c.headline.c_str(), got, want, 100 * rel_err(got, want), r.result.seconds);
    EXPECT_LT(rel_err(got, want), kParamTol);
    EXPECT_LT(r.result.final_heldout_rms, r.result.baseline_heldout_rms);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Catalog, IdentifiesEachCatalogEffect,
    ::testing::Values(
        Case1{Kind::Torsion, "series_compliance", "series_compliance", 0, "compliance_rad_per_Nm"},
        Case1{Kind::Torsion, "stiffness_nonlinearity", "stiffness_nonlinearity", 0, "K1_Nm_per_rad"},
        Case1{Kind::Torsion, "hysteresis", "hysteresis", 0, "loss_rad"},
        Case1{Kind::Torsion, "lost_motion", "lost_motion", 0, "width_rad"},
        Case1{Kind::Transmission, "wg_harmonic:order=1", "wg_harmonic", 1, "amplitude_rad"},
        Case1{Kind::Transmission, "wg_harmonic:order=2", "wg_harmonic", 2, "amplitude_rad"},
        Case1{Kind::Transmission, "output_harmonic:order=1", "output_harmonic", 1, "amplitude_rad"},
        Case1{Kind::Transmission, "output_harmonic:order=3", "output_harmonic", 3, "amplitude_rad"},
        Case1{Kind::Backlash, "load_torsion", "load_torsion", 0, "compliance_rad_per_Nm"},
        Case1{Kind::Backlash, "wg_harmonic:order=1", "wg_harmonic", 1, "amplitude_um"},
        Case1{Kind::Backlash, "uniform_clearance", "uniform_clearance", 0, "offset_um"}),
    [](const auto& info) {
      std::string s = kind_name(info.param.kind) + "_" + info.param.effect;
      for (char& ch : s)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return s;
    });

class NullRecordings : public ::testing::TestWithParam<Kind> {};

TEST_P(NullRecordings, GiveNoSignificantMismatchAtTheNominalRate) {
  // 30 seeds per kind. With the family-wise level 0.05 the expected count is <= 1.5; allowing 3 keeps the test
  // deterministic-seed honest while failing a test that is anti-conservative by more than 2x (P(>=4 | 5 %) = 6 %).
  constexpr int kSeeds = 30;
  constexpr int kMaxFalsePositives = 3;
  int fp = 0;
  for (int seed = 100; seed < 100 + kSeeds; ++seed) {
    const Outcome r = run(options(GetParam(), seed));
    if (r.result.verdict != "no_significant_mismatch") {
      ++fp;
      std::printf("[null] %s seed %d: %s\n", kind_name(GetParam()).c_str(), seed, names(r.result).c_str());
    }
  }
  std::printf("[null] %s: false positives %d / %d\n", kind_name(GetParam()).c_str(), fp, kSeeds);
  EXPECT_LE(fp, kMaxFalsePositives);
}

INSTANTIATE_TEST_SUITE_P(Kinds, NullRecordings, ::testing::Values(Kind::Torsion, Kind::Transmission, Kind::Backlash),
                         [](const auto& info) { return kind_name(info.param); });

TEST(MaskedEffect, SecondOrderHarmonicUnderFivePercentOfTheKnownResponseIsFound) {
  // The basic backlash itself varies 15 um at order 2; the hidden order-2 harmonic is 0.6 um (4 % of it), at a phase
  // the baseline does not have, under 0.35 um RMS noise.
  SynthOptions o = options(Kind::Backlash, 21);
  o.effects = {parse_synth_effect("wg_harmonic:order=2,amplitude_um=0.6,phase_rad=1.0")};
  const Outcome r = run(o);
  SCOPED_TRACE(names(r.result));
  const AcceptedEffect* e = find(r.result, "wg_harmonic", 2);
  ASSERT_NE(e, nullptr);
  EXPECT_LT(rel_err(param(*e, "amplitude_um"), 0.6), kParamTol);
  EXPECT_EQ(r.result.effects.size(), 1u);
}

TEST(TwoEffects, SeriesComplianceAndHysteresisAreBothFound) {
  SynthOptions o = options(Kind::Torsion, 31);
  o.concealment = 1.0;
  o.effects = {parse_synth_effect("series_compliance"), parse_synth_effect("hysteresis")};
  const Outcome r = run(o);
  SCOPED_TRACE(names(r.result));
  EXPECT_EQ(r.result.verdict, "explained");
  ASSERT_NE(find(r.result, "series_compliance"), nullptr);
  ASSERT_NE(find(r.result, "hysteresis"), nullptr);
  EXPECT_LT(rel_err(param(*find(r.result, "hysteresis"), "loss_rad"),
                    r.truth["effects"][1]["params"]["loss_rad"].get<double>()), kParamTol);
}

TEST(TwoEffects, TwoTransmissionHarmonicsAreBothFound) {
  SynthOptions o = options(Kind::Transmission, 32);
  o.concealment = kConcealment;
  o.effects = {parse_synth_effect("wg_harmonic:order=2"), parse_synth_effect("output_harmonic:order=1")};
  const Outcome r = run(o);
  SCOPED_TRACE(names(r.result));
  EXPECT_EQ(r.result.verdict, "explained");
  EXPECT_NE(find(r.result, "wg_harmonic", 2), nullptr);
  EXPECT_NE(find(r.result, "output_harmonic", 1), nullptr);
}

TEST(UnexplainedMismatch, IsReportedAsPartlyExplainedNotInventedAsAnEffect) {
  // A slow drift in time is not in the torsion catalog: reconcile must say so rather than name an effect for it.
  SynthOptions o = options(Kind::Torsion, 41);
  o.effects = {};
  SynthResult s = synthesize(o);
  auto& twist = s.recording.values.back();
  for (std::size_t i = 0; i < twist.size(); ++i) twist[i] += 3e-6 * double(i) / twist.size();
  sw::quiet_progress() = true;
  const Result r = reconcile(make_experiment(s.recording, o.baseline));
  SCOPED_TRACE(names(r));
  EXPECT_EQ(r.verdict, "partly_explained");
  bool time_flagged = false;
  for (const auto& u : r.unexplained) time_flagged = time_flagged || u.domain == "time";
  EXPECT_TRUE(time_flagged);
}
