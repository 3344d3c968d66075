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
#include "app/contact_job.hpp"
#include "app/fem_job.hpp"
#include "dynamics/moving_mesh_build.hpp"
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

/// The moving mesh of the case: a rigid rim on the case's generator curve, or the rim coupled through the FEM's body.
std::shared_ptr<const MovingMesh> moving_mesh(const Case& c, const DynamicsParams& p, const std::string& out_dir) {
  const ToothCompliance teeth =
      p.pair_stiffness == PairStiffness::Teeth ? series_parts(c).tooth_pair_m_per_N : ToothCompliance{};
  if (p.rim == RimCoupling::Rigid) {
    const double rm = rim_mean_radius(c.flexspline), w0 = case_radial_deformation_m(c);
    const NeutralCurve curve =
        c.wave_generator ? generator_neutral_curve(rm, w0, *c.wave_generator) : cam_neutral_curve(rm, w0);
    return std::make_shared<MovingMesh>(rigid_rim_mesh(*c.gear, curve, teeth, 64));
  }
  check_contact_case(c);
  FemJobOptions o;
  o.write_vtk = false;
  const FemJobResult fem = run_fem_job(c, out_dir, o);
  if (!fem.mesh || !fem.system) throw InputError(c.path + ": rim = \"fem\" needs the TET10 solver (solver.method)");
  const double rated = c.load.rated_torque_Nm.value_or(c.load.torque_Nm);
  return std::make_shared<MovingMesh>(
      fem_coupled_mesh(c, *fem.mesh, *fem.system, fem.solution, teeth, rated, p.compliance_phases,
                       std::max(1, 64 / p.compliance_phases)));  // the flank table every pitch/64: see test_moving
}

void run_dynamics(const std::string& case_path, std::string out_dir, const std::string& clearances,
                  const std::string& fem_result, const std::string& interference, const std::string& pairs_option,
                  const std::string& rim_option) {
  Stopwatch total;
  const Case c = load_case(case_path);
  if (!c.gear) throw InputError(case_path + ": [gear] is missing; the dynamics needs the tooth numbers and module");
  DynamicsParams p = c.dynamics ? *c.dynamics : DynamicsParams{};
  if (!pairs_option.empty()) p.pair_motion = pairs_option == "moving" ? PairMotion::Moving : PairMotion::Frozen;
  if (!rim_option.empty()) p.rim = rim_option == "fem" ? RimCoupling::Fem : RimCoupling::Rigid;
  const bool moving = p.pair_motion == PairMotion::Moving;
  if (moving) validate_moving(p, case_path);
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
  DynamicsModel m = make_model(*c.gear, c.flexspline, c.flexspline.shape == FlexsplineShape::Cup, c.material, p,
                               std::move(pairs), case_path);
  if (moving) {
    if (out_dir.empty()) out_dir = default_out_dir(c).string();
    m.moving = moving_mesh(c, p, out_dir);
    m.pairs.clear();
    source = m.moving->source;
  }
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
  std::printf("dynamics %s (%s, %d/%d teeth, %s): %.3g s simulated in %.3g s (real-time factor %.3g)\n",
              case_path.c_str(), to_string(p.configuration), m.teeth_flexspline, m.teeth_circular, source.c_str(),
              p.duration_s, info.simulate_time_s, p.duration_s / info.simulate_time_s);
  for (const auto& sc : r.speeds)
    std::printf("  speed %-16s %12.6f rpm (theory %12.6f, error %.2e)\n", sc.body.c_str(), sc.simulated_rpm,
                sc.theory_rpm, sc.error_rel);
  std::printf("  pair forces vs quasi-static: max error %.2e; torque balance %.2e; energy balance %.2e\n",
              r.max_pair_force_error_rel, r.torque_balance_error_rel, r.energy_error_rel);
  std::printf("  mesh frequency %.2f Hz; strongest line %s\n", r.theory.mesh_frequency_Hz,
              r.lines.empty() ? "none" : (std::to_string(r.lines[0].frequency_Hz) + " Hz").c_str());
  std::printf("  steady window: mesh deflection %.4g to %.4g mrad, largest flank force %.4g N, %g to %g flanks in contact, "
              "transmission error %.4g µrad peak to peak\n", r.deflection_min_rad * 1e3, r.deflection_max_rad * 1e3,
              r.max_pair_force_N, r.flanks_in_contact_min, r.flanks_in_contact_max, r.te_peak_to_peak_rad * 1e6);
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
  auto pairs = std::make_shared<std::string>();
  cmd->add_option("--pairs", *pairs, "tooth pairs: moving (travel through the mesh) | frozen (generator angle 0); "
                                     "overrides dynamics.pairs")->check(CLI::IsMember({"moving", "frozen"}));
  auto rim = std::make_shared<std::string>();
  cmd->add_option("--rim", *rim, "moving pairs joined through the flexspline body (fem) or independent (rigid); "
                                 "overrides dynamics.rim")->check(CLI::IsMember({"fem", "rigid"}));
  cmd->callback([=] { run_dynamics(*case_path, *out, *clearances, *fem, *interference, *pairs, *rim); });
}

}  // namespace sw::app
