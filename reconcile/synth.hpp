#pragma once
// Synthetic recordings for proofs and demos: the baseline of a kind plus chosen hidden effects (the same model laws
// reconcile fits), white + AR(1) noise, sensor gain error and encoder quantisation, and a truth record.
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "reconcile/effects.hpp"
#include "reconcile/experiment.hpp"
#include "reconcile/recording.hpp"

namespace sw::reconcile {

/// Torsion: torque cycles between -A and +A (a cosine, starting at the reversal -A).
struct TorsionRows {
  static constexpr Kind kind = Kind::Torsion;
  double cycles = 4.0;
  double torque_amplitude_Nm = 44.1;
  double sample_period_s = 0.01;           ///< time_s step
};

/// Transmission: the wave generator turning at constant speed through a number of output revolutions.
struct TransmissionRows {
  static constexpr Kind kind = Kind::Transmission;
  double output_revolutions = 2.0;
  double sample_period_s = 0.01;           ///< time_s step
};

/// Backlash: one wave-generator revolution at each torque level 0 .. the highest, equally spaced.
struct BacklashRows {
  static constexpr Kind kind = Kind::Backlash;
  double torque_amplitude_Nm = 44.1;       ///< highest torque level
  int torque_levels = 3;
};

/// Dynamics: the dynamics model's run on its own time grid, with white noise on both speed columns.
struct DynamicsRows {
  static constexpr Kind kind = Kind::Dynamics;
  double speed_sd_rpm = 0.0;
};

/// How a synthetic recording's rows run, per kind.
using SynthRows = std::variant<TorsionRows, TransmissionRows, BacklashRows, DynamicsRows>;

struct SynthOptions {
  Baseline baseline;                       ///< the simulated model the effects are added to (its kind's recording)
  /// How the recording's rows run, for the baseline's kind.
  SynthRows rows;
  int samples = 4000;                      ///< rows (torsion, transmission, backlash)
  std::vector<SynthEffect> effects;
  double concealment = 0.0;                ///< > 0: each effect scaled so effect RMS = concealment * noise RMS
  double white_sd = 0.0;                   ///< white noise sd (response units)
  double ar1_sd = 0.0;                     ///< AR(1) component: process sd (response units)
  double ar1_phi = 0.8;                    ///< AR(1) coefficient, |phi| < 1
  double quantum = 0.0;                    ///< encoder/sensor resolution (response units); 0: none
  double gain_error = 0.0;                 ///< measured response = (1 + gain_error) * true response
  std::uint64_t seed = 1;
};

struct SynthResult {
  Recording recording;
  std::string truth_json;                  ///< effects with their (scaled) headline parameters, noise, seed
  double noise_rms = 0.0;                  ///< sqrt(white^2 + ar1^2 + quantum^2 / 12)
  std::vector<std::pair<std::string, double>> effect_rms;  ///< RMS of each effect's contribution
};

/// The noise of the dynamics proofs and of bench_reconcile_dynamics on a dynamics baseline: white and AR(1)
/// (phi 0.8) noise of sd noise_N each on the meshing force, quantum noise_N / 5, 0.05 rpm white on both speeds.
SynthOptions dynamics_proof_options(const Baseline& baseline, double noise_N, std::uint64_t seed);

/// Generates a recording of the baseline's kind. Throws InputError when the rows are of another kind, for unknown
/// effect names or parameters, or effects of another kind.
SynthResult synthesize(const SynthOptions& options);

/// Parses "name[:key=value,...]" ("order" is a key too). Throws InputError naming the text and the expectation.
SynthEffect parse_synth_effect(const std::string& text);

/// Parses a comma-separated list of effects, "a,b:key=value,key=value,c": an item with '=' and no ':' belongs to the
/// effect before it.
std::vector<SynthEffect> parse_synth_effects(const std::string& text);

/// Help text listing each kind's effects, their parameters and defaults.
std::string synth_effect_help();

}  // namespace sw::reconcile
