// `strainwave backlash CASE.toml [--fem DIR/result.json] [--phi0 RAD] [--curve generator|fem] [--out DIR]`:
// backlash over a wave-generator revolution, basic (φ₀ = 0) and load-compensated (φ₀ from the FEM or --phi0).
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <numbers>

#include <CLI/CLI.hpp>

#include "app/backlash_job.hpp"
#include "app/commands.hpp"
#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "io/atomic_file.hpp"
#include "contact/circular_spline.hpp"
#include "io/case.hpp"
#include "io/drive_drawing.hpp"
#include "io/fem_output.hpp"
#include "io/provenance.hpp"

namespace sw::app {

namespace fs = std::filesystem;

namespace {


/// φ₀ and where it came from: --phi0, else C_τ·T of the FEM's result.json, else its φ₀, else none.
void set_phi0(BacklashReport& r, const Case& c, const BacklashJobOptions& o, const OutputSet& out) {
  std::optional<FemCompensation> fem;
  if (o.fem_result) fem = read_fem_compensation(out.read_path(*o.fem_result));
  if (o.phi0_rad) {
    r.phi0_rad = *o.phi0_rad;
    r.phi0_source = "--phi0";
  } else if (fem && fem->compliance_rad_per_Nm && c.load.torque_Nm != 0) {
    r.phi0_rad = *fem->compliance_rad_per_Nm * c.load.torque_Nm;
    r.phi0_source = "C_tau x torque from " + o.fem_result->string();
  } else if (fem) {
    r.phi0_rad = fem->phi0_rad;
    r.phi0_source = "phi0_rad from " + o.fem_result->string();
  } else {
    r.phi0_source = "none (no --fem, no --phi0): compensated = basic";
  }
  if (fem) r.compliance_rad_per_Nm = fem->compliance_rad_per_Nm;
}

/// The deformed neutral curve: the FEM's (neutral_curve.csv beside result.json) or the generator model's.
NeutralCurve backlash_curve(const Case& c, const BacklashJobOptions& o, const OutputSet& out, double rm, double w0) {
  if (!o.fem_curve) return generator_neutral_curve(rm, w0, *c.wave_generator);
  if (!o.fem_result) throw InputError("--curve fem needs --fem DIR/result.json (neutral_curve.csv is read beside it)");
  const fs::path csv = o.fem_result->parent_path() / "neutral_curve.csv";
  const NeutralCurveSamples s = read_neutral_curve_csv(out.read_path(csv));
  return fit_neutral_curve(rm, s.phi_rad, s.w_wg_m, s.v_wg_m, s.mu_wg_rad,
                           "FEM neutral curve " + csv.string() + " (generator alone)");
}

/// The paper's table, every pair position over a turn and a revolution of the generator, basic and compensated.
void sweep(BacklashReport& r, const BacklashModel& m, int revolution_steps) {
  Stopwatch clock;
  for (double pos : {0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0}) {
    const double phi = (90.0 - pos) * kPi / 180.0;
    r.table.push_back({pos, pair_clearance(m, phi, 0.0), pair_clearance(m, phi, r.phi0_rad)});
  }
  for (int i = -719; i <= 720; ++i) {  // 0.25° over (−180°, 180°]
    const double phi = i * 0.25 * kPi / 180.0;
    r.positions_basic.push_back(pair_clearance(m, phi, 0.0));
    r.positions_compensated.push_back(pair_clearance(m, phi, r.phi0_rad));
  }
  const double t_positions = clock.lap();
  r.revolution_basic = sweep_revolution(m, 0.0, revolution_steps);
  r.revolution_compensated = sweep_revolution(m, r.phi0_rad, revolution_steps);
  const double t_rev = clock.lap();
  progress("backlash: 1440 pair positions in " + std::to_string(t_positions) + " s; revolution (" +
           std::to_string(revolution_steps) + " steps x 2) in " + std::to_string(t_rev) + " s");
}

/// The radii of the drive's drawing from the case: the circular spline's outside by its design rule when the case has
/// no [circular_spline].
DriveOutline drive_outline(const Case& c) {
  DriveOutline o;
  o.bore_radius_m = c.flexspline.inner_radius_m;
  o.circular_spline_outer_radius_m = c.circular_spline ? c.circular_spline->outer_radius_m
                                                       : default_circular_spline(*c.gear, c.flexspline.rim_width_m).outer_radius_m;
  o.bearing = c.wave_generator->bearing;
  o.generator = model_name(c.wave_generator->model);
  return o;
}

/// The geometry check, the play over a revolution and the paper's table, on stdout.
void print_backlash_summary(const Case& c, const BacklashReport& r) {
  std::printf("backlash %s: %s\n", c.path.c_str(), r.curve_source.c_str());
  std::printf("%s", geometry_check_text(r.geometry, r.module_m).c_str());
  const auto& rb = r.revolution_basic;
  std::printf("  geometric angular play of the output over a revolution%s: %.3f .. %.3f arcmin (teeth and rim rigid; "
              "not the catalog's lost motion, which includes elastic twist)\n", at_face_centre(c).c_str(),
              rb.angular_play_min_rad * kArcmin, rb.angular_play_max_rad * kArcmin);
  int near_min = 1 << 30, near_max = 0;
  for (const MeshState& st : rb.period) {
    near_min = std::min({near_min, st.near_ccw[1], st.near_cw[1]});
    near_max = std::max({near_max, st.near_ccw[1], st.near_cw[1]});
  }
  std::printf("  pairs in mesh %d .. %d; pairs within 5 um of contact on one flank: %d .. %d\n", rb.engaged_pairs_min,
              rb.engaged_pairs_max, near_min, near_max);
  std::printf("  the paper's table (rigid teeth, rim turned rigidly by phi0 = %.6e rad, %s):\n", r.phi0_rad,
              r.phi0_source.c_str());
  std::printf("  %-10s %-12s %-12s %-12s %s\n", "psi(deg)", "j/m basic", "j/m comp", "play(um)", "j_t1/j_t2 basic -> comp (um)");
  for (const auto& row : r.table) {
    if (!row.basic.engaged) {
      std::printf("  %-10.0f not in mesh (teeth face tip to tip: no backlash)\n", row.position_deg);
      continue;
    }
    const double b = row.basic.backlash_m() / r.module_m, cc = row.compensated.backlash_m() / r.module_m;
    std::printf("  %-10.0f %-12.5f %-12.5f %-12.3f %.3f/%.3f -> %.3f/%.3f%s\n", row.position_deg, b, cc,
                row.basic.total_play_m() * 1e6, row.basic.ccw.clearance_m * 1e6, row.basic.cw.clearance_m * 1e6,
                row.compensated.ccw.clearance_m * 1e6, row.compensated.cw.clearance_m * 1e6,
                b < 0 ? "  (interference)" : cc <= 0 ? "  (loaded flank in contact)" : "");
  }
  std::printf("  min over pairs in mesh and a revolution: basic %.5f mm (j/m %.5f), compensated %.5f mm (j/m %.5f)\n",
              rb.min_m * 1e3, rb.min_m / r.module_m, r.revolution_compensated.min_m * 1e3,
              r.revolution_compensated.min_m / r.module_m);
}

}  // namespace

BacklashReport run_backlash_job(const Case& c, const BacklashJobOptions& o, OutputSet& out) {
  if (!c.gear) throw InputError(c.path + ": [gear] is missing; the backlash model needs the tooth data");
  if (!c.wave_generator || !c.wave_generator->radial_deformation_m)
    throw InputError(c.path + ": wave_generator.radial_deformation_mm is missing; the backlash model needs w0");
  const double rm = rim_mean_radius(c.flexspline);
  const double w0 = *c.wave_generator->radial_deformation_m;

  BacklashReport r;
  r.case_path = c.path;
  r.provenance = provenance_of(c);
  r.module_m = c.gear->module_m;
  r.torque_Nm = c.load.torque_Nm;
  out.own(kBacklashJobFiles);
  set_phi0(r, c, o, out);
  const NeutralCurve curve = backlash_curve(c, o, out, rm, w0);
  r.curve_source = curve.source;
  const BacklashModel m = make_backlash_model(*c.gear, curve);
  progress("backlash: " + curve.source + ", r_m = " + std::to_string(rm * 1e3) + " mm, phi0 = " +
           std::to_string(r.phi0_rad) + " rad");

  Stopwatch clock;
  r.geometry = check_geometry(*c.gear, curve);
  progress("backlash: geometry check in " + std::to_string(clock.lap()) + " s");
  sweep(r, m, o.revolution_steps);

  write_file_atomic(out.staging() / "backlash.json", backlash_json(backlash_result(r)));
  write_file_atomic(out.staging() / "backlash.csv", backlash_csv(r));
  write_file_atomic(out.staging() / "backlash.svg", backlash_svg(r));
  write_profiles_vtp(out.staging() / "profiles.vtp", m, r.phi0_rad);
  write_file_atomic(out.staging() / "drive.svg", drive_svg(m, drive_outline(c), c.path));
  print_backlash_summary(c, r);
  return r;
}

void add_backlash_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("backlash", "backlash over a wave-generator cycle, basic and load-compensated");
  static std::string case_path, out, fem, curve = "generator";
  static double phi0 = 0;
  static int steps = 3600;
  cmd->add_option("case", case_path, "case file (TOML)")->required();
  cmd->add_option("--fem", fem, "FEM result (DIR/result.json): phi0 = C_tau x torque, or its phi0_rad");
  auto* phi0_opt = cmd->add_option("--phi0", phi0, "flexspline wind-up under load, rad (overrides --fem)");
  cmd->add_option("--curve", curve, "deformed neutral curve: generator (case's model) or fem (neutral_curve.csv)")
      ->check(CLI::IsMember({"generator", "fem"}));
  cmd->add_option("--steps", steps, "wave-generator steps per revolution")->check(CLI::Range(1, 1000000));
  cmd->add_option("--out", out, "output directory (default out/<case stem>/)");
  cmd->callback([phi0_opt] {
    const Case c = load_case(case_path);
    progress(case_headline(c));
    BacklashJobOptions o;
    if (!fem.empty()) o.fem_result = fem;
    if (phi0_opt->count() > 0) o.phi0_rad = phi0;
    o.fem_curve = curve == "fem";
    o.revolution_steps = steps;
    OutputSet outputs(out.empty() ? default_out_dir(c) : fs::path(out));
    write_resolved_case(c, outputs);
    run_backlash_job(c, o, outputs);
    outputs.commit();
    std::printf("  wrote %s\n", outputs.dir().string().c_str());
  });
}

}  // namespace sw::app
