// `strainwave dynamics CASE.toml [--out DIR] [--clearances kinematics|approximate]`: the multibody run-up and steady
// run. Reads the case, takes the tooth-pair clearances of the basic kinematic model (kinematics/, φ₀ = 0,
// wave generator at 0) or the dynamics module's stand-in, integrates, checks against kinematics and statics, and
// writes dynamics.csv, dynamics.json and dynamics.svg (atomically).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/dynamics_job.hpp"
#include "app/fem_job.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "dynamics/analysis.hpp"
#include "dynamics/run_summary.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "io/dynamics_output.hpp"
#include "io/provenance.hpp"

namespace sw::app {
namespace {

/// The case's [dynamics] table (or its defaults) with the command line's --pairs and --rim.
DynamicsParams resolved_params(const Case& c, const std::string& pairs_option, const std::string& rim_option) {
  DynamicsParams p = c.dynamics ? *c.dynamics : DynamicsParams{};
  if (!pairs_option.empty()) p.pair_motion = pairs_option == "moving" ? PairMotion::Moving : PairMotion::Frozen;
  if (!rim_option.empty()) p.rim = rim_option == "fem" ? RimCoupling::Fem : RimCoupling::Rigid;
  return p;
}

/// dynamics.csv, dynamics.json and dynamics.svg in the staging folder `dir`; the command's wall clock (`total`) is read
/// for dynamics.json, with the case run (`resolved`: its [dynamics] as run).
void write_outputs(const std::filesystem::path& dir, const DynamicsModel& m, const DynamicsSeries& s,
                   const DynamicsSummary& r, DynamicsReportInfo& info, Stopwatch& total, const Case& resolved) {
  write_file_atomic(dir / "dynamics.csv", dynamics_csv(m, s));
  info.total_time_s = total.lap();
  write_file_atomic(dir / "dynamics.json", dynamics_json(dynamics_result(m, s, r, info), provenance_of(resolved)));
  write_file_atomic(dir / "dynamics.svg", dynamics_svg(m, s, r, info));
}

/// The strongest three lines of the total force and of the transmission error, in orders and above their floors.
void print_lines(const DynamicsSummary& r) {
  const double fm = r.theory.mesh_frequency_Hz, fg = r.generator_frequency_Hz;
  for (std::size_t i = 0; i < std::min<std::size_t>(3, r.lines.size()); ++i)
    std::printf("  force line %zu: %.2f Hz (mesh order %.3f, generator order %.2f), %.4g N, %.1f dB above the floor "
                "%.3g N\n", i + 1, r.lines[i].frequency_Hz, r.lines[i].frequency_Hz / fm, r.lines[i].frequency_Hz / fg,
                r.lines[i].amplitude_N, 20 * std::log10(r.lines[i].amplitude_N / r.noise_floor_N), r.noise_floor_N);
  for (std::size_t i = 0; i < std::min<std::size_t>(3, r.te_lines.size()); ++i)
    std::printf("  transmission-error line %zu: %.2f Hz (mesh order %.3f, generator order %.2f), %.4g µrad, %.1f dB "
                "above the floor\n", i + 1, r.te_lines[i].frequency_Hz, r.te_lines[i].frequency_Hz / fm,
                r.te_lines[i].frequency_Hz / fg, r.te_lines[i].amplitude_N * 1e6,
                20 * std::log10(r.te_lines[i].amplitude_N / r.te_noise_floor_rad));
}

/// The run's figures on stdout: speeds against kinematics, the balances, the steady window and the spectral lines.
void print_summary(const DynamicsModel& m, const DynamicsSummary& r, const DynamicsReportInfo& info,
                   const std::string& out_dir) {
  const DynamicsParams& p = m.params;
  std::printf("dynamics %s (%s, %d/%d teeth, %s): %.3g s simulated in %.3g s (real-time factor %.3g)\n",
              info.case_path.c_str(), to_string(p.configuration), m.teeth_flexspline, m.teeth_circular,
              info.clearance_source.c_str(), p.duration_s, info.simulate_time_s, p.duration_s / info.simulate_time_s);
  for (const auto& sc : r.speeds)
    std::printf("  speed %-16s %12.6f rpm (theory %12.6f, error %.2e)\n", sc.body.c_str(), sc.simulated_rpm,
                sc.theory_rpm, sc.error_rel);
  if (!m.moving)  // moving pairs: the quasi-static comparison is a test (slow run against the loaded contact)
    std::printf("  pair forces vs quasi-static: max error %.2e; ", r.max_pair_force_error_rel);
  else
    std::printf("  ");
  std::printf("torque balance %.2e; energy balance %.2e\n", r.torque_balance_error_rel, r.energy_error_rel);
  const SteadyPower& w = r.power;
  std::printf("  efficiency %.4f: output over output + the flanks' friction (mu = %g) + the generator's moment on the "
              "rim (%s); the contact's damping beside it; the lubricant's churning and seals not modelled: %.4g W in, "
              "%.4g W out, %.4g W flank friction, %.4g W generator (bearing, ring on the bore, flexspline damping), "
              "%.4g W contact damping; power balance %.2e\n",
              w.efficiency, m.friction_coefficient, info.bearing_source.c_str(), w.input_W, w.output_W, w.friction_W,
              w.bearing_W, w.dissipated_W, w.balance_error_rel);
  if (w.damping_exceeds_output)
    std::printf("  WARNING: the contact's damping dissipates %.4g W, more than the %.4g W the output delivers: the run "
                "is dominated by vibration the contact's damper (the model's idealisation of the teeth's damping) "
                "sets, so the efficiency and the loss split above describe that damper more than the drive\n",
                w.dissipated_W, w.output_W);
  std::printf("  mesh frequency %.2f Hz; strongest line %s\n", r.theory.mesh_frequency_Hz,
              r.lines.empty() ? "none" : (std::to_string(r.lines[0].frequency_Hz) + " Hz").c_str());
  std::printf("  steady window: mesh deflection %.4g to %.4g mrad, largest flank force %.4g N, %g to %g flanks in "
              "contact, transmission error %.4g µrad peak to peak\n", r.deflection_min_rad * 1e3, r.deflection_max_rad * 1e3,
              r.max_pair_force_N, r.flanks_in_contact_min, r.flanks_in_contact_max, r.te_peak_to_peak_rad * 1e6);
  print_lines(r);
  std::printf("  wrote %s/dynamics.{csv,json,svg}\n", out_dir.c_str());
}

void run_dynamics(const std::string& case_path, const std::string& out_dir, const std::string& clearances,
                  const std::string& fem_result, const std::string& interference, const std::string& pairs_option,
                  const std::string& rim_option) {
  Stopwatch total;
  Case c = load_case(case_path);
  if (!c.gear) throw InputError(case_path + ": [gear] is missing; the dynamics needs the tooth numbers and module");
  const DynamicsParams p = resolved_params(c, pairs_option, rim_option);
  OutputSet outputs(out_dir.empty() ? default_out_dir(c) : std::filesystem::path(out_dir),
                    {"dynamics.csv", "dynamics.json", "dynamics.svg"});
  progress(case_headline(c) + "\n[dynamics] as run:\n" + keys_toml(p, dynamics_keys()));
  DynamicsModelOptions o;
  o.clearances = clearances;
  o.interference = interference;
  o.fem_result = fem_result;
  const DynamicsJobModel job = dynamics_model(c, p, o, outputs);
  const DynamicsModel& m = job.model;
  progress("dynamics: " + std::string(to_string(p.configuration)) + ", " + std::to_string(m.pairs.size()) +
           " tooth pairs (" + job.source + "), " + std::to_string(std::lround(p.duration_s / p.output_step_s)) +
           " output steps");
  Stopwatch sim;
  const DynamicsSeries s = simulate(m);
  DynamicsReportInfo info;
  info.case_path = case_path;
  info.clearance_source = job.source;
  info.bearing_source = job.bearing_source;
  info.simulate_time_s = sim.lap();
  progress("dynamics: integrated " + std::to_string(p.duration_s) + " s in " + std::to_string(info.simulate_time_s) +
           " s (" + std::to_string(s.stats.steps) + " steps)");
  const DynamicsSummary r = summarize(m, s);
  Case resolved = c;  // --pairs and --rim as run
  resolved.dynamics = p;
  write_resolved_case(resolved, outputs);
  write_outputs(outputs.staging(), m, s, r, info, total, resolved);
  outputs.commit();
  print_summary(m, r, info, outputs.dir().string());
}

}  // namespace

void add_dynamics_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("dynamics", "multibody run-up and steady run with tooth-pair contact");
  auto case_path = std::make_shared<std::string>();
  auto out = std::make_shared<std::string>();
  auto clearances = std::make_shared<std::string>("kinematics");
  cmd->add_option("case", *case_path, "case file (TOML) with [gear] and an optional [dynamics] table")->required();
  cmd->add_option("--out", *out, "output directory (default out/<case stem>/)");
  cmd->add_option("--clearances", *clearances, "tooth-pair clearances: kinematics (backlash module) | approximate")
      ->check(CLI::IsMember({"kinematics", "approximate"}));
  auto fem = std::make_shared<std::string>();
  cmd->add_option("--fem", *fem, "FEM result (DIR/result.json): split the flexspline into rim and flange joined by "
                                 "1/C_tau (overrides dynamics.flexspline_compliance_rad_per_Nm)");
  auto interference = std::make_shared<std::string>("preload");
  cmd->add_option("--interference", *interference,
                  "flanks with negative clearance at rest: preload (keep, default) | clip (clearance 0) | drop (pair)")
      ->check(CLI::IsMember({"preload", "clip", "drop"}));
  auto pairs = std::make_shared<std::string>();
  cmd->add_option("--pairs", *pairs, "tooth pairs: moving (travel through the mesh) | frozen (generator angle 0); "
                                     "overrides dynamics.pairs")->check(CLI::IsMember({"moving", "frozen"}));
  auto rim = std::make_shared<std::string>();
  cmd->add_option("--rim", *rim, "moving pairs joined through the flexspline body (fem) or independent (rigid); "
                                 "overrides dynamics.rim")->check(CLI::IsMember({"fem", "rigid"}));
  cmd->callback([=] { run_dynamics(*case_path, *out, *clearances, *fem, *interference, *pairs, *rim); });
}

}  // namespace sw::app
