// reconcile on recordings of kind dynamics (issue 6, "Recordings of dynamic runs"): synth runs the seed-1 dynamics
// model with one hidden effect plus noise; reconcile must name it with its headline parameter within 25 %, and a
// null recording must give no_significant_mismatch. The baseline is the same model with constant mesh stiffness,
// supplied here as the app supplies it (reconcile does not link the dynamics module).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../dynamics/seed_models.hpp"
#include "app/reconcile_baseline.hpp"
#include "dynamics/simulate.hpp"
#include "reconcile/reconcile.hpp"
#include "reconcile/synth.hpp"

namespace sw::reconcile {
namespace {

DynamicsModel test_model() {
  DynamicsModel m = sw::test::seed_model();
  // The run-up (10 ms) then a fast load step (0.2 ms): the step rings the contact mode, whose decay carries the
  // damping (with slow ramps only, the damping is unobservable in the meshing force).
  m.params.duration_s = 0.04;
  m.params.output_step_s = 1.0e-5;
  m.params.load_ramp_start_s = 0.012;
  m.params.load_ramp_end_s = 0.0122;
  m.params.steady_from_s = 0.02;
  return m;
}

struct Case {
  std::string effect;       // synth --effect text ("" = null)
  double concealment;
  std::string headline;
  double noise = 5.0;       // white and AR(1) sd of the meshing force, N (quantum noise / 5)
};

double c_ratio = 0.0;

Result run_case(const Case& c, std::uint64_t seed, double* truth) {
  SynthOptions o;
  o.kind = Kind::Dynamics;
  o.baseline = app::dynamics_baseline(test_model());  // the one `strainwave reconcile` uses
  o.white_sd = c.noise;
  o.ar1_sd = c.noise;
  o.quantum = 0.2 * c.noise;
  o.speed_sd_rpm = 0.05;
  o.seed = seed;
  o.concealment = c.concealment;
  if (!c.effect.empty()) o.effects.push_back(parse_synth_effect(c.effect));
  const SynthResult s = synthesize(o);
  if (!s.effect_rms.empty()) c_ratio = s.effect_rms[0].second / s.noise_rms;
  if (std::getenv("SW_DYN_DEBUG")) std::printf("truth: %s\n", s.truth_json.c_str());
  if (truth && !c.effect.empty()) {
    *truth = nlohmann::json::parse(s.truth_json)["effects"][0]["params"][c.headline].get<double>();
  }
  const Recording rec = parse_recording(format_recording(s.recording), "dyn.csv");
  const Experiment e = make_experiment(rec, o.baseline);
  Options opt;
  opt.seed = seed;
  return reconcile(e, opt);
}

void expect_named(const Case& c, std::uint64_t seed) {
  double truth = 0.0;
  const Result r = run_case(c, seed, &truth);
  const std::string name = c.effect.substr(0, c.effect.find(':'));
  ASSERT_TRUE(r.significant) << name;
  const AcceptedEffect* found = nullptr;
  for (const auto& fx : r.effects) if (fx.name == name) found = &fx;
  for (const auto& fx : r.effects) std::printf("  accepted %s (dBIC %.1f, p %.2g)\n", fx.name.c_str(), fx.delta_bic, fx.p_value);
  for (const auto& rj : r.rejected) std::printf("  rejected %s: %s\n", rj.name.c_str(), rj.reason.c_str());
  ASSERT_NE(found, nullptr) << name << " not named; verdict " << r.verdict;
  double value = NAN;
  for (const auto& h : found->params)
    if (h.name == c.headline) {
      value = h.value;
      std::printf("%s: %s = %.5g [%.5g, %.5g]\n", name.c_str(), h.name.c_str(), h.value, h.lo, h.hi);
    }
  std::printf("%s: concealment (effect RMS / noise RMS) %.3g\n", name.c_str(), r.samples ? c_ratio : 0.0);
  std::printf("%s: %s truth %.5g fitted %.5g (error %.1f %%), verdict %s, %zu effects\n", name.c_str(),
              c.headline.c_str(), truth, value, 100.0 * (value - truth) / truth, r.verdict.c_str(), r.effects.size());
  EXPECT_NEAR(value, truth, 0.25 * std::abs(truth)) << name;
  EXPECT_EQ(r.effects.size(), 1u) << "a single hidden effect";
}

TEST(ReconcileDynamics, NamesMeshStiffnessVariation) {
  expect_named({"mesh_stiffness_variation:amplitude_ratio=0.05,phase_rad=0.3", 0.0, "amplitude_ratio", 0.5}, 11);
}

TEST(ReconcileDynamics, NamesDamping) {
  expect_named({"damping:coefficient_Ns_per_m=2000", 0.0, "coefficient_Ns_per_m", 0.3}, 12);
}

TEST(ReconcileDynamics, NamesDragTorque) {
  expect_named({"drag_torque:coulomb_Nm=2,viscous_Nms_per_rad=0", 1.0, "torque_at_speed_Nm"}, 13);
}

TEST(ReconcileDynamics, NullRecordingHasNoSignificantMismatch) {
  const Result r = run_case({"", 0.0, ""}, 14, nullptr);
  EXPECT_EQ(r.verdict, "no_significant_mismatch");
  EXPECT_TRUE(r.effects.empty());
}

}  // namespace
}  // namespace sw::reconcile
