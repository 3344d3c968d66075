// `strainwave synth --kind K --out FILE.csv [--effect NAME[:k=v,...]]... [noise flags]`: a synthetic recording of a
// kind from its baseline plus hidden effects, white + AR(1) noise, encoder quantisation and sensor gain error, and a
// truth file FILE.truth.json beside it (for proofs and demos).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/reconcile_baseline.hpp"
#include "common/error.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "reconcile/synth.hpp"

namespace sw::app {
namespace {

struct SynthArgs {
  std::string kind = "torsion", out, case_path, fem;
  double compliance = 0.0;
  int teeth_flexspline = 0, teeth_circular = 0;
  std::vector<std::string> effects;
  std::string effect_list;
  std::vector<std::string> meta;
  reconcile::SynthOptions o;
  double cycles = 4.0, torque_Nm = 44.1, period_s = 0.01;
  int levels = 3;
  double white = -1, ar1 = -1, quantum = -1;  // < 0: the kind's default
};

/// The recording's rows of a kind from the command line. Transmission: --cycles output revolutions, 2 unless given
/// other than 4. Dynamics: 0.05 rpm white noise on both speeds.
reconcile::SynthRows rows_of(reconcile::Kind kind, const SynthArgs& a) {
  using reconcile::Kind;
  switch (kind) {
    case Kind::Torsion: return reconcile::TorsionRows{a.cycles, a.torque_Nm, a.period_s};
    case Kind::Transmission: return reconcile::TransmissionRows{a.cycles == 4.0 ? 2.0 : a.cycles, a.period_s};
    case Kind::Backlash: return reconcile::BacklashRows{a.torque_Nm, a.levels};
    case Kind::Dynamics: return reconcile::DynamicsRows{0.05};
  }
  throw std::logic_error("rows_of: unknown kind");
}

/// Per-kind noise defaults (response units): white and AR(1) noise of one sd, and an encoder-like resolution.
struct NoiseDefaults {
  double sd, quantum;
};
NoiseDefaults noise_defaults(reconcile::Kind kind) {
  using reconcile::Kind;
  switch (kind) {
    case Kind::Torsion: return {1e-6, 5e-7};
    case Kind::Transmission: return {2e-6, 1e-6};
    case Kind::Backlash: return {0.2, 0.1};
    case Kind::Dynamics: return {5.0, 1.0};
  }
  throw std::logic_error("noise_defaults: unknown kind");
}

void run_synth(SynthArgs a) {
  using reconcile::Kind;
  const std::optional<Kind> parsed = reconcile::kind_from_name(a.kind);
  if (!parsed) throw InputError("--kind = '" + a.kind + "'; expected torsion, transmission, backlash or dynamics");
  const Kind kind = *parsed;
  BaselineSources src;
  if (!a.case_path.empty()) src.case_file = load_case(a.case_path);
  src.fem_result = a.fem;
  if (a.compliance > 0.0) src.compliance = a.compliance;
  else if (a.fem.empty() && kind == Kind::Torsion) src.compliance = 5e-5;  // demo default, stated in --help
  reconcile::Recording meta;  // teeth given on the command line act as metadata
  if (a.teeth_flexspline > 0) meta.metadata.push_back({"teeth_flexspline", std::to_string(a.teeth_flexspline)});
  if (a.teeth_circular > 0) meta.metadata.push_back({"teeth_circular", std::to_string(a.teeth_circular)});
  if (kind == Kind::Transmission && !src.case_file && a.teeth_flexspline == 0) {
    meta.metadata = {{"teeth_flexspline", "190"}, {"teeth_circular", "192"}};
  }
  src.recording = &meta;
  std::vector<std::string> notes;
  a.o.baseline = make_baseline(kind, src, notes);
  a.o.rows = rows_of(kind, a);
  const NoiseDefaults noise = noise_defaults(kind);
  a.o.white_sd = a.white >= 0 ? a.white : noise.sd;
  a.o.ar1_sd = a.ar1 >= 0 ? a.ar1 : noise.sd;
  a.o.quantum = a.quantum >= 0 ? a.quantum : noise.quantum;
  for (const auto& e : a.effects) a.o.effects.push_back(reconcile::parse_synth_effect(e));
  if (!a.effect_list.empty())
    for (auto& e : reconcile::parse_synth_effects(a.effect_list)) a.o.effects.push_back(std::move(e));
  const reconcile::SynthResult r = reconcile::synthesize(a.o);
  if (a.out.empty()) a.out = "out/synth_" + a.kind + ".csv";
  std::filesystem::path path(a.out);
  std::filesystem::path truth = path;
  truth.replace_extension(".truth.json");
  reconcile::Recording rec = r.recording;
  for (const auto& m : a.meta) {
    const auto colon = m.find('=');
    if (colon == std::string::npos || colon == 0)
      throw InputError("--meta = '" + m + "'; expected key=value (a metadata line '# key: value')");
    rec.metadata.push_back({m.substr(0, colon), m.substr(colon + 1)});
  }
  rec.metadata.push_back({"truth", truth.filename().string()});
  write_file_atomic(truth, r.truth_json);
  write_file_atomic(path, reconcile::format_recording(rec));
  std::printf("synth %s: %zu samples, noise RMS %.3g", a.kind.c_str(), r.recording.rows(), r.noise_rms);
  for (const auto& [name, rms] : r.effect_rms) std::printf(", %s RMS %.3g", name.c_str(), rms);
  std::printf("\n  wrote %s and %s\n", path.string().c_str(), truth.string().c_str());
}

}  // namespace

void add_synth_command(CLI::App& app) {
  auto a = std::make_shared<SynthArgs>();
  auto* cmd = app.add_subcommand(
      "synth", "write a synthetic recording (baseline + hidden effects + noise) and its truth file FILE.truth.json");
  cmd->footer(reconcile::synth_effect_help() +
              "\nNoise defaults (response units): torsion white 1e-6 rad, AR(1) 1e-6 rad, quantum 5e-7 rad;\n"
              "transmission 2e-6 / 2e-6 / 1e-6 rad; backlash 0.2 / 0.2 / 0.1 um. Torsion without --fem/--compliance\n"
              "uses C_tau = 5e-5 rad/(N*m); transmission without a case uses z_f = 190, z_c = 192; backlash needs --case.\n"
              "dynamics (needs --case with [gear] and [dynamics]): the case's run with the hidden effects on its own time\n"
              "grid; noise on mesh_force_N white 5 N, AR(1) 5 N, quantum 1 N; speeds white 0.05 rpm.");
  cmd->add_option("--kind", a->kind, "torsion | transmission | backlash | dynamics")->capture_default_str();
  cmd->add_option("--out", a->out, "recording path (default out/synth_<kind>.csv); truth beside it");
  cmd->add_option("--case", a->case_path, "case file for the baseline (gear, flexspline)")->check(CLI::ExistingFile);
  cmd->add_option("--fem", a->fem, "FEM result.json (torsion C_tau)");
  cmd->add_option("--compliance", a->compliance, "torsion C_tau, rad/(N*m)")->check(CLI::PositiveNumber);
  cmd->add_option("--teeth-flexspline", a->teeth_flexspline, "transmission z_f without a case");
  cmd->add_option("--teeth-circular", a->teeth_circular, "transmission z_c without a case");
  cmd->add_option("--effect", a->effects, "hidden effect NAME[:key=value,...] (repeatable; see below)");
  cmd->add_option("--effects", a->effect_list,
                  "several hidden effects at once: a,b:key=value,key=value,c (an item with '=' and no ':' belongs "
                  "to the effect before it)");
  cmd->add_option("--meta", a->meta, "extra metadata key=value written into the recording (repeatable)");
  cmd->add_option("--concealment", a->o.concealment,
                  "rescale each effect so its RMS = this times the noise RMS (0: use the given amplitudes)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--samples", a->o.samples, "rows")->capture_default_str();
  cmd->add_option("--period", a->period_s, "time_s step, s (torsion, transmission)")->capture_default_str();
  cmd->add_option("--cycles", a->cycles, "torsion: torque cycles; transmission: output revolutions (default 2)")
      ->capture_default_str();
  cmd->add_option("--torque", a->torque_Nm, "torsion amplitude / backlash top level, N*m")->capture_default_str();
  cmd->add_option("--levels", a->levels, "backlash: torque levels 0..--torque")->capture_default_str();
  cmd->add_option("--white", a->white, "white noise sd (response units)");
  cmd->add_option("--ar1", a->ar1, "AR(1) noise: process sd (response units)");
  cmd->add_option("--ar1-phi", a->o.ar1_phi, "AR(1) coefficient")->capture_default_str();
  cmd->add_option("--quantum", a->quantum, "encoder resolution (response units; 0: none)");
  cmd->add_option("--gain-error", a->o.gain_error, "sensor gain error: recorded = (1 + g) * true")->capture_default_str();
  cmd->add_option("--seed", a->o.seed, "random seed")->capture_default_str();
  cmd->callback([a] { run_synth(*a); });
}

}  // namespace sw::app
