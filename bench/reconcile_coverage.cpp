// bench_reconcile_coverage — does each 95 % interval hold the truth in 95 % of recordings? For every single-effect
// proof of tests/reconcile/test_identify.cpp (torsion, transmission and backlash, the same noise and concealment) and
// --seeds noise seeds: how often the effect is named, and per headline parameter the truth has, how often the named
// effect's interval holds it. Parameters the effect holds (reported as fixed) and a harmonic's order are not
// intervals and are left out. Kind `model`: the model-updating proofs of tests/reconcile/test_model_update.cpp on the
// closed-form drive (each physical key changed alone, its noise), the refitted value's interval against the true value.
// Printed figures only.
//
//   build/bench/bench_reconcile_coverage                       # 20 seeds, concealment 0.5
//   build/bench/bench_reconcile_coverage --concealment 2 --kind torsion
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/progress.hpp"
#include "reconcile/model_update.hpp"
#include "reconcile/reconcile.hpp"
#include "reconcile/synth.hpp"
#include "tests/reconcile/closed_form_drive.hpp"
#include "tests/reconcile/proof_noise.hpp"

namespace {

using namespace sw::reconcile;

struct Proof {
  Kind kind;
  std::string effect;  ///< synth spec
};

const std::vector<Proof> kProofs = {
    {Kind::Torsion, "series_compliance"},       {Kind::Torsion, "stiffness_nonlinearity"},
    {Kind::Torsion, "hysteresis"},              {Kind::Torsion, "lost_motion"},
    {Kind::Transmission, "wg_harmonic:order=2"}, {Kind::Transmission, "output_harmonic:order=1"},
    {Kind::Backlash, "load_torsion"},           {Kind::Backlash, "wg_harmonic:order=1"},
    {Kind::Backlash, "uniform_clearance"}};

/// The recording options of the proofs (tests/reconcile/proof_noise.hpp) at `concealment`.
SynthOptions proof_options(Kind kind, std::uint64_t seed, double concealment) {
  SynthOptions o = sw::reconcile::testing::proof_options(kind, seed);
  o.concealment = concealment;
  return o;
}

struct Tally {
  int named = 0, extra = 0;
  /// per headline parameter: bounded intervals that hold the truth, bounded intervals, and unbounded ones (an end at
  /// infinity holds anything on its side: such an interval is counted apart, never as covering)
  std::map<std::string, int> covered, counted, unbounded;
  double seconds = 0.0;
};

/// Scores one analysis: the effect named, other names, and each fitted headline's interval against the truth.
void score(const Result& r, const std::string& name, const nlohmann::json& truth, Tally& t) {
  bool found = false;
  for (const auto& e : r.effects) {
    if (e.name != name || found) {
      ++t.extra;
      continue;
    }
    found = true;
    for (const auto& h : e.params) {
      if (h.fixed() || h.name == "order" || !truth.contains(h.name)) continue;
      const double want = truth[h.name].get<double>();
      if (!std::isfinite(h.lo) || !std::isfinite(h.hi)) {
        ++t.unbounded[h.name];
        continue;
      }
      ++t.counted[h.name];
      t.covered[h.name] += (h.lo <= want && want <= h.hi);
    }
  }
  t.named += found;
}

/// Each headline's coverage over its bounded intervals, the unbounded ones beside.
void print_coverage(Tally& t) {
  std::set<std::string> names;
  for (const auto& [name, n] : t.counted) names.insert(name);
  for (const auto& [name, n] : t.unbounded) names.insert(name);
  for (const std::string& name : names)
    std::printf("    %-24s coverage of the 95 %% interval %2d/%d bounded, %d unbounded (not counted)\n", name.c_str(),
                t.covered[name], t.counted[name], t.unbounded[name]);
}

/// The model-updating proofs: a recording of the closed-form drive with one key at `value` (closed_form::recording, as
/// test_model_update.cpp makes them), updated over the four candidates; the named key's refitted value against `value`.
void model_coverage(int seeds) {
  const Baseline base = closed_form::baseline();
  const std::vector<std::pair<std::string, double>> truths = {{"flexspline.rim_thickness_mm", 0.45},
                                                              {"flexspline.wall_thickness_mm", 0.30},
                                                              {"wave_generator.radial_deformation_mm", 0.20},
                                                              {"gear.tip_rounding_flexspline_mm", 0.02}};
  for (const auto& [key, value] : truths) {
    Tally t;
    for (int s = 0; s < seeds; ++s) {
      const Recording rec = closed_form::recording({{key, value}}, 1000 + s);
      const auto start = std::chrono::steady_clock::now();
      const ModelUpdate u = update_model(make_experiment(rec, base), base, closed_form::candidates());
      t.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      score(u.result, model_effect_name(key), nlohmann::json{{"value", value}}, t);
    }
    std::printf("%-13s %-38s named %2d/%d, extra names %d, %.2f s/recording\n", "model",
                (key + "=" + std::to_string(value).substr(0, 4)).c_str(), t.named, seeds, t.extra, t.seconds / seeds);
    print_coverage(t);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"reconcile: coverage of the 95 % intervals over noise seeds, single-effect proofs"};
  int seeds = 20;
  double concealment = 0.5;
  std::string kinds = "torsion,transmission,backlash,model";
  app.add_option("--seeds", seeds, "noise seeds per effect")->capture_default_str();
  app.add_option("--concealment", concealment, "effect RMS / noise RMS")->capture_default_str();
  app.add_option("--kind", kinds, "comma-separated kinds")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  sw::quiet_progress() = true;
  std::printf("concealment %g, %d seeds per effect (noise of tests/reconcile/test_identify.cpp)\n", concealment, seeds);
  for (const Proof& p : kProofs) {
    if (kinds.find(kind_name(p.kind)) == std::string::npos) continue;
    Tally t;
    const SynthEffect fx = parse_synth_effect(p.effect);
    for (int s = 0; s < seeds; ++s) {
      SynthOptions o = proof_options(p.kind, 1000 + s, concealment);
      o.effects = {fx};
      const SynthResult syn = synthesize(o);
      const auto start = std::chrono::steady_clock::now();
      const Result r = reconcile(make_experiment(syn.recording, o.baseline));
      t.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      score(r, fx.name, nlohmann::json::parse(syn.truth_json)["effects"][0]["params"], t);
    }
    std::printf("%-13s %-26s named %2d/%d, extra names %d, %.2f s/recording\n", kind_name(p.kind).c_str(),
                p.effect.c_str(), t.named, seeds, t.extra, t.seconds / seeds);
    print_coverage(t);
  }
  if (kinds.find("model") != std::string::npos) model_coverage(seeds);
  return 0;
}
