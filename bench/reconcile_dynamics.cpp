// bench_reconcile_dynamics — reconcile on recordings of kind dynamics over many noise seeds: for each concealed effect
// (mesh_stiffness_variation, damping, drag_torque) how often it is named, what else is named, the bias of each fitted
// headline parameter (mean relative error and its standard error over the seeds) and the coverage of its 95 %
// interval (share of seeds whose interval holds the truth); on null recordings the false-positive rate.
//
// The baseline is make_baseline's, from a case (default cases/mbd_26_28.toml, the paper's 26/28 gear), with the
// [dynamics] timing of tests/reconcile/test_dynamics.cpp (run-up 10 ms, a 0.2 ms load step at 12 ms, 40 ms) and the
// pair model of --pairs/--stiffness on a rigid rim (--rim fem: coupled through the FEM's flexspline body, which the
// baseline solves once before the first run). The effects (those of the test: Δk/k0 = 0.05 at phase 0.3,
// c = 2000 N·s/m, Coulomb drag 2 N·m) are rescaled to --concealment times the noise RMS (0: kept as stated); the noise
// is that of the test (white + AR(1) phi 0.8, --noise N each, quantum a fifth of it). Every run of the model is remembered (a run is a
// deterministic function of its variation), so the seeds share the sensitivity and calibration runs; seconds per
// recording are those of synth + make_experiment + reconcile after the first seed.
//
// --diagnose: for each effect, the noise-free effect signal (run with the effect minus the baseline run) fitted by the
// effect's own columns: by ordinary least squares, and by generalised least squares under the AR noise model reconcile
// estimates (what reconcile does), with the headline each gives and the share of the signal the columns leave.
// Printed figures only, never asserted.
//
//   build/bench/bench_reconcile_dynamics                         # 20 seeds, moving pairs, tooth-pair compliance
//   build/bench/bench_reconcile_dynamics --pairs frozen --seeds 20
//   build/bench/bench_reconcile_dynamics --diagnose --seeds 0
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/reconcile_baseline.hpp"
#include "common/progress.hpp"
#include "io/case.hpp"
#include "reconcile/effects.hpp"
#include "reconcile/fit.hpp"
#include "reconcile/reconcile.hpp"
#include "reconcile/stats.hpp"
#include "reconcile/synth.hpp"

namespace {

using namespace sw::reconcile;
using Vec = Eigen::VectorXd;
using Mat = Eigen::MatrixXd;

struct BenchOptions {
  std::string case_path = SW_SOURCE_DIR "/cases/mbd_26_28.toml";
  std::string pairs = "moving", stiffness = "teeth", rim = "rigid";
  int seeds = 20;
  int seed_offset = 0;  ///< the seeds start this far into each effect's sequence (split one row over processes)
  std::string only;  ///< one effect's name (mesh_stiffness_variation, damping, drag_torque, null); empty: all
  double concealment = 1.0, noise_N = 5.0, damping_Ns_per_m = 2000.0;
  bool diagnose = false;
};

/// The case with the reconcile timing and the chosen pair model and rim.
sw::Case bench_case(const BenchOptions& o) {
  sw::Case c = sw::load_case(o.case_path);
  sw::DynamicsParams p = c.dynamics ? *c.dynamics : sw::DynamicsParams{};
  p.pair_motion = o.pairs == "frozen" ? sw::PairMotion::Frozen : sw::PairMotion::Moving;
  p.pair_stiffness = o.stiffness == "constant" ? sw::PairStiffness::Constant : sw::PairStiffness::Teeth;
  p.rim = o.rim == "fem" ? sw::RimCoupling::Fem : sw::RimCoupling::Rigid;
  if (p.rim == sw::RimCoupling::Fem) c.solver.method = sw::SolverMethod::Tet10;  // the coupling reads TET10's body
  p.duration_s = 0.04;
  p.output_step_s = 1.0e-5;
  p.load_ramp_start_s = 0.012;
  p.load_ramp_end_s = 0.0122;
  p.steady_from_s = 0.02;
  c.dynamics = p;
  return c;
}

/// The dynamics model of the baseline.
const DynamicsPrediction& model(const Baseline& b) { return std::get<DynamicsPrediction>(b.prediction); }

SynthOptions synth_options(const Baseline& b, const BenchOptions& o, const std::string& effect, std::uint64_t seed) {
  SynthOptions s = dynamics_proof_options(b, o.noise_N, seed);
  s.concealment = o.concealment;
  if (!effect.empty()) s.effects.push_back(parse_synth_effect(effect));
  return s;
}

/// The headline parameters compared with the truth, per effect.
std::vector<std::string> headlines(const std::string& name) {
  if (name == "mesh_stiffness_variation") return {"amplitude_ratio"};
  if (name == "damping") return {"coefficient_Ns_per_m", "added_Ns_per_m"};
  return {"coulomb_Nm", "viscous_Nms_per_rad", "torque_at_speed_Nm"};
}

struct Tally {
  int recordings = 0, named = 0, extra = 0, significant = 0, failed = 0;  ///< failed: synth or reconcile threw
  double seconds = 0;        ///< per recording after the first (the model's runs remembered)
  double first_seconds = 0;  ///< the first recording, with the runs it needs that earlier effects did not
  std::map<std::string, std::vector<double>> rel_error;  ///< per headline: (fitted - truth) / truth of named seeds
  std::map<std::string, int> covered;                     ///< per headline: interval holds the truth
  std::map<std::string, int> extra_names;                 ///< effects named that were not concealed
};

void record(Tally& t, const std::string& name, const nlohmann::json& truth, const Result& r) {
  ++t.recordings;
  t.significant += r.verdict != "no_significant_mismatch";
  for (const auto& fx : r.effects) {
    if (fx.name != name) {
      ++t.extra;
      ++t.extra_names[fx.name];
      continue;
    }
    ++t.named;
    for (const auto& h : fx.params) {
      if (!truth.contains(h.name)) continue;
      const double want = truth[h.name].get<double>();
      bool wanted = false;
      for (const auto& k : headlines(name)) wanted = wanted || k == h.name;
      if (!wanted || want == 0.0) continue;
      t.rel_error[h.name].push_back((h.value - want) / want);
      t.covered[h.name] += (h.lo <= want && want <= h.hi);
      std::printf("    %s %.6g [%.6g, %.6g], truth %.6g\n", h.name.c_str(), h.value, h.lo, h.hi, want);
      std::fflush(stdout);
    }
  }
}

void print_tally(const std::string& name, const Tally& t) {
  if (name.empty()) {
    std::printf("%-26s %3d seeds: false positives %d (%.0f %%), names %d; %.3f s/recording\n", "null", t.recordings,
                t.significant, 100.0 * t.significant / std::max(1, t.recordings), t.extra, t.seconds);
    return;
  }
  std::printf("%-26s %3d seeds: named %d (%.0f %%), extra names %d, failed %d; first recording %.2f s, then %.3f "
              "s/recording\n", name.c_str(), t.recordings, t.named, 100.0 * t.named / std::max(1, t.recordings),
              t.extra, t.failed, t.first_seconds, t.seconds);
  for (const auto& [extra, count] : t.extra_names) std::printf("    also named: %s in %d\n", extra.c_str(), count);
  for (const auto& k : headlines(name)) {
    const auto it = t.rel_error.find(k);
    if (it == t.rel_error.end() || it->second.empty()) continue;
    const std::vector<double>& e = it->second;
    double mean = 0, var = 0;
    for (double x : e) mean += x / e.size();
    for (double x : e) var += (x - mean) * (x - mean) / std::max<std::size_t>(1, e.size() - 1);
    const int cov = t.covered.count(k) ? t.covered.at(k) : 0;
    std::printf("    %-22s bias %+7.2f %% +- %5.2f %% (SE), sd %6.2f %%, coverage of the 95 %% interval %d/%zu = %.0f %%\n",
                k.c_str(), 100 * mean, 100 * std::sqrt(var / e.size()), 100 * std::sqrt(var), cov, e.size(),
                100.0 * cov / e.size());
  }
}

/// One effect over the seeds.
Tally run_effect(const Baseline& b, const BenchOptions& o, const std::string& effect, std::uint64_t first_seed) {
  Tally t;
  const std::string name = effect.substr(0, effect.find(':'));
  for (int i = 0; i < o.seeds; ++i) {
    const auto start = std::chrono::steady_clock::now();
    // A seed whose recording or analysis fails (a model run the integrator cannot carry) counts as a recording not
    // named, and the bench goes on: a failure is a finding, not the end of the table.
    std::optional<SynthResult> syn;
    std::optional<Result> analysed;
    try {
      syn = synthesize(synth_options(b, o, effect, first_seed + i));
      Options opt;
      opt.seed = first_seed + i;
      analysed = reconcile(make_experiment(syn->recording, b), opt);
    } catch (const std::exception& ex) {
      ++t.recordings;
      ++t.failed;
      std::printf("    seed %llu failed (%s): %s\n", (unsigned long long)(first_seed + i),
                  syn ? "reconcile" : "synth", ex.what());
      continue;
    }
    const Result& r = *analysed;
    const nlohmann::json truth = nlohmann::json::parse(syn->truth_json);
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    (i == 0 ? t.first_seconds : t.seconds) += sec;
    record(t, name, effect.empty() ? nlohmann::json::object() : truth["effects"][0]["params"], r);
    bool named = effect.empty();
    for (const auto& fx : r.effects) named = named || fx.name == name;
    for (const auto& rj : r.rejected)
      if (!named && rj.name == name) std::printf("    seed %llu not named: %s\n", (unsigned long long)(first_seed + i),
                                                 rj.reason.c_str());
    if (!named && !r.significant) std::printf("    seed %llu not named: no significant mismatch\n",
                                             (unsigned long long)(first_seed + i));
  }
  t.seconds /= std::max(1, o.seeds - 1);
  return t;
}

/// The effect's columns fitted to its own noise-free signal, by OLS and by GLS under the AR model of one noisy
/// recording, with the headline each gives (through the effect's own headline mapping) and the share left unexplained.
void diagnose(const Baseline& b, const BenchOptions& o, const std::string& effect) {
  const std::string name = effect.substr(0, effect.find(':'));
  SynthOptions s = synth_options(b, o, effect, 1);
  const SynthResult noisy = synthesize(s);
  const nlohmann::json truth = nlohmann::json::parse(noisy.truth_json)["effects"][0]["params"];
  s.white_sd = s.ar1_sd = s.quantum = 0.0;
  s.rows = DynamicsRows{};
  s.concealment = 0.0;
  s.effects[0].params.clear();
  for (const auto& [k, v] : truth.items())
    if (k != "frequency_Hz" && k != "torque_at_speed_Nm" && k != "added_Ns_per_m") s.effects[0].params[k] = v.get<double>();
  const SynthResult clean = synthesize(s);
  const Experiment ec = make_experiment(clean.recording, b);
  const Experiment en = make_experiment(noisy.recording, b);
  const EffectSpec* spec = nullptr;
  for (const auto& fx : effect_catalog(Kind::Dynamics))
    if (fx.name == name) spec = &fx;
  const Vec d = ec.residual();
  const ArModel ar = fit_ar(en.residual() - d, 8);
  auto fit = [&](const ArModel& noise) {
    Term t;
    t.spec = spec;
    t.theta = Vec::Zero(spec->n_nonlinear());
    t.beta = Vec::Zero(spec->n_linear);
    return fit_model(ec, d, {t}, noise, FitOptions{});
  };
  const FitResult ols = fit(ArModel{}), gls = fit(ar);
  const double dw = whiten(ar, d).squaredNorm();
  std::printf("%s (signal RMS %.3g N, noise RMS %.3g N, AR(%d)): unexplained by its model: OLS %.1f %%, GLS %.1f %% "
              "(whitened)\n", name.c_str(), std::sqrt(d.squaredNorm() / d.size()), noisy.noise_rms, ar.order(),
              100 * std::sqrt(ols.rss_w / d.squaredNorm()), 100 * std::sqrt(gls.rss_w / dw));
  if (name == "damping") {
    const double c = truth["coefficient_Ns_per_m"].get<double>(), c0 = model(b).damping_Ns_per_m;
    const Vec table = (c - c0) * damping_secant(as<DynamicsExperiment>(ec), c);
    std::printf("    the table's interpolant at the true c misses %.1f %% of the response (RMS)\n",
                100 * (table - d).norm() / d.norm());
  }
  const NamedValues ho = spec->headline(ec, ols, 0), hg = spec->headline(ec, gls, 0);
  for (std::size_t i = 0; i < ho.size(); ++i)
    std::printf("    %-22s truth %-10.5g  OLS %.5g  GLS %.5g\n", ho[i].first.c_str(),
                truth.contains(ho[i].first) ? truth[ho[i].first].get<double>() : NAN, ho[i].second, hg[i].second);
}

/// RMS (N) of the meshing-force change for a drag, a damping change and a k(t) amplitude over several decades: a
/// model whose force is smooth in its parameters shows a change proportional to the step; a floor shows jitter.
void response_scaling(const Baseline& b) {
  const auto& run = model(b).dynamics_run;
  const sw::reconcile::DynamicsRun r0 = run(DynamicsVariation{});
  auto rms_change = [&](const DynamicsVariation& v) {
    const sw::reconcile::DynamicsRun r = run(v);
    double s2 = 0;
    for (std::size_t i = 0; i < r.mesh_force_N.size(); ++i) s2 += std::pow(r.mesh_force_N[i] - r0.mesh_force_N[i], 2);
    return std::sqrt(s2 / r.mesh_force_N.size());
  };
  {
    DynamicsVariation drag;
    drag.drag_coulomb_Nm = 1e-4;
    const sw::reconcile::DynamicsRun r = run(drag);
    std::printf("drag 1e-4 N*m: RMS change per 2 ms window:");
    const std::size_t w = 200;
    for (std::size_t a = 0; a + w <= r.mesh_force_N.size(); a += w) {
      double s2 = 0, m = 0;
      for (std::size_t i = a; i < a + w; ++i) {
        s2 += std::pow(r.mesh_force_N[i] - r0.mesh_force_N[i], 2);
        m = std::max(m, std::abs(r.mesh_force_N[i] - r0.mesh_force_N[i]));
      }
      std::printf(" %.3g/%.3g", std::sqrt(s2 / w), m);
    }
    std::printf("\n");
  }
  std::printf("meshing-force change (RMS, N) against the step:\n");
  for (double step : {1e-8, 1e-6, 1e-4, 1e-2, 1e0}) {
    DynamicsVariation drag, damp, stiff;
    drag.drag_coulomb_Nm = step;
    damp.damping_Ns_per_m = model(b).damping_Ns_per_m * (1.0 + step);
    stiff.stiffness_ratio = 0.1 * step;
    std::printf("    step %.0e: drag %.0e N*m %.4g N, damping x(1 + %.0e) %.4g N, k(t) ratio %.0e %.4g N\n", step, step,
                rms_change(drag), step, rms_change(damp), 0.1 * step, rms_change(stiff));
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_reconcile_dynamics: detection, bias and interval coverage of the dynamics effects over seeds"};
  BenchOptions o;
  app.add_option("--case", o.case_path, "case file with [gear] (and [dynamics])")->capture_default_str();
  app.add_option("--pairs", o.pairs, "tooth pairs: moving | frozen")->check(CLI::IsMember({"moving", "frozen"}))
      ->capture_default_str();
  app.add_option("--stiffness", o.stiffness, "moving pair stiffness: teeth | constant")
      ->check(CLI::IsMember({"teeth", "constant"}))->capture_default_str();
  app.add_option("--rim", o.rim, "moving pairs: rigid | fem (coupled through the flexspline body)")
      ->check(CLI::IsMember({"rigid", "fem"}))->capture_default_str();
  app.add_option("--only", o.only, "one effect: mesh_stiffness_variation, damping, drag_torque or null");
  app.add_option("--seeds", o.seeds, "noise seeds per effect")->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--seed-offset", o.seed_offset, "start this far into each effect's seeds (one row over processes)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--concealment", o.concealment, "effect RMS / noise RMS (0: the effects at their stated values)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  app.add_option("--noise", o.noise_N, "white and AR(1) sd of the meshing force, N (quantum: a fifth)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--damping", o.damping_Ns_per_m, "concealed damping coefficient before rescaling, N*s/m")
      ->check(CLI::PositiveNumber)->capture_default_str();
  app.add_flag("--diagnose", o.diagnose, "fit each effect's columns to its noise-free signal (OLS and GLS)");
  CLI11_PARSE(app, argc, argv);
  sw::quiet_progress() = true;
  try {
    sw::app::BaselineSources src;
    src.case_file = bench_case(o);
    std::vector<std::string> notes;
    const Baseline b = sw::app::make_baseline(Kind::Dynamics, src, notes);  // its runs are remembered
    std::printf("%s\nnoise: white %.3g N + AR(1) %.3g N (phi 0.8) + quantum %.3g N; effects at %.3g x the noise RMS\n",
                notes.back().c_str(), o.noise_N, o.noise_N, 0.2 * o.noise_N, o.concealment);
    const std::vector<std::string> effects{"mesh_stiffness_variation:amplitude_ratio=0.05,phase_rad=0.3",
                                           "damping:coefficient_Ns_per_m=" + std::to_string(o.damping_Ns_per_m),
                                           "drag_torque:coulomb_Nm=2", ""};
    if (o.diagnose) response_scaling(b);
    if (o.diagnose)
      for (std::size_t i = 0; i + 1 < effects.size(); ++i) diagnose(b, o, effects[i]);
    for (std::size_t i = 0; i < effects.size() && o.seeds > 0; ++i) {
      const std::string name = effects[i].empty() ? "null" : effects[i].substr(0, effects[i].find(':'));
      if (!o.only.empty() && o.only != name) continue;
      print_tally(effects[i].substr(0, effects[i].find(':')), run_effect(b, o, effects[i], 1000 * (i + 1) + o.seed_offset));
      std::fflush(stdout);
    }
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "bench_reconcile_dynamics: %s\n", ex.what());
    return 1;
  }
  return 0;
}
