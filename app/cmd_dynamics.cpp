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
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "io/fem_output.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "dynamics/analysis.hpp"
#include "dynamics/report.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "dynamics/kinematic_pairs.hpp"
#include "kinematics/backlash.hpp"
#include "kinematics/neutral_curve.hpp"

namespace sw::app {
namespace {

/// C_τ from `strainwave fem`'s result.json (key compliance_rad_per_Nm).
double compliance_from_fem(const std::string& path) { return read_fem_compliance(path); }

/// What to do with a flank whose clearance at rest is negative (interference in the basic kinematic model):
/// "preload" keeps it (contact force at rest), "clip" sets the clearance to 0, "drop" removes the pair.
std::vector<ToothPair> treat_interference(std::vector<ToothPair> pairs, const std::string& policy) {
  if (policy == "preload") return pairs;
  std::vector<ToothPair> out;
  for (ToothPair t : pairs) {
    const bool interferes = t.clearance_drive_m < 0 || t.clearance_coast_m < 0;
    if (policy == "drop" && interferes) continue;
    t.clearance_drive_m = std::max(0.0, t.clearance_drive_m);
    t.clearance_coast_m = std::max(0.0, t.clearance_coast_m);
    out.push_back(t);
  }
  return out;
}

void run_dynamics(const std::string& case_path, std::string out_dir, const std::string& clearances,
                  const std::string& fem_result, const std::string& interference) {
  Stopwatch total;
  const Case c = load_case(case_path);
  if (!c.gear) throw InputError(case_path + ": [gear] is missing; the dynamics needs the tooth numbers and module");
  DynamicsParams p = c.dynamics ? *c.dynamics : DynamicsParams{};
  if (!fem_result.empty()) {
    p.flexspline_compliance_rad_per_Nm = compliance_from_fem(fem_result);
    progress("dynamics: flexspline rim and flange joined by 1/C_tau, C_tau = " +
             std::to_string(p.flexspline_compliance_rad_per_Nm) + " rad/(N m) from " + fem_result);
  }
  if (out_dir.empty()) out_dir = default_out_dir(c).string();
  progress("case:\n" + describe(p));
  std::vector<ToothPair> pairs;
  std::string source;
  if (clearances == "kinematics") {
    pairs = pairs_from_kinematics(c);
    source = "kinematics (basic model, wave generator at 0, phi0 = 0), " + std::to_string(pairs.size()) + " engaged pairs";
  } else {
    pairs = approximate_tooth_pairs(*c.gear, case_radial_deformation_m(c), c.load.engagement_half_angle_rad,
                                    p.base_clearance_m);
    source = "approximate stand-in (w0(1 - cos 2phi) sin(alpha) within +-engagement_half_angle), " +
             std::to_string(pairs.size()) + " pairs";
  }
  int interfering = 0;
  for (const auto& tp : pairs) interfering += (tp.clearance_drive_m < 0 || tp.clearance_coast_m < 0) ? 1 : 0;
  if (interfering > 0) {
    progress("dynamics: " + std::to_string(interfering) + " pairs have negative clearance (interference) at rest: " +
             (interference == "preload" ? "carried as contact preload"
              : interference == "clip"  ? "clearance set to 0"
                                        : "pairs left out"));
    pairs = treat_interference(std::move(pairs), interference);
    source += ", interference: " + interference;
  }
  const DynamicsModel m = make_model(*c.gear, c.flexspline, c.flexspline.shape == FlexsplineShape::Cup, c.material, p,
                                     std::move(pairs), case_path);
  progress("dynamics: " + std::string(to_string(p.configuration)) + ", " + std::to_string(m.pairs.size()) +
           " tooth pairs (" + source + "), " + std::to_string(std::lround(p.duration_s / p.output_step_s)) +
           " output steps");
  Stopwatch sim;
  const DynamicsSeries s = simulate(m);
  DynamicsReportInfo info;
  info.case_path = case_path;
  info.clearance_source = source;
  info.simulate_time_s = sim.lap();
  progress("dynamics: integrated " + std::to_string(p.duration_s) + " s in " + std::to_string(info.simulate_time_s) +
           " s (" + std::to_string(s.stats.steps) + " steps)");
  const DynamicsSummary r = summarize(m, s);
  const std::filesystem::path dir(out_dir);
  write_file_atomic(dir / "dynamics.csv", dynamics_csv(m, s));
  info.total_time_s = total.lap();
  write_file_atomic(dir / "dynamics.json", dynamics_json(m, s, r, info));
  write_file_atomic(dir / "dynamics.svg", dynamics_svg(m, s, r, info));
  std::printf("dynamics %s (%s, %d/%d teeth, %zu pairs): %.3g s simulated in %.3g s (real-time factor %.3g)\n",
              case_path.c_str(), to_string(p.configuration), m.teeth_flexspline, m.teeth_circular, m.pairs.size(),
              p.duration_s, info.simulate_time_s, p.duration_s / info.simulate_time_s);
  for (const auto& sc : r.speeds)
    std::printf("  speed %-16s %12.6f rpm (theory %12.6f, error %.2e)\n", sc.body.c_str(), sc.simulated_rpm,
                sc.theory_rpm, sc.error_rel);
  std::printf("  pair forces vs quasi-static: max error %.2e; torque balance %.2e; energy balance %.2e\n",
              r.max_pair_force_error_rel, r.torque_balance_error_rel, r.energy_error_rel);
  std::printf("  mesh frequency %.2f Hz; strongest line %s\n", r.theory.mesh_frequency_Hz,
              r.lines.empty() ? "none" : (std::to_string(r.lines[0].frequency_Hz) + " Hz").c_str());
  std::printf("  wrote %s/dynamics.{csv,json,svg}\n", out_dir.c_str());
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
  cmd->callback([=] { run_dynamics(*case_path, *out, *clearances, *fem, *interference); });
}

}  // namespace sw::app
