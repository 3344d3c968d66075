// `strainwave datasheet CASE.toml`: the designed drive's catalog sheet from its geometry. The flexspline on the harmonic
// solver, the loaded contact on it, then each limit from the stage that owns it; the published figures beside where
// the case names a catalog size.
#include <cmath>
#include <cstdio>
#include <numbers>
#include <filesystem>
#include <limits>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/contact_job.hpp"
#include "app/fem_job.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "contact/harmonic_body.hpp"
#include "datasheet/datasheet.hpp"
#include "datasheet/limits.hpp"
#include "fem/fourier_buckling.hpp"
#include "fem/infinite_life.hpp"
#include "gear/mesh_friction.hpp"
#include "io/atomic_file.hpp"
#include "kinematics/neutral_curve.hpp"
#include "io/datasheet_output.hpp"
#include "io/vtu.hpp"

namespace sw::app {
namespace {

// The catalog's rating speed of the generator bearing's life: 2,000 rpm input (shared/reference).
constexpr double kInputSpeed_rpm = 2000;

// How far past rated torque the ratcheting torque is looked for: a search bound, not a physical parameter (the
// catalog's ratcheting torques are 5 to 15 times the rated; the sheet says "above" when it is not reached).
constexpr double kRatchetingCeilingPerRated = 100;

inline const std::vector<std::string> kDatasheetFiles = {"datasheet.json", "datasheet.html", "buckling.vtu"};

/// The harmonic solution of the case with the bands the loaded contact reads.
FemJobResult solve_flexspline(const Case& c, double max_memory_gb) {
  progress("datasheet: the flexspline on harmonics 0.." + std::to_string(c.solver.harmonics));
  double section_s = 0;
  FourierSolution fourier = solve_fourier_model(c, max_memory_gb, section_s);
  FemJobResult job;
  job.solution = std::move(fourier.figures);
  job.harmonic = std::make_shared<const FourierSolution>(std::move(fourier));
  return job;
}

/// Where the rated torque comes from, in words.
std::string rated_torque_origin(const Case& c) {
  if (c.load.rated_torque_Nm) return "[load] rated_torque_Nm";
  return "[load] torque_Nm (the case gives no rated_torque_Nm)";
}

/// The flexspline's first yield (fem/infinite_life.hpp), searched up to 100 × rated, or why not.
std::optional<FirstYield> first_yield(const Case& c, const FourierSolution& s, double rated_Nm, std::string& why) {
  if (!c.material.yield_strength_Pa) {
    why = "not computed: the case gives no [material] yield_strength_MPa";
    return std::nullopt;
  }
  progress("datasheet: the flexspline's first yield over a generator revolution");
  return first_yield_torque(s, flexspline_model(c), 100 * rated_Nm);
}

/// The torque for infinite life, searched up to 20 × rated (beyond it the sheet says so).
std::optional<InfiniteLife> infinite_life(const Case& c, const FourierSolution& s, double rated_Nm, std::string& why) {
  if (!c.material.fatigue_limit_Pa) {
    why = "not computed: the case gives no [material] fatigue_limit_MPa and ultimate_strength_MPa";
    return std::nullopt;
  }
  progress("datasheet: the flexspline's fatigue over a generator revolution");
  return infinite_life_torque(s, flexspline_model(c), 20 * rated_Nm);
}

/// Sectors of the buckling mode's VTU grid (as the fem job's harmonic grid: the series exact at its nodes).
constexpr int kModeGridSectors = 32;

/// The flexspline's linear buckling under the torque's prestress, harmonic by harmonic; its mode as buckling.vtu.
BucklingFigure buckling(const Case& c, const FourierSolution& s, const std::filesystem::path& staging) {
  progress("datasheet: the flexspline's buckling under the torque, harmonic by harmonic");
  const BucklingResult b = torsion_buckling_fourier(flexspline_model(c), s);
  const TetMesh grid = fourier::revolve_section(s.section, kModeGridSectors);
  const Eigen::VectorXd u = fourier::revolved_displacement(s.section, b.mode, kModeGridSectors);
  write_vtu(staging / "buckling.vtu", grid,
            {{"mode", Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(u.data(), u.size() / 3, 3)}});
  BucklingFigure f;
  f.torque_Nm = b.load_factor;  // the prestress is the torque case's at T = 1 N·m
  f.harmonic = b.n;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "elastic linear buckling of the flexspline under the torque's shear taken uniform round the body (the "
                "torque case's harmonic 0: the shear the torque concentrates at the engagement zones is left out, and "
                "a rim loaded there buckles lower), harmonics 0..%d scanned (Spectra on each harmonic's factor), boss "
                "clamped, rim free: the generator is neither prestress nor support; mode with %d waves around "
                "(buckling.vtu), eigenpair residual %.1e",
                b.per_harmonic.empty() ? 0 : b.per_harmonic.back().n, b.n, b.mode_residual);
  f.method = buf;
  // The body wall's shear at that torque, T/(2π r² t) at its mid-surface: an elastic bifurcation far beyond the
  // material's shear strength (von Mises: S_u/√3) is not reached; the figure is then an upper bound.
  const FlexsplineParams& fp = c.flexspline;
  const double r = fp.inner_radius_m + fp.wall_thickness_m / 2;
  const double tau = f.torque_Nm / (2 * std::numbers::pi * r * r * fp.wall_thickness_m);
  std::snprintf(buf, sizeof buf, "; the body wall's shear there %.0f MPa", tau / 1e6);
  f.method += buf;
  if (c.material.ultimate_strength_Pa && tau > *c.material.ultimate_strength_Pa / std::sqrt(3.0))
    f.method += ", beyond the material's shear strength S_u/√3: the elastic figure is an upper bound (the wall yields "
                "first)";
  return f;
}

/// The losses at the catalog's conditions (datasheet/losses.hpp), or why not.
std::optional<LossFigures> losses(const Case& c, const FourierSolution& fem, const ContactAnalysis& contact,
                                  const ContactBody& body, const FemReadout& readout, int ratio, std::string& why_not) {
  if (!c.lubricant) {
    why_not = "not computed: the case gives no [lubricant] (kind, viscosity_40C_mm2_s, viscosity_100C_mm2_s, "
              "temperature_C)";
    return std::nullopt;
  }
  if (!c.wave_generator->bearing || !body.stations().unilateral || contact.steps.back().station_force_N.empty()) {
    why_not = "not computed: the generator bearing's friction needs its balls (a [wave_generator] bearing) loaded by "
              "a cam or rollers in the contact";
    return std::nullopt;
  }
  const GeneratorBearing& bearing = *c.wave_generator->bearing;
  const BacklashModel model = make_backlash_model(*c.gear, fem_neutral_curve(readout.neutral_curve));
  const std::vector<double> sliding = flank_sliding_m_per_rad(model, contact);
  LossFigures l;
  LossConditions at;
  at.lubricant = *c.lubricant;
  if (c.contact.friction_coefficient > 0) {
    at.flank_friction = c.contact.friction_coefficient;
    l.flank_friction_from = "[contact] friction_coefficient";
  } else {
    at.flank_friction = kBoundaryFriction;
    l.flank_friction_from = "the case fixes none: boundary friction of steel flanks, ISO/TS 6336-20's value where the "
                            "rolling speed vanishes (the teeth slide radially in and out of the spaces)";
  }
  l.flank_friction = at.flank_friction;
  at.loss_factor = l.loss_factor = c.material.loss_factor;
  at.wave_energy_J = harmonic_strain_energy_J(fem.section, c.material, fem.generator);
  at.ring = ring_on_bore(c, body.stations());
  l.ring_friction = at.ring.friction;
  const LossAt split = [&](std::size_t i, const LossConditions& conditions) {
    return drive_losses(contact, i, sliding, bearing,
                        ball_loads_N(body.stations(), contact.steps[i].station_force_N, bearing.balls), ratio,
                        conditions);
  };
  const auto at_step = [&](std::size_t i, double rpm) {
    at.input_speed_rpm = rpm;
    return split(i, at);
  };
  const double rated = contact.steps.back().torque_Nm;
  l.rated_2000 = at_step(contact.steps.size() - 1, kInputSpeed_rpm);
  l.rated_1000 = at_step(contact.steps.size() - 1, 0.5 * kInputSpeed_rpm);
  l.half_rated_2000 = at_step(step_nearest(contact, 0.5 * rated), kInputSpeed_rpm);
  const std::size_t rest = step_nearest(contact, 0.0);
  l.no_load_2000 = at_step(rest, kInputSpeed_rpm);
  // The rate-independent losses at rest, so there at breakaway, read off the no-load split: the flexspline's damping,
  // the ring's slip, and the flanks' sliding where the teeth bear on each other with no load (a preloaded mesh;
  // nothing on teeth cut to zero backlash).
  const double omega_in = kInputSpeed_rpm * 2 * std::numbers::pi / 60;
  l.damping_input_torque_Nm = l.no_load_2000.flexspline_damping_W / omega_in;
  l.ring_slip_input_torque_Nm = l.no_load_2000.ring_slip_W / omega_in;
  l.flanks_at_rest_input_torque_Nm = l.no_load_2000.flank_sliding_W / omega_in;
  l.starting_torque_Nm = starting_torque_Nm(
      bearing, ball_loads_N(body.stations(), contact.steps[rest].station_force_N, bearing.balls), ratio, {},
      l.damping_input_torque_Nm + l.ring_slip_input_torque_Nm + l.flanks_at_rest_input_torque_Nm);
  l.backdriving_torque_Nm = backdriving_torque_Nm(l.starting_torque_Nm, l.rated_2000, ratio);
  l.map = loss_map(contact, split, at);
  char text[200];
  std::snprintf(text, sizeof text, "%s, base oil %.4g/%.4g mm²/s at 40/100 °C, at %.4g °C: %.4g mm²/s (ASTM D341)",
                c.lubricant->kind.c_str(), c.lubricant->viscosity_40C_mm2_s, c.lubricant->viscosity_100C_mm2_s,
                c.lubricant->temperature_C, l.rated_2000.viscosity_mm2_s);
  l.lubricant = text;
  return l;
}

}  // namespace

void add_datasheet_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("datasheet", "the drive's catalog sheet from its geometry: limits, stiffness, lost "
                                              "motion, life; the published figures beside for a catalog size");
  static std::string case_path, out;
  static double max_memory_gb = 0;
  cmd->add_option("case", case_path, "case file (TOML)")->required();
  cmd->add_option("--out", out, "output directory (default out/<case stem>/)");
  cmd->add_option("--max-memory", max_memory_gb, "refuse a model whose estimated peak memory exceeds this (GB)");
  cmd->callback([] {
    // The sheet reads the flexspline on harmonics (its buckling is solved harmonic by harmonic): refused up front for
    // a case that is not a body of revolution, like every case the loaded contact cannot take.
    const Case c = load_case_with_solver(case_path, "fourier", "");
    const FlexsplineModel model = flexspline_model(c);
    naming_file(c.path, [&] { check_contact_model(model); });
    if (!reduction_ratio(*c.gear))
      throw InputError(c.path + ": gear.teeth_circular = " + std::to_string(c.gear->teeth_circular) +
                       "; the datasheet needs a whole reduction ratio z_f / (z_c - z_f) (teeth_flexspline = " +
                       std::to_string(c.gear->teeth_flexspline) + "), as catalog drives have");
    OutputSet outputs(out.empty() ? default_out_dir(c) : std::filesystem::path(out), kDatasheetFiles);
    write_resolved_case(c, outputs);

    const FemJobResult fem = solve_flexspline(c, max_memory_gb);
    const FemReadout readout = fem_readout(fem.solution);
    const std::unique_ptr<ContactBody> body = contact_body(c, fem, readout.generator_u);
    ContactOptions options = contact_options(c, series_parts(c));
    options.ratcheting_ceiling_Nm = kRatchetingCeilingPerRated * options.rated_torque_Nm;
    progress("datasheet: the loaded contact from -rated to +rated torque, then past it to the ratcheting torque");
    const ContactAnalysis contact = naming_file(c.path, [&] { return analyse_contact(model, *body, readout, options); });

    DatasheetInputs in;
    in.rated_torque_Nm = options.rated_torque_Nm;
    in.rated_torque_origin = rated_torque_origin(c);
    in.ratio = *reduction_ratio(*c.gear);  // whole: checked before any work
    in.catalog_size = c.catalog_size;
    in.contact = &contact;
    in.infinite_life = infinite_life(c, *fem.harmonic, in.rated_torque_Nm, in.why_no_infinite_life);
    in.first_yield = first_yield(c, *fem.harmonic, in.rated_torque_Nm, in.why_no_yield);
    in.buckling = naming_file(c.path, [&] { return buckling(c, *fem.harmonic, outputs.staging()); });
    if (c.wave_generator->bearing)
      in.bearing = naming_file(c.path, [&] {
        return generator_bearing_life(*c.wave_generator->bearing, body->stations(), contact, in.ratio, kInputSpeed_rpm);
      });
    else
      in.why_no_bearing = "not computed: the case gives no [wave_generator] bearing (balls, ball_diameter_mm)";
    in.losses = naming_file(
        c.path, [&] { return losses(c, *fem.harmonic, contact, *body, readout, in.ratio, in.why_no_losses); });
    if (!c.material.fatigue_limit_Pa)
      in.why_no_tooth_root = "not computed: the case gives no [material] fatigue_limit_MPa and ultimate_strength_MPa";
    else if ((in.why_no_tooth_root = tooth_root_not_covered(*c.gear, c.flexspline)).empty())
      in.tooth_root = tooth_root_limit(*c.gear, c.flexspline, c.material, contact);
    const Datasheet sheet = make_datasheet(in);

    write_file_atomic(outputs.staging() / "datasheet.json", datasheet_json(sheet, c));
    write_file_atomic(outputs.staging() / "datasheet.html", datasheet_html(sheet, c));
    outputs.commit();
    std::printf("datasheet %s (ratio %d%s):\n%s", c.path.c_str(), in.ratio,
                c.catalog_size ? (", catalog size " + std::to_string(*c.catalog_size)).c_str() : "",
                datasheet_table(sheet).c_str());
    std::printf("  wrote %s\n", outputs.dir().string().c_str());
  });
}

}  // namespace sw::app
