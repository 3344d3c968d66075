#pragma once
// A drive with a closed-form torque-twist curve in four physical case keys, each bending the curve its own way (the
// rim and wall soften it, the generator's deformation moves a soft start, tip rounding widens the zero crossing):
// the cheap stand-in for the drive's model in the model-updating proofs (tests/reconcile/test_model_update.cpp) and
// their coverage over noise seeds (bench_reconcile_coverage --kind model).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "reconcile/model_update.hpp"
#include "reconcile/synth.hpp"

namespace sw::reconcile::closed_form {

constexpr double kRim = 0.5, kWall = 0.35, kDeformation = 0.18, kTip = 0.0;
/// White noise of the proofs' recordings (rad): the twist at 10 N*m is ~1e-3 rad, so an SNR of a few hundred.
constexpr double kNoise_rad = 2e-6;
constexpr double kAmplitude_Nm = 9.5;

inline double key_of(const ModelKeyValues& kv, const std::string& key, double fallback) {
  for (const auto& [k, v] : kv)
    if (k == key) return v;
  return fallback;
}

/// twist(T) of the closed-form drive: rim and wall compliances in series (the rim's bending goes as 1/t^3, the
/// wall's shear as 1/t), a stiffening tooth term, a soft start whose breakpoint moves with the generator's
/// deformation, and a zero-crossing step that grows with tip rounding.
inline Prediction drive(const ModelKeyValues& kv) {
  const double rim = key_of(kv, "flexspline.rim_thickness_mm", kRim);
  const double wall = key_of(kv, "flexspline.wall_thickness_mm", kWall);
  const double w0 = key_of(kv, "wave_generator.radial_deformation_mm", kDeformation);
  const double tip = key_of(kv, "gear.tip_rounding_flexspline_mm", kTip);
  TorsionPrediction p;
  p.compliance_rad_per_Nm = 1e-4;
  p.twist_rad = [=](double T) {
    const double body = 4e-5 * std::pow(kRim / rim, 3) * T + 4e-5 * (kWall / wall) * T * std::abs(T) / 10.0;
    const double soft = 2e-4 * (kDeformation / w0) * std::tanh(T / (2.0 * w0 / kDeformation));
    return body + soft + 1e-2 * tip * std::tanh(T / 0.3) + 3e-5 * T;
  };
  return p;
}

inline Baseline baseline() {
  Baseline b;
  b.model = "contact";
  b.prediction = drive({});
  b.model_run = drive;
  return with_remembered_model_runs(b);
}

inline std::vector<ModelCandidate> candidates() {
  return {{"flexspline.rim_thickness_mm", "the rim is thinner or thicker than drawn", 0.35, 0.65, kRim},
          {"flexspline.wall_thickness_mm", "the wall is thinner or thicker than drawn", 0.245, 0.455, kWall},
          {"wave_generator.radial_deformation_mm", "the generator deflects more or less", 0.144, 0.216, kDeformation},
          {"gear.tip_rounding_flexspline_mm", "the tips are rounded", 0.0, 0.05, kTip}};
}

/// A recording of the drive `truth` (a +-kAmplitude_Nm torsion loop, 2000 samples) with white noise kNoise_rad.
inline Recording recording_of(const Baseline& truth, std::uint64_t seed) {
  SynthOptions o;
  o.baseline = truth;
  TorsionRows rows;
  rows.torque_amplitude_Nm = kAmplitude_Nm;
  o.rows = rows;
  o.samples = 2000;
  o.white_sd = kNoise_rad;
  o.seed = seed;
  return parse_recording(format_recording(synthesize(o).recording), "model.csv");
}

/// A recording of the closed-form drive with the key values `truth`.
inline Recording recording(const ModelKeyValues& truth, std::uint64_t seed) {
  Baseline b;
  b.prediction = drive(truth);
  return recording_of(b, seed);
}

}  // namespace sw::reconcile::closed_form
