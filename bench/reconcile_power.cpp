// bench_reconcile_power — how often reconcile names several concealed effects at once, by how many effects and by
// signal-to-noise, and how often it names something in a recording that has nothing (the false-positive rate).
//
// Cells: kind (torsion, transmission) x effects at once (2, 3, 4) x SNR (each effect's RMS / noise RMS: 1, 5, 20),
// `--replicates` seeds each. Torsion effects, in the order added: series_compliance, hysteresis, lost_motion,
// stiffness_nonlinearity (two segments); transmission: wg_harmonic 2, output_harmonic 1, wg_harmonic 1,
// output_harmonic 3. Noise as tests/reconcile/test_identify.cpp (4000 samples, white + AR(1) phi 0.8 + quantum).
// Per cell: detection (every effect named), names found (fraction of the effects present), extra names (mean count
// of names not present), the median relative error of the headline parameter of the effects found (series: added
// compliance; stiffness: the step 1/K1 - 1/K2; hysteresis: loss; play: width; harmonics: amplitude), and the seconds
// per recording. Then the false-positive rate on null recordings (verdict other than no_significant_mismatch).
// Printed figures only, never asserted.
//
//   build/bench/bench_reconcile_power                    # 10 replicates per cell, 40 null recordings per kind
//   build/bench/bench_reconcile_power --replicates 4 --null 20 --kind torsion
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/progress.hpp"
#include "reconcile/reconcile.hpp"
#include "reconcile/synth.hpp"

namespace {

using namespace sw::reconcile;

SynthOptions base_options(Kind kind, std::uint64_t seed) {
  SynthOptions o;
  o.samples = 4000;
  o.seed = seed;
  o.ar1_phi = 0.8;
  if (kind == Kind::Torsion) {
    o.baseline.prediction = TorsionPrediction{.compliance_rad_per_Nm = 5e-5};
    o.white_sd = 1e-6; o.ar1_sd = 1e-6; o.quantum = 5e-7;
  } else {
    o.baseline.gear = {.teeth_flexspline = 190, .teeth_circular = 192};
    o.baseline.prediction = TransmissionPrediction{};
    o.rows = TransmissionRows{.output_revolutions = 2.0};
    o.white_sd = 2e-6; o.ar1_sd = 2e-6; o.quantum = 1e-6;
  }
  return o;
}

std::vector<std::string> pool(Kind kind) {
  if (kind == Kind::Torsion) return {"series_compliance", "hysteresis", "lost_motion", "stiffness_nonlinearity"};
  return {"wg_harmonic:order=2", "output_harmonic:order=1", "wg_harmonic:order=1", "output_harmonic:order=3"};
}

/// Effect key: name, plus the order of harmonics.
std::string key_of(const std::string& name, int order) { return order ? name + "#" + std::to_string(order) : name; }

double headline(const std::string& name, const std::vector<std::pair<std::string, double>>& p) {
  auto get = [&](const std::string& k) -> double {
    for (const auto& [n, v] : p)
      if (n == k) return v;
    return NAN;
  };
  if (name == "series_compliance") return get("compliance_rad_per_Nm");
  if (name == "stiffness_nonlinearity") return 1.0 / get("K1_Nm_per_rad") - 1.0 / get("K2_Nm_per_rad");
  if (name == "hysteresis") return get("loss_rad");
  if (name == "lost_motion") return get("width_rad");
  return get("amplitude_rad");
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// What the recordings of one cell (kind, number of effects, SNR) gave.
struct Cell {
  int detected = 0, found = 0, present = 0, extra = 0;
  double seconds = 0;
  std::vector<double> errors;  ///< relative error of each named effect's headline
};

/// The harmonic order of a truth entry (0: none).
int truth_order(const nlohmann::json& t) {
  return t["params"].contains("order") ? t["params"]["order"].get<int>() : 0;
}

/// Scores one analysis against its truth: the effects named, those named that were not hidden, the headline errors.
void score(const Result& r, const nlohmann::json& truth, Cell& cell) {
  std::set<std::string> want;
  for (const auto& e : truth["effects"]) want.insert(key_of(e["name"], truth_order(e)));
  int hits = 0;
  for (const auto& e : r.effects) {
    int order = 0;
    std::vector<std::pair<std::string, double>> p;
    for (const auto& h : e.params) {
      if (h.name == "order") order = static_cast<int>(std::lround(h.value));
      p.emplace_back(h.name, h.value);
    }
    const std::string key = key_of(e.name, order);
    if (!want.count(key)) { ++cell.extra; continue; }
    ++hits;
    for (const auto& t : truth["effects"]) {
      if (key_of(t["name"], truth_order(t)) != key) continue;
      std::vector<std::pair<std::string, double>> tp;
      for (const auto& [n, v] : t["params"].items()) tp.emplace_back(n, v.get<double>());
      // Stiffness: the truth's K's hold C_tau only; the fit's hold the series compliance too: the headline compares
      // the step.
      cell.errors.push_back(std::abs(headline(e.name, p) - headline(e.name, tp)) / std::abs(headline(e.name, tp)));
    }
  }
  cell.found += hits;
  cell.present += static_cast<int>(want.size());
  if (hits == static_cast<int>(want.size())) ++cell.detected;
}

/// `replicates` recordings with the first k effects of the kind's pool at an SNR.
Cell run_cell(Kind kind, int k, double snr, int replicates) {
  Cell cell;
  for (int rep = 0; rep < replicates; ++rep) {
    SynthOptions o = base_options(kind, 1000 + 100 * k + rep);
    o.concealment = snr;
    for (int i = 0; i < k; ++i) o.effects.push_back(parse_synth_effect(pool(kind)[i]));
    const SynthResult s = synthesize(o);
    const Result r = reconcile(make_experiment(s.recording, o.baseline));
    cell.seconds += r.seconds;
    score(r, nlohmann::json::parse(s.truth_json), cell);
  }
  return cell;
}

/// False positives on recordings without a hidden effect.
void run_nulls(Kind kind, int nulls) {
  int fp = 0;
  double seconds = 0;
  for (int rep = 0; rep < nulls; ++rep) {
    SynthOptions o = base_options(kind, 5000 + rep);
    const SynthResult s = synthesize(o);
    const Result r = reconcile(make_experiment(s.recording, o.baseline));
    seconds += r.seconds;
    if (r.verdict != "no_significant_mismatch") ++fp;
  }
  std::printf("%-12s null recordings: false positives %d / %d = %.1f %% (target <= 5 %%), %.2f s/rec\n",
              kind_name(kind).c_str(), fp, nulls, 100.0 * fp / std::max(1, nulls), seconds / std::max(1, nulls));
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_reconcile_power: detection, names and parameter error with several concealed effects at once"};
  int replicates = 10, nulls = 40;
  std::string kinds = "torsion,transmission";
  app.add_option("--replicates", replicates, "recordings per cell")->capture_default_str();
  app.add_option("--null", nulls, "null recordings per kind (false-positive rate)")->capture_default_str();
  app.add_option("--kind", kinds, "torsion, transmission or both (comma-separated)")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  sw::quiet_progress() = true;
  try {
    std::printf("%-12s %7s %5s %10s %11s %11s %12s %8s\n", "kind", "effects", "SNR", "detected", "names found",
                "extra names", "param error", "s/rec");
    for (Kind kind : {Kind::Torsion, Kind::Transmission}) {
      if (kinds.find(kind_name(kind)) == std::string::npos) continue;
      for (int k : {2, 3, 4})
        for (double snr : {1.0, 5.0, 20.0}) {
          const Cell c = run_cell(kind, k, snr, replicates);
          std::printf("%-12s %7d %5.0f %9.0f%% %10.0f%% %11.2f %11.1f%% %8.2f\n", kind_name(kind).c_str(), k, snr,
                      100.0 * c.detected / replicates, 100.0 * c.found / std::max(1, c.present),
                      double(c.extra) / replicates, 100.0 * median(c.errors), c.seconds / replicates);
          std::fflush(stdout);
        }
      run_nulls(kind, nulls);
    }
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "bench_reconcile_power: %s\n", ex.what());
    return 1;
  }
  return 0;
}
