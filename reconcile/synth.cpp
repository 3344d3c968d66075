#include "reconcile/synth.hpp"

#include <cmath>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "reconcile/catalog.hpp"

namespace sw::reconcile {

using Vec = Eigen::VectorXd;

namespace {

double rms(const Vec& v) { return std::sqrt(v.squaredNorm() / std::max<Eigen::Index>(1, v.size())); }

double get(const SynthEffect& fx, const std::string& key, double fallback) {
  const auto it = fx.params.find(key);
  return it == fx.params.end() ? fallback : it->second;
}

void check_keys(const SynthEffect& fx, const std::vector<std::string>& allowed) {
  for (const auto& [k, v] : fx.params) {
    bool ok = false;
    for (const auto& a : allowed) ok = ok || a == k;
    if (!ok) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw InputError("synth effect " + fx.name + ": parameter " + k + " = " + std::to_string(v) +
                       "; unknown, expected one of " + list);
    }
  }
}

/// Unit-amplitude shape of an effect and how to turn an amplitude into headline parameters.
struct Shape {
  Vec column;         // contribution per unit amplitude
  double amplitude;   // the requested amplitude
  std::function<nlohmann::json(double amplitude)> headline;
};

Shape shape_of(const SynthEffect& fx, const Experiment& e) {
  const double A = e.torque_amplitude_Nm;
  const double C = e.model.compliance_rad_per_Nm;
  Shape s;
  auto harmonic = [&](const Vec& angle, const std::string& unit, double def_amp) {
    check_keys(fx, {"order", "amplitude_" + unit, "phase_rad"});
    const int k = fx.order;
    if (k < 1 || k > kMaxHarmonicOrder)
      throw InputError("synth effect " + fx.name + ": order = " + std::to_string(k) + "; expected 1.." +
                       std::to_string(kMaxHarmonicOrder));
    const double ph = get(fx, "phase_rad", 0.3);
    s.column = (k * angle.array() + ph).cos();
    s.amplitude = get(fx, "amplitude_" + unit, def_amp);
    s.headline = [k, ph, unit](double a) {
      return nlohmann::json{{"order", k}, {"amplitude_" + unit, a}, {"phase_rad", ph}};
    };
  };
  if (e.kind == Kind::Torsion) {
    if (fx.name == "series_compliance") {
      check_keys(fx, {"compliance_rad_per_Nm"});
      s.column = e.torque_Nm;
      s.amplitude = get(fx, "compliance_rad_per_Nm", 0.25 * C);
      s.headline = [](double a) { return nlohmann::json{{"compliance_rad_per_Nm", a}}; };
      return s;
    }
    if (fx.name == "stiffness_nonlinearity") {
      check_keys(fx, {"K1_Nm_per_rad", "T1_Nm"});
      const double t1 = get(fx, "T1_Nm", 0.3 * A);
      s.column = soft_start_column(e.torque_Nm, t1);
      s.amplitude = 1.0 / get(fx, "K1_Nm_per_rad", 0.5 / C) - C;  // 1/K1 - 1/K2 with K2 = 1/C_tau
      s.headline = [t1, C](double a) {
        return nlohmann::json{{"K1_Nm_per_rad", 1.0 / (C + a)}, {"T1_Nm", t1}, {"K2_Nm_per_rad", 1.0 / C}};
      };
      return s;
    }
    if (fx.name == "hysteresis") {
      check_keys(fx, {"loss_rad", "transition_Nm"});
      const double th = get(fx, "transition_Nm", 0.05 * A);
      const double factor = hysteresis_loss_rad(1.0, th, A);
      s.column = hysteresis_column(e, th) / factor;  // per unit of loss (gap at zero torque)
      s.amplitude = get(fx, "loss_rad", 1e-4);
      s.headline = [th](double a) { return nlohmann::json{{"loss_rad", a}, {"transition_Nm", th}}; };
      return s;
    }
    if (fx.name == "lost_motion") {
      check_keys(fx, {"width_rad", "transition_Nm"});
      const double ts = get(fx, "transition_Nm", 0.01 * A);
      s.column = lost_motion_column(e.torque_Nm, ts);
      s.amplitude = get(fx, "width_rad", 1e-4);
      s.headline = [ts](double a) { return nlohmann::json{{"width_rad", a}, {"transition_Nm", ts}}; };
      return s;
    }
  } else if (e.kind == Kind::Transmission) {
    if (fx.name == "wg_harmonic") { harmonic(e.wg_angle_rad, "rad", 1e-5); return s; }
    if (fx.name == "output_harmonic") { harmonic(e.output_angle_rad, "rad", 1e-5); return s; }
  } else if (e.kind == Kind::Backlash) {
    if (fx.name == "wg_harmonic") { harmonic(e.wg_angle_rad, "um", 1.0); return s; }
    if (fx.name == "load_torsion") {
      check_keys(fx, {"compliance_rad_per_Nm"});
      s.column = -e.model.pitch_radius_m * 1e6 * e.torque_Nm;
      s.amplitude = get(fx, "compliance_rad_per_Nm", 2e-5);
      s.headline = [](double a) { return nlohmann::json{{"compliance_rad_per_Nm", a}}; };
      return s;
    }
    if (fx.name == "uniform_clearance") {
      check_keys(fx, {"offset_um"});
      s.column = Vec::Ones(e.n);
      s.amplitude = get(fx, "offset_um", 1.0);
      s.headline = [](double a) { return nlohmann::json{{"offset_um", a}}; };
      return s;
    }
  }
  throw InputError("synth effect = '" + fx.name + "'; not an effect of kind " + kind_name(e.kind) +
                   " (see strainwave synth --help)");
}

/// A dynamics effect as a model variation with amplitude `scale` times its headline parameters.
struct DynamicsEffect {
  DynamicsVariation variation;
  std::function<DynamicsVariation(double scale)> scaled;
  std::function<nlohmann::json(double scale)> headline;
};

DynamicsEffect dynamics_effect(const SynthEffect& fx, const Baseline& b) {
  DynamicsEffect d;
  if (fx.name == "mesh_stiffness_variation") {
    check_keys(fx, {"amplitude_ratio", "phase_rad"});
    const double r = get(fx, "amplitude_ratio", 0.05), ph = get(fx, "phase_rad", 0.3);
    const double fm = b.mesh_frequency_Hz;
    d.scaled = [r, ph](double k) { DynamicsVariation v; v.stiffness_ratio = k * r; v.stiffness_phase_rad = ph; return v; };
    d.headline = [r, ph, fm](double k) {
      return nlohmann::json{{"amplitude_ratio", k * r}, {"frequency_Hz", fm}, {"phase_rad", ph}};
    };
  } else if (fx.name == "damping") {
    check_keys(fx, {"coefficient_Ns_per_m"});
    const double c0 = b.damping_Ns_per_m;
    const double c = get(fx, "coefficient_Ns_per_m", c0 > 0 ? 2.0 * c0 : 1e3);
    d.scaled = [c, c0](double k) { DynamicsVariation v; v.damping_Ns_per_m = std::max(0.0, c0 + k * (c - c0)); return v; };
    d.headline = [c, c0](double k) {
      return nlohmann::json{{"coefficient_Ns_per_m", std::max(0.0, c0 + k * (c - c0))}, {"added_Ns_per_m", k * (c - c0)}};
    };
  } else if (fx.name == "drag_torque") {
    check_keys(fx, {"coulomb_Nm", "viscous_Nms_per_rad"});
    const double tc = get(fx, "coulomb_Nm", std::max(0.02 * b.load_torque_Nm, 0.1));
    const double bv = get(fx, "viscous_Nms_per_rad", tc / std::max(b.output_speed_rad_s, 1e-6));
    const double w = b.output_speed_rad_s;
    d.scaled = [tc, bv](double k) {
      DynamicsVariation v; v.drag_coulomb_Nm = k * tc; v.drag_viscous_Nms_per_rad = k * bv; return v;
    };
    d.headline = [tc, bv, w](double k) {
      return nlohmann::json{{"coulomb_Nm", k * tc}, {"viscous_Nms_per_rad", k * bv}, {"torque_at_speed_Nm", k * (tc + bv * w)}};
    };
  } else {
    throw InputError("synth effect = '" + fx.name + "'; not an effect of kind dynamics (see strainwave synth --help)");
  }
  d.variation = d.scaled(1.0);
  return d;
}

}  // namespace

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
  return "effects (--effect name[:key=value,...]; A = torque amplitude, C = C_tau):\n"
         "  torsion:      series_compliance:compliance_rad_per_Nm (0.25 C)\n"
         "                stiffness_nonlinearity:K1_Nm_per_rad (0.5/C),T1_Nm (0.3 A)   [K2 = 1/C]\n"
         "                hysteresis:loss_rad (1e-4),transition_Nm (0.05 A)\n"
         "                lost_motion:width_rad (1e-4),transition_Nm (0.01 A)\n"
         "  transmission: wg_harmonic:order=k,amplitude_rad (1e-5),phase_rad (0.3)\n"
         "                output_harmonic:order=k,amplitude_rad (1e-5),phase_rad (0.3)\n"
         "  backlash:     load_torsion:compliance_rad_per_Nm (2e-5)\n"
         "                wg_harmonic:order=k,amplitude_um (1),phase_rad (0.3)\n"
         "                uniform_clearance:offset_um (1)\n"
         "  dynamics:     mesh_stiffness_variation:amplitude_ratio (0.05),phase_rad (0.3)   [frequency_Hz = f_m]\n"
         "                damping:coefficient_Ns_per_m (2 c0)\n"
         "                drag_torque:coulomb_Nm (0.02 load),viscous_Nms_per_rad (same torque at speed)\n"
         "With --concealment R each effect's amplitude is rescaled so that its RMS is R times the noise RMS.";
}

namespace {

/// Dynamics: the recording is a run of the dynamics model with the hidden effects (all at once), on the model's own
/// time grid, plus noise on the meshing force (white, AR(1), quantum) and white noise of speed_sd_rpm on both speeds.
SynthResult synthesize_dynamics(const SynthOptions& o, Recording rec) {
  const Baseline& b = o.baseline;
  if (!b.dynamics_run) throw InputError("synth: kind = dynamics needs the case's dynamics model (--case)");
  SynthResult out;
  out.noise_rms = std::sqrt(o.white_sd * o.white_sd + o.ar1_sd * o.ar1_sd + o.quantum * o.quantum / 12.0);
  const DynamicsRun base = b.dynamics_run(DynamicsVariation{});
  const Vec f0 = Eigen::Map<const Vec>(base.mesh_force_N.data(), base.mesh_force_N.size());
  auto force = [&](const DynamicsVariation& v) {
    const DynamicsRun r = b.dynamics_run(v);
    return std::make_pair(r, Vec(Eigen::Map<const Vec>(r.mesh_force_N.data(), r.mesh_force_N.size())));
  };
  DynamicsVariation all;
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& fx : o.effects) {
    DynamicsEffect d = dynamics_effect(fx, b);
    double k = 1.0;
    Vec diff = force(d.variation).second - f0;
    if (o.concealment > 0.0) {
      // Rescale so the effect's RMS on the meshing force is concealment x noise RMS (two secant steps).
      for (int it = 0; it < 2; ++it) {
        const double r = rms(diff);
        if (!(r > 0.0)) throw InputError("synth effect " + fx.name + " has no effect on this run");
        k *= o.concealment * out.noise_rms / r;
        diff = force(d.scaled(k)).second - f0;
      }
    }
    const DynamicsVariation v = d.scaled(k);
    if (fx.name == "mesh_stiffness_variation") { all.stiffness_ratio = v.stiffness_ratio; all.stiffness_phase_rad = v.stiffness_phase_rad; }
    if (fx.name == "damping") all.damping_Ns_per_m = v.damping_Ns_per_m;
    if (fx.name == "drag_torque") { all.drag_coulomb_Nm = v.drag_coulomb_Nm; all.drag_viscous_Nms_per_rad = v.drag_viscous_Nms_per_rad; }
    out.effect_rms.push_back({fx.name, rms(diff)});
    effects.push_back({{"name", fx.name}, {"params", d.headline(k)}, {"rms", rms(diff)}});
  }
  const DynamicsRun run = o.effects.empty() ? base : force(all).first;
  const int n = static_cast<int>(run.time_s.size());
  rec.columns = {"time_s", "wg_speed_rpm", "output_speed_rpm", "mesh_force_N"};
  rec.values = {run.time_s, run.wg_speed_rpm, run.output_speed_rpm, run.mesh_force_N};
  rec.lines.resize(n);
  for (int i = 0; i < n; ++i) rec.lines[i] = i + 1;
  rec.metadata.push_back({"mesh_frequency_Hz", std::to_string(b.mesh_frequency_Hz)});
  rec.metadata.push_back({"load_torque_Nm", std::to_string(b.load_torque_Nm)});
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double innov = o.ar1_sd * std::sqrt(1.0 - o.ar1_phi * o.ar1_phi);
  double ar = o.ar1_sd * normal(rng);
  for (int i = 0; i < n; ++i) {
    if (i > 0) ar = o.ar1_phi * ar + innov * normal(rng);
    double v = (1.0 + o.gain_error) * rec.values[3][i] + o.white_sd * normal(rng) + ar;
    if (o.quantum > 0.0) v = std::round(v / o.quantum) * o.quantum;
    rec.values[3][i] = v;
    rec.values[1][i] += o.speed_sd_rpm * normal(rng);
    rec.values[2][i] += o.speed_sd_rpm * normal(rng);
  }
  nlohmann::json truth = {
      {"kind", kind_name(o.kind)},
      {"seed", o.seed},
      {"samples", n},
      {"effects", effects},
      {"noise",
       {{"white_sd", o.white_sd}, {"ar1_sd", o.ar1_sd}, {"ar1_phi", o.ar1_phi}, {"quantum", o.quantum},
        {"speed_sd_rpm", o.speed_sd_rpm}, {"rms", out.noise_rms}}},
      {"gain_error", o.gain_error},
      {"concealment", o.concealment},
      {"baseline",
       {{"damping_Ns_per_m", b.damping_Ns_per_m}, {"mesh_frequency_Hz", b.mesh_frequency_Hz},
        {"load_torque_Nm", b.load_torque_Nm}, {"output_speed_rad_s", b.output_speed_rad_s}}}};
  out.truth_json = truth.dump(2) + "\n";
  out.recording = std::move(rec);
  return out;
}

}  // namespace

SynthResult synthesize(const SynthOptions& o) {
  if (o.samples < kMinSamples)
    throw InputError("synth: samples = " + std::to_string(o.samples) + "; must be >= " + std::to_string(kMinSamples));
  if (!(std::abs(o.ar1_phi) < 1.0))
    throw InputError("synth: ar1_phi = " + std::to_string(o.ar1_phi) + "; must satisfy |phi| < 1");
  const int n = o.samples;
  Recording rec;
  rec.path = "<synth>";
  rec.kind = o.kind;
  rec.metadata = {{"strainwave-recording", "1"},
                  {"kind", kind_name(o.kind)},
                  {"source", "synthetic: strainwave synth (hidden effects and noise; see the truth file)"},
                  {"seed", std::to_string(o.seed)}};
  std::vector<std::vector<double>> cols;
  const double A = o.torque_amplitude_Nm;
  if (o.kind == Kind::Torsion) {
    rec.columns = {"time_s", "torque_Nm", "twist_rad"};
    cols.assign(3, std::vector<double>(n));
    for (int i = 0; i < n; ++i) {
      cols[0][i] = i * o.sample_period_s;
      cols[1][i] = A * std::sin(2.0 * M_PI * o.cycles * i / n);
    }
    rec.metadata.push_back({"torque_amplitude_Nm", std::to_string(A)});
  } else if (o.kind == Kind::Transmission) {
    const auto& b = o.baseline;
    rec.columns = {"time_s", "wg_angle_rad", "output_angle_rad"};
    cols.assign(3, std::vector<double>(n));
    const double wg_total = o.cycles * 2.0 * M_PI * b.teeth_flexspline / double(b.teeth_circular - b.teeth_flexspline);
    for (int i = 0; i < n; ++i) {
      cols[0][i] = i * o.sample_period_s;
      cols[1][i] = wg_total * i / n;
    }
    rec.metadata.push_back({"teeth_flexspline", std::to_string(b.teeth_flexspline)});
    rec.metadata.push_back({"teeth_circular", std::to_string(b.teeth_circular)});
  } else if (o.kind == Kind::Backlash) {
    rec.columns = {"wg_angle_deg", "torque_Nm", "backlash_um"};
    cols.assign(3, std::vector<double>(n));
    const int levels = std::max(1, o.torque_levels);
    const int per = (n + levels - 1) / levels;
    for (int i = 0; i < n; ++i) {
      const int level = i / per;
      cols[0][i] = 360.0 * (i % per) / per;
      cols[1][i] = levels == 1 ? A : A * level / (levels - 1.0);
    }
  } else if (o.kind == Kind::Dynamics) {
    return synthesize_dynamics(o, std::move(rec));
  } else {
    throw InputError("synth: kind = " + kind_name(o.kind) + "; synth writes torsion, transmission, backlash, dynamics");
  }
  rec.values = cols;
  rec.lines.resize(n);
  for (int i = 0; i < n; ++i) rec.lines[i] = i + 1;
  // Experiment with a zero response, to get the baseline and the derived inputs.
  rec.values.back().assign(n, 0.0);
  Experiment e = make_experiment(rec, o.baseline);

  SynthResult out;
  out.noise_rms = std::sqrt(o.white_sd * o.white_sd + o.ar1_sd * o.ar1_sd + o.quantum * o.quantum / 12.0);
  Vec truth_response = e.baseline;
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& fx : o.effects) {
    Shape s = shape_of(fx, e);
    double amp = s.amplitude;
    if (o.concealment > 0.0) {
      const double r = rms(s.column);
      if (!(r > 0.0)) throw InputError("synth effect " + fx.name + " has no effect on this experiment");
      amp = (amp < 0 ? -1.0 : 1.0) * o.concealment * out.noise_rms / r;
    }
    const Vec contribution = amp * s.column;
    truth_response += contribution;
    out.effect_rms.push_back({fx.name, rms(contribution)});
    effects.push_back({{"name", fx.name}, {"params", s.headline(amp)}, {"rms", rms(contribution)}});
  }
  std::mt19937_64 rng(o.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double innov = o.ar1_sd * std::sqrt(1.0 - o.ar1_phi * o.ar1_phi);
  double ar = o.ar1_sd * normal(rng);  // stationary start
  std::vector<double>& response = rec.values.back();
  for (int i = 0; i < n; ++i) {
    if (i > 0) ar = o.ar1_phi * ar + innov * normal(rng);
    double v = (1.0 + o.gain_error) * truth_response[i] + o.white_sd * normal(rng) + ar;
    if (o.quantum > 0.0) v = std::round(v / o.quantum) * o.quantum;
    response[i] = v;
  }
  nlohmann::json truth = {
      {"kind", kind_name(o.kind)},
      {"seed", o.seed},
      {"samples", n},
      {"effects", effects},
      {"noise",
       {{"white_sd", o.white_sd}, {"ar1_sd", o.ar1_sd}, {"ar1_phi", o.ar1_phi}, {"quantum", o.quantum},
        {"rms", out.noise_rms}}},
      {"gain_error", o.gain_error},
      {"concealment", o.concealment},
      {"baseline",
       {{"compliance_rad_per_Nm", o.baseline.compliance_rad_per_Nm},
        {"teeth_flexspline", o.baseline.teeth_flexspline},
        {"teeth_circular", o.baseline.teeth_circular},
        {"pitch_radius_m", o.baseline.pitch_radius_m}}}};
  out.truth_json = truth.dump(2) + "\n";
  out.recording = std::move(rec);
  return out;
}

}  // namespace sw::reconcile
