// `strainwave design --size N [--ratio R] [--out CASE.toml]`: a cup-type case for a catalog size from the one set of
// proportions in design/proportions.hpp, its teeth set to zero backlash on the rim as the generator leaves it (the
// harmonic FEM of the designed cup: the neutral curve the loaded contact meshes the teeth on). The text is read back
// by the case reader and the flexspline checked before anything is written; --out is written atomically, without it
// the case goes to stdout.
#include <cstdio>
#include <numbers>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/fem_job.hpp"
#include "common/error.hpp"
#include "contact/loaded_contact.hpp"
#include "design/proportions.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "kinematics/neutral_curve.hpp"
#include "mesh/flexspline.hpp"

namespace sw::app {
namespace {

/// A whole decimal integer, or InputError naming the option.
int parse_int(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size())
    throw InputError(option + " " + text + "; expected an integer");
  return v;
}

/// The rim's neutral curve at mid-face under the generator alone, from the case's harmonic FEM: the curve the loaded
/// contact places the teeth on.
NeutralCurve generator_deformed_curve(const Case& c) {
  double section_s = 0;
  const FourierSolution fs = solve_fourier_model(c, 0, 0.0, section_s);
  return fem_neutral_curve(*fs.figures.neutral_curve, "FEM's generator-deformed (mid-face, harmonic solver)");
}

/// The case text of a design, read back and checked as any case.
Case checked_case(const std::string& text, const std::string& name) {
  Case c = parse_case(text, name);  // the written case must load and validate as any other
  validate_flexspline(c.flexspline, c.mesh);
  check_teeth_on_rim(c.flexspline, c.gear);
  return c;
}

}  // namespace

void add_design_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("design", "write a cup-type case for a catalog size from documented proportions");
  static std::string size, ratio = "100", out;
  cmd->add_option("--size", size, "catalog size: the pitch diameter in tenths of an inch (8-65; 14, 17, 20 have "
                                  "published stiffness)")->required();
  cmd->add_option("--ratio", ratio, "reduction ratio z_f/(z_c - z_f), 30-160 (default 100)");
  cmd->add_option("--out", out, "case file to write (default: print to stdout)");
  cmd->callback([] {
    CupDesign d = design_cup(parse_int("--size", size), parse_int("--ratio", ratio));
    const std::string name = out.empty() ? "cup_size" + std::to_string(d.size) + ".toml" : out;
    set_zero_backlash(d, generator_deformed_curve(checked_case(design_case_toml(d), name)));
    const std::string text = design_case_toml(d);
    checked_case(text, name);
    if (out.empty()) {
      std::fputs(text.c_str(), stdout);
      return;
    }
    write_file_atomic(out, text);
    std::printf("design: size %d, ratio %d: d = %.4g mm, m = %.4g mm, z_f/z_c = %d/%d, rated torque %.4g N m -> %s\n",
                d.size, d.ratio, d.pitch_diameter_m * 1e3, d.gear.module_m * 1e3, d.gear.teeth_flexspline,
                d.gear.teeth_circular, d.rated_torque_Nm, out.c_str());
    const ZeroBacklash& z = d.zero_backlash;
    std::printf("  zero backlash on the %s curve: x_c - x_f = %.8f, the tightest pairs touching at +-%.1f deg (%s); "
                "the major-axis pair's dead band %.3f arcmin\n",
                z.curve.c_str(), z.shift_difference, z.tightest_angle_deg, z.tightest_parts.c_str(),
                z.major_axis_play_rad * 180.0 / std::numbers::pi * 60.0);
  });
}

}  // namespace sw::app
