// `strainwave design --size N [--ratio R] [--out CASE.toml]`: a cup-type case for a catalog size from the one set of
// proportions in design/proportions.hpp, its teeth set to zero backlash on the rim as the generator leaves it (the
// harmonic FEM of the designed cup: the neutral curves at the face's sections the loaded contact meshes the teeth
// on). The text is read back by the case reader and the flexspline checked before anything is written; --out is
// written atomically, without it the case goes to stdout.
#include <cmath>
#include <cstdio>
#include <iterator>
#include <numbers>
#include <string>
#include <type_traits>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/fem_job.hpp"
#include "common/error.hpp"
#include "common/format.hpp"
#include "contact/contact_body.hpp"
#include "contact/loaded_contact.hpp"
#include "fem/fourier_solver.hpp"
#include "fem/infinite_life.hpp"
#include "design/proportions.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "kinematics/neutral_curve.hpp"
#include "mesh/flexspline.hpp"

namespace sw::app {
namespace {

/// A whole decimal integer (T = int) or a decimal number (T = double), or InputError naming the option.
template <class T>
T parse_number(const std::string& option, const std::string& text) {
  std::size_t used = 0;
  T v = 0;
  try {
    if constexpr (std::is_same_v<T, int>) v = std::stoi(text, &used);
    else v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size())
    throw InputError(option + " " + text + (std::is_same_v<T, int> ? "; expected an integer" : "; expected a number"));
  return v;
}

/// The rim's neutral curves under the generator alone at the face's sections the loaded contact meshes (`sections`
/// of contact/contact_body.hpp face_slice: for the design's three, its closed-end edge, its centre and its open end),
/// from the case's harmonic FEM: the curves the contact places the teeth on.
std::vector<NeutralCurve> generator_deformed_sections(const Case& c, const FourierSolution& fs, int sections) {
  const double face = c.flexspline.rim_width_m, mid = fs.figures.neutral_curve->z_m;
  std::vector<double> z;
  for (int j = 0; j < sections; ++j) z.push_back(face_section_z_m(mid, face, j, sections));
  std::vector<NeutralCurve> curves;
  const std::vector<NeutralCurveSamples> read =
      neutral_curves_at(fs.section, fs.generator, neutral_radius(c.flexspline), z);
  for (std::size_t j = 0; j < read.size(); ++j) {
    char where[64];
    std::snprintf(where, sizeof where, "%.4g mm from the face's centre", (z[j] - mid) * 1e3);
    curves.push_back(
        fem_neutral_curve(read[j], std::string("FEM's generator-deformed (harmonic solver, ") + where + ")"));
  }
  return curves;
}

/// The designed flexspline body's fatigue strength, one line: its torque for infinite life (body_life below) against
/// the rated torque. The generator's bending stress grows as rim × w0 / r², and w0 = m grows as the ratio falls: at a
/// low ratio the rim the diameter sets can fail under the generator alone. The design is written all the same (a case
/// to study), and the line says it would not live and what lowers that stress.
std::string strength_line(const InfiniteLife& life, double rated_Nm) {
  const FatigueState& z = life.at_zero;
  char where[160];
  std::snprintf(where, sizeof where, "safety factor %.2f under the generator alone, at the %s r = %.2f mm, z = %.2f mm",
                z.safety_factor, z.place.c_str(), z.r_m * 1e3, z.z_m * 1e3);
  char line[640];
  const char* what = "  strength of the flexspline body (Sines-Goodman over a generator revolution; the teeth's notch "
                     "left out)";
  if (life.torque_Nm == 0)
    std::snprintf(line, sizeof line,
                  "%s: fails: the generator's bending alone exceeds the fatigue limit (%s); it grows with the rim's "
                  "thickness times w0 = m, so a thinner rim (--rim-per-d) lowers it\n",
                  what, where);
  else if (life.torque_Nm < rated_Nm)
    std::snprintf(line, sizeof line,
                  "%s: fails at rated torque: infinite life only up to %.4g N m of the rated %.4g N m (%s)\n", what,
                  life.torque_Nm, rated_Nm, where);
  else
    std::snprintf(line, sizeof line, "%s: infinite life up to %.4g N m, %.3g x the rated %.4g N m (%s)\n", what,
                  life.torque_Nm, life.torque_Nm / rated_Nm, rated_Nm, where);
  return line;
}

/// The case text of a design, read back and checked as any case.
Case checked_case(const std::string& text, const std::string& name) {
  Case c = parse_case(text, name);  // the written case must load and validate as any other
  validate_flexspline(c.flexspline, c.mesh);
  check_teeth_on_rim(c.flexspline, c.gear);
  return c;
}

/// The body's infinite life on a design's harmonic solution, searched to 20 × rated as the datasheet's.
InfiniteLife body_life(const Case& c, const FourierSolution& fs, double rated_Nm) {
  return infinite_life_torque(fs, flexspline_model(c), 20 * rated_Nm);
}

/// The body's torque for infinite life of the design `d` (its own harmonic FEM, a few seconds).
double body_life_Nm(const CupDesign& d, const std::string& name) {
  const Case c = checked_case(design_case_toml(d), name);
  double section_s = 0;
  return body_life(c, solve_fourier_model(c, 0.0, section_s), d.rated_torque_Nm).torque_Nm;
}

/// For a design whose body fails at rated torque: the thickest rim in Ivanov's range, the other proportions as given,
/// at which it lives (infinite life at rated torque), on the option's grid of 1e-4 d by bisection (a FEM a step:
/// about six), with its torque for infinite life; one line of advice, not a rule `design` applies (the case keeps the
/// rim it was asked for). The generator's bending stress falls with the rim, the torque's rises as it thins: the
/// bisection takes the rims between the range's thinnest and the one given as living below a threshold, which it
/// checks at the thinnest. `given_life_Nm`: the given rim's, which fails; so does every grid rim at least as thick
/// (the bracket's upper end, never solved again).
std::string thickest_living_rim_line(const CupDesign& d, double given_life_Nm, const std::string& name) {
  const DesignProportion& rim = kDesignProportions[0];
  auto life_at = [&](int k) {
    DesignProportions p = d.proportions;
    p.rim_per_d = k * 1e-4;
    return body_life_Nm(design_cup(d.size, d.ratio, p), name);
  };
  int lo = static_cast<int>(std::ceil(rim.min * 1e4 - 1e-9));
  int hi = static_cast<int>(std::ceil(d.proportions.rim_per_d * 1e4 - 1e-9));
  double lo_life = hi <= lo ? given_life_Nm : life_at(lo);
  char line[320];
  if (lo_life < d.rated_torque_Nm) {
    std::snprintf(line, sizeof line,
                  "    even the thinnest rim of Ivanov's range (--rim-per-d %.4g) fails at rated torque (infinite life "
                  "up to %.4g N m): this ratio needs a design beyond these proportions\n",
                  lo * 1e-4, lo_life);
    return line;
  }
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    const double life = life_at(mid);
    if (life >= d.rated_torque_Nm) {
      lo = mid;
      lo_life = life;
    } else {
      hi = mid;
    }
  }
  std::snprintf(line, sizeof line,
                "    the thickest rim of Ivanov's range that lives at rated torque: --rim-per-d %.4f (infinite life up "
                "to %.4g N m)\n",
                lo * 1e-4, lo_life);
  return line;
}

}  // namespace

void add_design_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("design", "write a cup-type case for a catalog size from documented proportions");
  static std::string size, ratio = "100", out;
  static std::string proportion[std::size(kDesignProportions)], tip_rounding;
  cmd->add_option("--size", size, "catalog size: the pitch diameter in tenths of an inch (8-65; 14, 17, 20 have "
                                  "published stiffness)")->required();
  cmd->add_option("--ratio", ratio, "reduction ratio z_f/(z_c - z_f), 30-160 (default 100)");
  cmd->add_option("--out", out, "case file to write (default: print to stdout)");
  const DesignProportions nominal;
  for (std::size_t i = 0; i < std::size(kDesignProportions); ++i) {
    const DesignProportion& q = kDesignProportions[i];
    cmd->add_option(q.option, proportion[i], std::string(q.meaning) + ", in Ivanov's [" + six_digits(q.min) + ", " +
                                                 six_digits(q.max) + "] (default " + six_digits(nominal.*q.member) + ")");
  }
  cmd->add_option("--tip-rounding-per-m", tip_rounding,
                  "both gears' tip corners rounded by this times the module before the zero-backlash cut (default 0: "
                  "sharp, as generated)");
  cmd->callback([] {
    DesignProportions p;
    for (std::size_t i = 0; i < std::size(kDesignProportions); ++i)
      if (!proportion[i].empty())
        p.*kDesignProportions[i].member = parse_number<double>(kDesignProportions[i].option, proportion[i]);
    CupDesign d = design_cup(parse_number<int>("--size", size), parse_number<int>("--ratio", ratio), p);
    if (!tip_rounding.empty()) round_tips(d, parse_number<double>("--tip-rounding-per-m", tip_rounding));
    const std::string name = out.empty() ? "cup_size" + std::to_string(d.size) + ".toml" : out;
    const Case first = checked_case(design_case_toml(d), name);
    double section_s = 0;
    const FourierSolution fs = solve_fourier_model(first, 0.0, section_s);
    set_zero_backlash(d, generator_deformed_sections(first, fs, kDesignFaceSections),
                      "FEM's generator-deformed (harmonic solver) face-end and mid-face");
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
    std::printf("  zero backlash on the %s curves: x_c - x_f = %.8f, the tightest pairs touching at +-%.1f deg (%s) "
                "on the %s curve; the major-axis pair's dead band at mid-face %.3f arcmin\n",
                z.curve.c_str(), z.shift_difference, z.tightest_angle_deg, z.tightest_parts.c_str(),
                z.tightest_section.c_str(), z.major_axis_play_rad * 180.0 / std::numbers::pi * 60.0);
    const InfiniteLife life = body_life(first, fs, d.rated_torque_Nm);
    std::fputs(strength_line(life, d.rated_torque_Nm).c_str(), stdout);
    if (life.torque_Nm < d.rated_torque_Nm) {
      std::fflush(stdout);  // the advice takes a few FEMs
      std::fputs(thickest_living_rim_line(d, life.torque_Nm, name).c_str(), stdout);
    }
  });
}

}  // namespace sw::app
