// bench_design_band: how far the designed drive's stiffness moves over the proportions its source gives as ranges
// (Ivanov's rim under the teeth 0.01–0.015 d, body wall 0.6–0.9 of the rim, toothed face 0.15–0.2 d:
// design/proportions.hpp DesignProportions), beside the catalog's. Report, never fit: the design keeps its defaults.
//   1. DGEMM rate of the loaded BLAS (the limit of the harmonic factorisations).
//   2. For each size and ratio and each set of proportions: `strainwave design` with them, then `strainwave contact`
//      (frictionless, harmonic solver): the twist at the catalog's T1, T2 and rated torque against the catalog's
//      three-segment law, K1/K2/K3, lost motion and play, the split of the twist at rated, and the seconds both took.
// The sets: the design's defaults; the compliant end of all three ranges together (thin rim, thin wall, narrow face)
// and the stiff end; with --each also every proportion alone at either end of its range.
// Run by hand: build/bench/bench_design_band [--sizes 14,17,20] [--ratios 30,50,100] [--each]. Wall clock.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "common/constants.hpp"
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
  bool each = false;
  app.add_option("--sizes", sizes, "catalog sizes, comma-separated");
  app.add_option("--ratios", ratios, "ratios, comma-separated");
  app.add_flag("--each", each, "also every proportion alone at either end of its range");
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
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("sw_bench_design_band_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::printf("DGEMM (n = 2000): %.1f GF/s\n", sw::bench::dgemm_gflops(2000, 3));
  std::printf("size ratio | proportions | twist at T1, T2, rated (arcmin, computed / catalog) | K1 K2 K3 (1e4 N·m/rad) "
              "| lost motion, play (arcmin) | body, teeth, generator, circular spline, engagement (%% of the twist "
              "at rated) | seconds\n");
  using sw::kArcmin;
  for (const int size : sw::bench::integer_list(sizes))
    for (const int ratio : sw::bench::integer_list(ratios))
      for (const Proportions& p : sets) {
        const std::string tag = std::to_string(size) + "_" + std::to_string(ratio);
        const fs::path case_file = dir / (tag + ".toml"), out = dir / tag;
        const auto start = std::chrono::steady_clock::now();
        const auto design = sw::testing::run_strainwave("design --size " + std::to_string(size) + " --ratio " +
                                                        std::to_string(ratio) + " " + p.options + " --out " +
                                                        case_file.string());
        if (design.exit_code != 0) {
          std::printf("%d %d | %s | design failed: %s", size, ratio, p.name, design.output.c_str());
          continue;
        }
        const auto run = sw::testing::run_strainwave("contact --quiet " + case_file.string() + " --out " + out.string());
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (run.exit_code != 0) {
          std::printf("%d %d | %s | contact failed: %s", size, ratio, p.name, run.output.c_str());
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
        std::printf("%d %d | %s | %s, %s, %s | %.2f %.2f %.2f | %.2f, %.2f | %.0f, %.0f, %.0f, %.0f, %.0f | %.1f\n", size,
                    ratio, p.name, against(at_T1, published("twist_at_T1_rad")).c_str(),
                    against(at_T2, published("twist_at_T2_rad")).c_str(),
                    against(c["twist_at_rated_arcmin"].get<double>(), published("twist_at_rated_rad")).c_str(),
                    K1 * 1e-4, K2 * 1e-4, K3 * 1e-4, c["lost_motion_arcmin"].get<double>(),
                    c["play_arcmin"].get<double>(), 100 * s["body"].get<double>(), 100 * s["teeth"].get<double>(),
                    100 * s["generator"].get<double>(), 100 * s["circular_spline"].get<double>(),
                    100 * s["engagement"].get<double>(), seconds);
        std::fflush(stdout);
      }
  fs::remove_all(dir);
  return 0;
}
