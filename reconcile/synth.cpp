#include "reconcile/synth.hpp"

#include <cmath>
#include <random>
#include <sstream>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "reconcile/effects.hpp"

namespace sw::reconcile {

using Vec = Eigen::VectorXd;

namespace {


/// Headline parameters as the truth file writes them (a harmonic's order as an integer).
nlohmann::json json_of(const NamedValues& values) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, v] : values) {
    if (name == "order") j[name] = static_cast<int>(v);
    else j[name] = v;
  }
  return j;
}

double noise_rms(const SynthOptions& o) {
  return std::sqrt(o.white_sd * o.white_sd + o.ar1_sd * o.ar1_sd + o.quantum * o.quantum / 12.0);
}

/// The recorded response, row after row: sensor gain error, white and AR(1) noise (stationary start), quantisation.
/// One random stream per recording (o.seed): the speed noise of a dynamics recording is drawn from it between rows.
class SensorNoise {
 public:
  explicit SensorNoise(const SynthOptions& o)
      : o_(o), rng_(o.seed), innovation_(o.ar1_sd * std::sqrt(1.0 - o.ar1_phi * o.ar1_phi)),
        ar_(o.ar1_sd * normal_(rng_)) {}

  /// The recorded value of the next row's true response.
  double record(double truth) {
    if (rows_++ > 0) ar_ = o_.ar1_phi * ar_ + innovation_ * normal_(rng_);
    double v = (1.0 + o_.gain_error) * truth + o_.white_sd * normal_(rng_) + ar_;
    if (o_.quantum > 0.0) v = std::round(v / o_.quantum) * o_.quantum;
    return v;
  }
  /// A standard normal draw from the same stream.
  double normal() { return normal_(rng_); }

 private:
  const SynthOptions& o_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  double innovation_;
  double ar_;
  int rows_ = 0;
};

// ---- the truth file -----------------------------------------------------------------------------------------------

/// The baseline the effects were added to: every kind but dynamics records the drive's figures (compliance 0 where
/// the baseline has none).
nlohmann::json drive_truth(const DriveGear& g, double compliance_rad_per_Nm) {
  return {{"compliance_rad_per_Nm", compliance_rad_per_Nm}, {"teeth_flexspline", g.teeth_flexspline},
          {"teeth_circular", g.teeth_circular}, {"pitch_radius_m", g.pitch_radius_m}};
}
nlohmann::json baseline_truth(const DriveGear& g, const TorsionPrediction& p) {
  return drive_truth(g, p.compliance_rad_per_Nm);
}
nlohmann::json baseline_truth(const DriveGear& g, const TransmissionPrediction&) { return drive_truth(g, 0.0); }
nlohmann::json baseline_truth(const DriveGear& g, const BacklashPrediction&) { return drive_truth(g, 0.0); }
nlohmann::json baseline_truth(const DriveGear&, const DynamicsPrediction& p) {
  return {{"damping_Ns_per_m", p.damping_Ns_per_m}, {"mesh_frequency_Hz", p.mesh_frequency_Hz},
          {"load_torque_Nm", p.load_torque_Nm}, {"output_speed_rad_s", p.output_speed_rad_s}};
}

std::string truth_text(const SynthOptions& o, int samples, const nlohmann::json& effects, double noise) {
  nlohmann::json noise_block = {{"white_sd", o.white_sd}, {"ar1_sd", o.ar1_sd}, {"ar1_phi", o.ar1_phi},
                                {"quantum", o.quantum}, {"rms", noise}};
  if (const auto* d = std::get_if<DynamicsRows>(&o.rows)) noise_block["speed_sd_rpm"] = d->speed_sd_rpm;
  const nlohmann::json truth = {
      {"kind", kind_name(o.baseline.kind())},
      {"seed", o.seed},
      {"samples", samples},
      {"effects", effects},
      {"noise", noise_block},
      {"gain_error", o.gain_error},
      {"concealment", o.concealment},
      {"baseline", std::visit([&](const auto& p) { return baseline_truth(o.baseline.gear, p); },
                              o.baseline.prediction)}};
  return truth.dump(2) + "\n";
}

// ---- the recording's rows -----------------------------------------------------------------------------------------

void number_rows(Recording& rec, int n) {
  rec.lines.resize(n);
  for (int i = 0; i < n; ++i) rec.lines[i] = i + 1;
}

void lay_out_rows(const SynthOptions& o, const TorsionRows& rows, Recording& rec) {
  const int n = o.samples;
  const double A = rows.torque_amplitude_Nm;
  rec.columns = {"time_s", "torque_Nm", "twist_rad"};
  rec.values.assign(3, std::vector<double>(n));
  for (int i = 0; i < n; ++i) {
    rec.values[0][i] = i * rows.sample_period_s;
    rec.values[1][i] = -A * std::cos(2.0 * M_PI * rows.cycles * i / n);
  }
  rec.metadata.push_back({"torque_amplitude_Nm", std::to_string(A)});
}

void lay_out_rows(const SynthOptions& o, const TransmissionRows& rows, Recording& rec) {
  const int n = o.samples;
  const DriveGear& g = o.baseline.gear;
  rec.columns = {"time_s", "wg_angle_rad", "output_angle_rad"};
  rec.values.assign(3, std::vector<double>(n));
  const double wg_total =
      rows.output_revolutions * 2.0 * M_PI * g.teeth_flexspline / double(g.teeth_circular - g.teeth_flexspline);
  for (int i = 0; i < n; ++i) {
    rec.values[0][i] = i * rows.sample_period_s;
    rec.values[1][i] = wg_total * i / n;
  }
  rec.metadata.push_back({"teeth_flexspline", std::to_string(g.teeth_flexspline)});
  rec.metadata.push_back({"teeth_circular", std::to_string(g.teeth_circular)});
}

void lay_out_rows(const SynthOptions& o, const BacklashRows& rows, Recording& rec) {
  const int n = o.samples;
  const double A = rows.torque_amplitude_Nm;
  rec.columns = {"wg_angle_deg", "torque_Nm", "backlash_um"};
  rec.values.assign(3, std::vector<double>(n));
  const int levels = std::max(1, rows.torque_levels);
  const int per = (n + levels - 1) / levels;
  for (int i = 0; i < n; ++i) {
    const int level = i / per;
    rec.values[0][i] = 360.0 * (i % per) / per;
    rec.values[1][i] = levels == 1 ? A : A * level / (levels - 1.0);
  }
}

// ---- kinds with a response column ---------------------------------------------------------------------------------

/// Adds one hidden effect to the true response and its entries (and an effect its law implies) to the truth.
void add_column_effect(const SynthOptions& o, const Experiment& e, const SynthEffect& fx, SynthResult& out,
                       Vec& truth_response, nlohmann::json& effects) {
  const SynthLaw law = synth_law(e.kind(), fx);
  const SynthShape s = std::get<ColumnLaw>(law.generator->law)(fx, e);
  double amp = s.amplitude;
  if (o.concealment > 0.0) {
    const double r = rms(s.column);
    if (!(r > 0.0)) throw InputError("synth effect " + fx.name + " has no effect on this experiment");
    amp = (amp < 0 ? -1.0 : 1.0) * o.concealment * out.noise_rms / r;
  }
  const Vec contribution = amp * s.column;
  truth_response += contribution;
  out.effect_rms.push_back({fx.name, rms(contribution)});
  nlohmann::json entry = {{"name", law.effect->name}, {"params", json_of(s.truth(amp))}, {"rms", rms(contribution)}};
  if (law.generator->names_generator) entry["generator"] = fx.name;
  effects.push_back(entry);
  if (s.implied && std::abs(s.implied->value(amp)) > 0.0) {
    const double c = s.implied->value(amp);
    effects.push_back({{"name", s.implied->name},
                       {"params", {{s.implied->parameter, c}}},
                       {"rms", rms(Vec(c * s.implied->column))},
                       {"implied_by", fx.name}});
  }
}

/// Torsion, transmission, backlash: the baseline of the recording's rows plus the hidden effects, recorded with noise.
SynthResult synthesize_response(const SynthOptions& o, Recording rec) {
  const int n = o.samples;
  number_rows(rec, n);
  // Experiment with a zero response, to get the baseline and the derived inputs.
  rec.values.back().assign(n, 0.0);
  const Experiment e = make_experiment(rec, o.baseline);
  SynthResult out;
  out.noise_rms = noise_rms(o);
  Vec truth_response = e.baseline;
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& fx : o.effects) add_column_effect(o, e, fx, out, truth_response, effects);
  SensorNoise noise(o);
  std::vector<double>& response = rec.values.back();
  for (int i = 0; i < n; ++i) response[i] = noise.record(truth_response[i]);
  out.truth_json = truth_text(o, n, effects, out.noise_rms);
  out.recording = std::move(rec);
  return out;
}

// ---- dynamics -----------------------------------------------------------------------------------------------------

/// The meshing force of the dynamics model under a variation, and the run.
std::pair<DynamicsRun, Vec> force_of(const DynamicsPrediction& p, const DynamicsVariation& v) {
  const DynamicsRun r = p.dynamics_run(v);
  return {r, Vec(Eigen::Map<const Vec>(r.mesh_force_N.data(), r.mesh_force_N.size()))};
}

/// Adds one hidden effect to the variation of the recorded run (`all`) and its entry to the truth. Its size is
/// measured where reconcile compares (the baseline's analysed rows, from `first` on).
void add_dynamics_effect(const SynthOptions& o, const DynamicsPrediction& p, const SynthEffect& fx, const Vec& f0,
                         Eigen::Index first, DynamicsVariation& all, SynthResult& out, nlohmann::json& effects) {
  const SynthLaw law = synth_law(Kind::Dynamics, fx);
  const SynthVariation d = std::get<VariationLaw>(law.generator->law)(fx, p);
  auto scaled = [&](double k) {
    DynamicsVariation v;
    d.vary(v, k);
    return v;
  };
  auto analysed_rms = [&](const Vec& diff) { return rms(diff.tail(diff.size() - first)); };
  double k = 1.0;
  Vec diff = force_of(p, scaled(1.0)).second - f0;
  if (o.concealment > 0.0) {
    // Rescale so the effect's RMS on the meshing force is concealment x noise RMS (two secant steps).
    for (int it = 0; it < 2; ++it) {
      const double r = analysed_rms(diff);
      if (!(r > 0.0)) throw InputError("synth effect " + fx.name + " has no effect on this run");
      k *= o.concealment * out.noise_rms / r;
      diff = force_of(p, scaled(k)).second - f0;
    }
  }
  d.vary(all, k);
  out.effect_rms.push_back({fx.name, analysed_rms(diff)});
  effects.push_back({{"name", law.effect->name}, {"params", json_of(d.truth(k))}, {"rms", analysed_rms(diff)}});
}

/// Dynamics: the recording is a run of the dynamics model with the hidden effects (all at once), on the model's own
/// time grid, plus noise on the meshing force (white, AR(1), quantum) and white noise of speed_sd_rpm on both speeds.
SynthResult synthesize_dynamics(const SynthOptions& o, const DynamicsPrediction& p, const DynamicsRows& rows,
                                Recording rec) {
  if (!p.dynamics_run) throw InputError("synth: kind = dynamics needs the case's dynamics model (--case)");
  SynthResult out;
  out.noise_rms = noise_rms(o);
  const DynamicsRun base = p.dynamics_run(DynamicsVariation{});
  const Vec f0 = Eigen::Map<const Vec>(base.mesh_force_N.data(), base.mesh_force_N.size());
  const auto first = std::lower_bound(base.time_s.begin(), base.time_s.end(), p.analysis_from_s) - base.time_s.begin();
  DynamicsVariation all;
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& fx : o.effects) add_dynamics_effect(o, p, fx, f0, first, all, out, effects);
  const DynamicsRun run = o.effects.empty() ? base : force_of(p, all).first;
  const int n = static_cast<int>(run.time_s.size());
  rec.columns = {"time_s", "wg_speed_rpm", "output_speed_rpm", "mesh_force_N"};
  rec.values = {run.time_s, run.wg_speed_rpm, run.output_speed_rpm, run.mesh_force_N};
  number_rows(rec, n);
  rec.metadata.push_back({"mesh_frequency_Hz", std::to_string(p.mesh_frequency_Hz)});
  rec.metadata.push_back({"load_torque_Nm", std::to_string(p.load_torque_Nm)});
  SensorNoise noise(o);
  for (int i = 0; i < n; ++i) {
    rec.values[3][i] = noise.record(rec.values[3][i]);
    rec.values[1][i] += rows.speed_sd_rpm * noise.normal();
    rec.values[2][i] += rows.speed_sd_rpm * noise.normal();
  }
  out.truth_json = truth_text(o, n, effects, out.noise_rms);
  out.recording = std::move(rec);
  return out;
}

}  // namespace

std::vector<SynthEffect> parse_synth_effects(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const bool continues = item.find(':') == std::string::npos && item.find('=') != std::string::npos;
    if (continues) {
      if (items.empty()) throw InputError("--effects = '" + text + "'; '" + item + "' expected an effect name first");
      items.back() += "," + item;
    } else {
      items.push_back(item);
    }
  }
  std::vector<SynthEffect> out;
  for (const auto& x : items) out.push_back(parse_synth_effect(x));
  return out;
}

SynthEffect parse_synth_effect(const std::string& text) {
  SynthEffect fx;
  const auto colon = text.find(':');
  fx.name = text.substr(0, colon);
  if (fx.name.empty()) throw InputError("--effect = '" + text + "'; expected name[:key=value,...]");
  if (colon == std::string::npos) return fx;
  std::stringstream ss(text.substr(colon + 1));
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw InputError("--effect = '" + text + "'; item '" + item + "' expected key=value");
    const std::string key = item.substr(0, eq);
    const std::string val = item.substr(eq + 1);
    char* end = nullptr;
    const double v = std::strtod(val.c_str(), &end);
    if (val.empty() || *end != '\0' || !std::isfinite(v))
      throw InputError("--effect = '" + text + "'; " + key + " = '" + val + "' expected a number");
    if (key == "order") fx.order = static_cast<int>(v);
    else fx.params[key] = v;
  }
  return fx;
}

std::string synth_effect_help() {
  std::string help =
      "effects (--effect name[:key=value,...], or --effects a,b:key=value,key=value,c; A = torque amplitude,\n"
      "C = C_tau):\n";
  for (Kind kind : kKinds) {
    std::string label = "  " + kind_name(kind) + ":";
    label.resize(16, ' ');
    for (const Effect& effect : effect_table(kind))
      for (const SynthGenerator& g : effect.generators) {
        help += label + g.name + g.help + "\n";
        label.assign(16, ' ');
      }
  }
  return help + "With --concealment R each effect's amplitude is rescaled so that its RMS is R times the noise RMS.";
}

SynthOptions dynamics_proof_options(const Baseline& baseline, double noise_N, std::uint64_t seed) {
  SynthOptions o;
  o.baseline = baseline;
  o.white_sd = noise_N;
  o.ar1_sd = noise_N;
  o.quantum = 0.2 * noise_N;
  o.rows = DynamicsRows{.speed_sd_rpm = 0.05};
  o.seed = seed;
  return o;
}

SynthResult synthesize(const SynthOptions& o) {
  if (o.samples < kMinSamples)
    throw InputError("synth: samples = " + std::to_string(o.samples) + "; must be >= " + std::to_string(kMinSamples));
  if (!(std::abs(o.ar1_phi) < 1.0))
    throw InputError("synth: ar1_phi = " + std::to_string(o.ar1_phi) + "; must satisfy |phi| < 1");
  Recording rec;
  rec.path = "<synth>";
  rec.kind = o.baseline.kind();
  rec.metadata = {{"strainwave-recording", "1"},
                  {"kind", kind_name(rec.kind)},
                  {"source", "synthetic: strainwave synth (hidden effects and noise; see the truth file)"},
                  {"seed", std::to_string(o.seed)}};
  return std::visit(
      [&](const auto& p, const auto& rows) -> SynthResult {
        using P = std::decay_t<decltype(p)>;
        using Rows = std::decay_t<decltype(rows)>;
        if constexpr (P::kind != Rows::kind) {
          throw InputError("synth: the rows are laid out for kind " + kind_name(Rows::kind) +
                           "; the baseline is of kind " + kind_name(P::kind));
        } else if constexpr (P::kind == Kind::Dynamics) {
          return synthesize_dynamics(o, p, rows, std::move(rec));
        } else {
          lay_out_rows(o, rows, rec);
          return synthesize_response(o, std::move(rec));
        }
      },
      o.baseline.prediction, o.rows);
}

}  // namespace sw::reconcile
