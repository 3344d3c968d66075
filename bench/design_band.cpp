// bench_design_band: how far the designed drive's stiffness moves over the proportions its source gives as ranges
// (Ivanov's rim under the teeth 0.01–0.015 d, body wall 0.6–0.9 of the rim, toothed face 0.15–0.2 d:
// design/proportions.hpp DesignProportions), beside the catalog's. Report, never fit: the design keeps its defaults.
//   1. DGEMM rate of the loaded BLAS (the limit of the harmonic factorisations).
//   2. For each size and ratio and each set of proportions: `strainwave design` with them, then `strainwave contact`
//      (frictionless, harmonic solver): the twist at the catalog's T1, T2 and rated torque against the catalog's
//      three-segment law, K1/K2/K3, lost motion and play, the split of the twist at rated, and the seconds both took.
//   3. With --friction μ,…: `contact` again on the same case with [contact] friction_coefficient = μ, the catalog's
//      loop (rated torque, cycled): its hysteresis loss at zero torque and the loop's seconds.
//   4. With --generator-at f,…: steps 2 and 3 with the generator locked f of a circular-spline pitch from a tooth on
//      the major axis ([contact] generator_angle_deg = f·360/z_c; default 0 alone).
// The sets: the design's defaults; the compliant end of all three ranges together (thin rim, thin wall, narrow face)
// and the stiff end; with --each also every proportion alone at either end of its range; --defaults-only: the first.
// Each point ends with the catalog's targets it meets: twist within 25 % at T1, T2 and rated (where the catalog
// lists it); at ratio ≥ 50, where the catalog states them (../shared/reference/catalog_torsional_stiffness.md),
// lost motion below 1 arcmin and a hysteresis loss between 0.1 and 1 arcmin (each friction coefficient). At ratio 30
// the catalog's own K1 puts the elastic twist between ±4 % of rated above 1 arcmin, and it states neither.
// Run by hand: build/bench/bench_design_band [--sizes 14,17,20] [--ratios 30,50,100] [--each | --defaults-only]
// [--friction 0.05,0.1] [--generator-at 0,0.25,0.5]. Wall clock.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/constants.hpp"
#include "io/case.hpp"
#include "io/case_edit.hpp"
#include "dgemm.hpp"
#include "integer_list.hpp"
#include "tests/cli.hpp"

namespace {

struct Proportions {
  const char* name;
  const char* options;  ///< `design`'s options that set them
};

/// "1.451 / 1.341 (+8 %)": computed, catalog and the difference; the computed value alone without a catalog figure.
std::string against(double computed, const nlohmann::json& catalog) {
  char b[96];
  if (catalog.is_null()) {
    std::snprintf(b, sizeof b, "%.3f", computed);
  } else {
    const double c = catalog.get<double>();
    std::snprintf(b, sizeof b, "%.3f / %.3f (%+.0f %%)", computed, c, 100 * (computed / c - 1));
  }
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_design_band: the designed drive's stiffness over its proportions' published ranges"};
  std::string sizes = "14,17,20", ratios = "30,50,100";
  bool each = false, defaults_only = false;
  std::vector<double> friction;
  app.add_option("--sizes", sizes, "catalog sizes, comma-separated");
  app.add_option("--ratios", ratios, "ratios, comma-separated");
  app.add_flag("--each", each, "also every proportion alone at either end of its range");
  app.add_flag("--defaults-only", defaults_only, "the design's defaults alone");
  app.add_option("--friction", friction, "friction coefficients of the flanks' loop, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 1.0));
  std::vector<double> positions = {0};
  app.add_option("--generator-at", positions,
                 "where the generator is locked, fractions of a circular-spline pitch from a tooth on the major axis, "
                 "comma-separated (0 to 0.5 covers every position: the mesh mirrors about 0.5)")
      ->delimiter(',')
      ->check(CLI::Range(0.0, 1.0));
  CLI11_PARSE(app, argc, argv);
  std::vector<Proportions> sets = {
      {"defaults (rim 0.014 d, wall 0.7 rim, face 0.15 d)", ""},
      {"compliant end (0.01, 0.6, 0.15)", "--rim-per-d 0.01 --wall-per-rim 0.6 --face-per-d 0.15"},
      {"stiff end (0.015, 0.9, 0.2)", "--rim-per-d 0.015 --wall-per-rim 0.9 --face-per-d 0.2"}};
  if (each)
    sets.insert(sets.end(), {{"rim 0.01 d", "--rim-per-d 0.01"},
                             {"rim 0.015 d", "--rim-per-d 0.015"},
                             {"wall 0.6 rim", "--wall-per-rim 0.6"},
                             {"wall 0.9 rim", "--wall-per-rim 0.9"},
                             {"face 0.2 d", "--face-per-d 0.2"}});
  if (defaults_only) sets.resize(1);
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("sw_bench_design_band_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::printf("DGEMM (n = 2000): %.1f GF/s\n", sw::bench::dgemm_gflops(2000, 3));
  std::printf("size ratio | proportions | twist at T1, T2, rated (arcmin, computed / catalog) | K1 K2 K3 (1e4 N·m/rad) "
              "| lost motion, play (arcmin) | body, teeth, generator, circular spline, engagement (%% of the twist "
              "at rated) | hysteresis loss at each mu (arcmin) | catalog targets met | seconds\n");
  using sw::kArcmin;
  for (const int size : sw::bench::integer_list(sizes))
    for (const int ratio : sw::bench::integer_list(ratios))
      for (const Proportions& p : sets) {
        const std::string tag = std::to_string(size) + "_" + std::to_string(ratio);
        const fs::path design_file = dir / (tag + ".toml");
        const auto design_start = std::chrono::steady_clock::now();
        const auto design = sw::testing::run_strainwave("design --size " + std::to_string(size) + " --ratio " +
                                                        std::to_string(ratio) + " " + p.options + " --out " +
                                                        design_file.string());
        if (design.exit_code != 0) {
          std::printf("%d %d | %s | design failed: %s", size, ratio, p.name, design.output.c_str());
          continue;
        }
        const double design_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - design_start).count();
        const std::string design_text = sw::testing::read_text(design_file);
        const int teeth_circular = sw::load_case(design_file.string()).gear->teeth_circular;
        for (const double at : positions) {
          const auto start = std::chrono::steady_clock::now();
          // The case with the generator locked `at` of a circular-spline pitch on and, for a loop, the flanks' μ.
          const auto case_with = [&](const std::string& name, double mu) {
            const fs::path f = dir / (tag + "_" + name + ".toml");
            std::ofstream(f) << sw::case_text_with(design_text, design_file.string(),
                                                   {{"contact.generator_angle_deg", at * 360.0 / teeth_circular},
                                                    {"contact.friction_coefficient", mu}},
                                                   "bench");
            return f;
          };
          char row[160];
          std::snprintf(row, sizeof row, "%d %d | %s, generator at %.2f pitch", size, ratio, p.name, at);
          const fs::path out = dir / tag;
          const auto run = sw::testing::run_strainwave("contact --quiet " + case_with("frictionless", 0).string() +
                                                       " --out " + out.string());
          if (run.exit_code != 0) {
            std::printf("%s | contact failed: %s", row, run.output.c_str());
            continue;
          }
          const nlohmann::json c = sw::testing::read_json(out / "contact.json");
          const nlohmann::json& k = c["catalog"];
          const nlohmann::json& ref = c["catalog_reference"];
          const double T1 = k["T1_Nm"], T2 = k["T2_Nm"], K1 = k["K1_Nm_per_rad"], K2 = k["K2_Nm_per_rad"],
                       K3 = k["K3_Nm_per_rad"];
          // The secants are the curve's own points at T1 and T2 (contact/torque_twist.hpp), so these are its twists.
          const double at_T1 = T1 / K1 * kArcmin, at_T2 = at_T1 + (T2 - T1) / K2 * kArcmin;
          const auto published = [&](const char* key) {
            return !ref.is_object() || !ref.contains(key) || ref[key].is_null()
                       ? nlohmann::json()
                       : nlohmann::json(ref[key].get<double>() * kArcmin);
          };
          const nlohmann::json& s = c["compliance_split"];
          // The catalog's targets: twist within 25 % where it lists one, lost motion below 1, hysteresis 0.1 to 1 arcmin.
          int met = 0, targets = 0;
          const auto target = [&](bool ok) {
            ++targets;
            met += ok;
          };
          const double twists[] = {at_T1, at_T2, c["twist_at_rated_arcmin"].get<double>()};
          const nlohmann::json catalog_twists[] = {published("twist_at_T1_rad"), published("twist_at_T2_rad"),
                                                   published("twist_at_rated_rad")};
          for (int i = 0; i < 3; ++i)
            if (!catalog_twists[i].is_null()) target(std::abs(twists[i] / catalog_twists[i].get<double>() - 1) <= 0.25);
          const bool stated = ratio >= 50;  // the catalog's lost motion and hysteresis figures
          if (stated) target(c["lost_motion_arcmin"].get<double>() < 1);
          std::string loops;
          for (const double mu : friction) {
            const fs::path loop_out = dir / (tag + "_loop");
            const auto t0 = std::chrono::steady_clock::now();
            const auto loop = sw::testing::run_strainwave("contact --quiet " + case_with("loop", mu).string() +
                                                          " --out " + loop_out.string());
            const double loop_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            char b[96];
            if (loop.exit_code != 0) {
              std::snprintf(b, sizeof b, "%smu %g failed", loops.empty() ? "" : ", ", mu);
              if (stated) target(false);
            } else {
              const double h = sw::testing::read_json(loop_out / "contact.json")["hysteresis_loss_arcmin"];
              std::snprintf(b, sizeof b, "%s%.3f at %g (%.1f s)", loops.empty() ? "" : ", ", h, mu, loop_s);
              if (stated) target(h >= 0.1 && h <= 1);
            }
            loops += b;
          }
          const double seconds =
              design_s + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          std::printf("%s | %s, %s, %s | %.2f %.2f %.2f | %.2f, %.2f | %.0f, %.0f, %.0f, %.0f, %.0f | %s | %d of %d | "
                      "%.1f\n", row, against(twists[0], catalog_twists[0]).c_str(),
                      against(twists[1], catalog_twists[1]).c_str(), against(twists[2], catalog_twists[2]).c_str(), K1 * 1e-4, K2 * 1e-4, K3 * 1e-4,
                      c["lost_motion_arcmin"].get<double>(), c["play_arcmin"].get<double>(),
                      100 * s["body"].get<double>(), 100 * s["teeth"].get<double>(),
                      100 * s["generator"].get<double>(), 100 * s["circular_spline"].get<double>(),
                      100 * s["engagement"].get<double>(), loops.empty() ? "-" : loops.c_str(), met, targets,
                      seconds);
          std::fflush(stdout);
        }
      }
  fs::remove_all(dir);
  return 0;
}
