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
  std::string truth_name;                             // catalog name in the truth file ("": the effect's own)
  std::function<double(double amplitude)> implied_series;  // series compliance a law implies (rad/(N*m))
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
    if (fx.name == "stiffness_nonlinearity" || fx.name == "stiffness_smooth") {
      // The whole drive's law (catalog form: K1 up to T1, K2 up to T2, K3 beyond; two segments without T2) minus
      // the baseline C_tau T; a last slope other than 1/C_tau is series compliance, listed in the truth as implied.
      // stiffness_smooth rounds each corner over width * T (tanh steps of the compliance): a structure the fitter's
      // straight segments do not have.
      const bool smooth = fx.name == "stiffness_smooth";
      check_keys(fx, smooth ? std::vector<std::string>{"K1_Nm_per_rad", "K2_Nm_per_rad", "K3_Nm_per_rad", "T1_Nm",
                                                       "T2_Nm", "width"}
                            : std::vector<std::string>{"K1_Nm_per_rad", "K2_Nm_per_rad", "K3_Nm_per_rad", "T1_Nm",
                                                       "T2_Nm"});
      const bool three = fx.params.count("T2_Nm") > 0;
      const double t1 = get(fx, "T1_Nm", 0.3 * A), t2 = three ? get(fx, "T2_Nm", 0.0) : INFINITY;
      const double k1 = get(fx, "K1_Nm_per_rad", 0.5 / C);
      const double k2 = get(fx, "K2_Nm_per_rad", three ? 0.75 / C : 1.0 / C);
      const double k3 = three ? get(fx, "K3_Nm_per_rad", 1.0 / C) : k2;
      if (!(t1 > 0.0) || (three && !(t2 > t1)) || !(k1 > 0.0) || !(k2 > 0.0) || !(k3 > 0.0))
        throw InputError("synth effect " + fx.name + ": expected 0 < T1_Nm < T2_Nm and K1, K2, K3 > 0");
      const double w = get(fx, "width", 0.3);
      auto smooth_twist = [=](double T) {
        // integral of 1/K3 + (1/K2 - 1/K3) s(x, T2) + (1/K1 - 1/K2) s(x, T1), s = (1 - tanh((x - Tb) / d)) / 2
        auto logcosh = [](double u) { return std::abs(u) + std::log1p(std::exp(-2.0 * std::abs(u))) - std::log(2.0); };
        auto step_integral = [&](double x, double tb) {
          if (!std::isfinite(tb)) return x;
          const double d = w * tb;
          return 0.5 * (x - d * logcosh((x - tb) / d) + d * logcosh(-tb / d));
        };
        const double x = std::abs(T);
        const double v = x / k3 + (1.0 / k2 - 1.0 / k3) * step_integral(x, t2) + (1.0 / k1 - 1.0 / k2) * step_integral(x, t1);
        return T < 0 ? -v : v;
      };
      s.column.resize(e.n);
      for (int i = 0; i < e.n; ++i) {
        const double T = e.torque_Nm[i];
        s.column[i] = (smooth ? smooth_twist(T) : segment_law_twist(T, k1, k2, k3, t1, std::isfinite(t2) ? t2 : 1e300)) - C * T;
      }
      s.amplitude = 1.0;  // a scale of every compliance step relative to C_tau
      s.implied_series = [k3, C](double a) { return a * (1.0 / k3 - C); };
      s.headline = [=](double a) {
        auto K = [&](double k) { return 1.0 / (C + a * (1.0 / k - C)); };
        nlohmann::json j = {{"K1_Nm_per_rad", K(k1)}, {"T1_Nm", t1}, {"K2_Nm_per_rad", K(k2)}};
        if (three) j.update({{"T2_Nm", t2}, {"K3_Nm_per_rad", K(k3)}});
        if (smooth) j["corner_width"] = w;
        return j;
      };
      s.truth_name = "stiffness_nonlinearity";
      return s;
    }
    if (fx.name == "friction_bouc_wen") {
      // Bouc-Wen friction in the twist, driven by torque: dz = dT (1 - (sgn(dT z) + 1) |z|^n / 2) / T_h; the twist is
      // -z h / 2, so the loading branch lies below. The branch gap grows with amplitude and its shape (n = 2 by
      // default) is not the fitter's exponential. Run over the signal twice (the first pass sets the history), scaled
      // so the gap at zero torque is loss_rad.
      check_keys(fx, {"loss_rad", "transition_Nm", "n"});
      const double th = get(fx, "transition_Nm", 0.05 * A), nexp = get(fx, "n", 2.0);
      Vec z(e.n);
      double zi = 0.0;
      for (int pass = 0; pass < 2; ++pass)
        for (int i = 0; i < e.n; ++i) {
          const double dT = (e.torque_Nm[i] - e.torque_Nm[i == 0 ? e.n - 1 : i - 1]) / 50.0;
          for (int k = 0; k < 50; ++k) {
            const double sg = dT * zi > 0 ? 1.0 : dT * zi < 0 ? -1.0 : 0.0;
            zi += dT / th * (1.0 - 0.5 * (sg + 1.0) * std::pow(std::abs(zi), nexp));
          }
          z[i] = zi;
        }
      const Vec col = -0.5 * z;
      // Branch gap at zero torque, from the zero crossings (linear interpolation) after the first cycle.
      double up = 0, down = 0;
      int nu = 0, nd = 0;
      for (int i = e.n / 4; i + 1 < e.n; ++i) {
        const double a0 = e.torque_Nm[i], a1 = e.torque_Nm[i + 1];
        if ((a0 < 0) == (a1 < 0) || a0 == a1) continue;
        const double f = a0 / (a0 - a1), v = col[i] + f * (col[i + 1] - col[i]);
        if (a1 > a0) { up += v; ++nu; } else { down += v; ++nd; }
      }
      if (nu == 0 || nd == 0) throw InputError("synth effect friction_bouc_wen: the torque must cross zero both ways");
      const double gap = down / nd - up / nu;
      s.column = col / gap;
      s.amplitude = get(fx, "loss_rad", 1e-4);
      s.headline = [th, nexp](double a) {
        return nlohmann::json{{"loss_rad", a}, {"bouc_wen_transition_Nm", th}, {"bouc_wen_n", nexp}};
      };
      s.truth_name = "hysteresis";
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
  return "effects (--effect name[:key=value,...], or --effects a,b:key=value,key=value,c; A = torque amplitude,\n"
         "C = C_tau):\n"
         "  torsion:      series_compliance:compliance_rad_per_Nm (0.25 C)\n"
         "                stiffness_nonlinearity:K1_Nm_per_rad (0.5/C),T1_Nm (0.3 A),K2_Nm_per_rad (1/C)\n"
         "                  three segments with T2_Nm: K2 default 0.75/C, K3_Nm_per_rad (1/C); a last slope other than\n"
         "                  1/C is series compliance, listed in the truth as implied\n"
         "                stiffness_smooth: the same keys + width (0.3): corners rounded over width*T (other structure)\n"
         "                hysteresis:loss_rad (1e-4),transition_Nm (0.05 A)\n"
         "                friction_bouc_wen:loss_rad (1e-4),transition_Nm (0.05 A),n (2): Bouc-Wen friction, the branch\n"
         "                  gap grows with amplitude (other structure; named hysteresis in the truth)\n"
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
  // The effect's size is measured where reconcile compares (the baseline's analysed rows).
  const auto first = std::lower_bound(base.time_s.begin(), base.time_s.end(), b.analysis_from_s) - base.time_s.begin();
  auto analysed_rms = [&](const Vec& diff) { return rms(diff.tail(diff.size() - first)); };
  DynamicsVariation all;
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& fx : o.effects) {
    DynamicsEffect d = dynamics_effect(fx, b);
    double k = 1.0;
    Vec diff = force(d.variation).second - f0;
    if (o.concealment > 0.0) {
      // Rescale so the effect's RMS on the meshing force is concealment x noise RMS (two secant steps).
      for (int it = 0; it < 2; ++it) {
        const double r = analysed_rms(diff);
        if (!(r > 0.0)) throw InputError("synth effect " + fx.name + " has no effect on this run");
        k *= o.concealment * out.noise_rms / r;
        diff = force(d.scaled(k)).second - f0;
      }
    }
    const DynamicsVariation v = d.scaled(k);
    if (fx.name == "mesh_stiffness_variation") { all.stiffness_ratio = v.stiffness_ratio; all.stiffness_phase_rad = v.stiffness_phase_rad; }
    if (fx.name == "damping") all.damping_Ns_per_m = v.damping_Ns_per_m;
    if (fx.name == "drag_torque") { all.drag_coulomb_Nm = v.drag_coulomb_Nm; all.drag_viscous_Nms_per_rad = v.drag_viscous_Nms_per_rad; }
    out.effect_rms.push_back({fx.name, analysed_rms(diff)});
    effects.push_back({{"name", fx.name}, {"params", d.headline(k)}, {"rms", analysed_rms(diff)}});
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

SynthOptions dynamics_proof_options(const Baseline& baseline, double noise_N, std::uint64_t seed) {
  SynthOptions o;
  o.kind = Kind::Dynamics;
  o.baseline = baseline;
  o.white_sd = noise_N;
  o.ar1_sd = noise_N;
  o.quantum = 0.2 * noise_N;
  o.speed_sd_rpm = 0.05;
  o.seed = seed;
  return o;
}

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
      cols[1][i] = -A * std::cos(2.0 * M_PI * o.cycles * i / n);  // starts at a reversal, -A
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
    nlohmann::json entry = {{"name", s.truth_name.empty() ? fx.name : s.truth_name}, {"params", s.headline(amp)},
                            {"rms", rms(contribution)}};
    if (!s.truth_name.empty()) entry["generator"] = fx.name;
    effects.push_back(entry);
    if (s.implied_series && std::abs(s.implied_series(amp)) > 0.0) {
      const double c = s.implied_series(amp);
      effects.push_back({{"name", "series_compliance"},
                         {"params", {{"compliance_rad_per_Nm", c}}},
                         {"rms", rms(Vec(c * e.torque_Nm))},
                         {"implied_by", fx.name}});
    }
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
