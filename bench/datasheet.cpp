// bench_datasheet: the designed drives' catalog sheets beside the published figures, and what each sheet costs.
//   1. DGEMM rate of the loaded BLAS (the limit of the harmonic factorisations).
//   2. For each size and ratio: `strainwave design`, then `strainwave datasheet` on it (wall clock of the whole
//      command), and one row of the sheet's figures with the catalog's beside (published in brackets).
// Run by hand: build/bench/bench_datasheet [--sizes 14,17,20] [--ratios 50,80,100] [--friction MU]
// [--lubricant NU40,NU100,TEMP_C] [--design "OPTIONS"]. --friction sets [contact] friction_coefficient (the loop's
// hysteresis) and --lubricant adds a [lubricant] table (the losses' rows); without them those rows are "-". --design
// passes its options to `strainwave design` (the proportions within their published ranges, docs/commands.md). Wall
// clock; on a shared machine say so with the figures.
#include <chrono>
#include <cstdio>
#include <fstream>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "dgemm.hpp"
#include "integer_list.hpp"
#include "io/case_edit.hpp"
#include "tests/cli.hpp"

namespace {

std::string number(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

/// A figure of the sheet as "value (published)": "-" when not computed or not on the sheet (the efficiencies at the
/// other conditions come only with a lubricant), "inf" when beyond the search.
std::string figure(const nlohmann::json& f, const char* name, const char* format, double scale = 1) {
  if (!f.contains(name)) return "-";
  const auto& x = f[name];
  std::string out = x["value"].is_null() ? (x["computed"].get<bool>() ? "inf" : "-")
                                         : number(format, x["value"].get<double>() * scale);
  if (!x["published"].is_null()) out += " (" + number(format, x["published"].get<double>() * scale) + ")";
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_datasheet: the designed drives' sheets beside the catalog, and their cost"};
  std::string sizes = "14,17,20", ratios = "50,80,100";
  app.add_option("--sizes", sizes, "catalog sizes, comma-separated");
  app.add_option("--ratios", ratios, "ratios, comma-separated");
  double friction = 0;
  std::string lubricant;
  app.add_option("--friction", friction, "the flanks' friction coefficient written into each designed case");
  app.add_option("--lubricant", lubricant, "NU40,NU100,TEMP_C: an oil written into each designed case");
  std::string design_options;
  app.add_option("--design", design_options,
                 "more options for `strainwave design`, e.g. \"--rim-per-d 0.01 --wall-per-rim 0.6\" (its proportions)");
  CLI11_PARSE(app, argc, argv);
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("sw_bench_datasheet_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::printf("DGEMM (n = 2000): %.1f GF/s\n", sw::bench::dgemm_gflops(2000, 3));
  std::printf("size ratio | K1 K2 K3 (1e4 N·m/rad) | lost motion, play, hysteresis (arcmin) | buckling | ratcheting | "
              "first yield | momentary | infinite life | "
              "tooth root | L10 (h) | exponent | efficiency 2000/1000 rpm, half load | no-load, starting (mN·m) | "
              "seconds\n");
  for (const int size : sw::bench::integer_list(sizes))
    for (const int ratio : sw::bench::integer_list(ratios)) {
      const std::string tag = std::to_string(size) + "_" + std::to_string(ratio);
      const fs::path case_file = dir / (tag + ".toml"), out = dir / tag;
      const auto design = sw::testing::run_strainwave("design --size " + std::to_string(size) + " --ratio " +
                                                      std::to_string(ratio) + " " + design_options + " --out " +
                                                      case_file.string());
      if (design.exit_code != 0) {
        std::printf("%d %d | design failed: %s", size, ratio, design.output.c_str());
        continue;
      }
      if (friction > 0) {  // into the design's [contact] table (the key set as `sweep --set` sets it)
        std::ifstream in(case_file);
        const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        std::ofstream(case_file) << sw::case_text_with(text, case_file.string(),
                                                       {{"contact.friction_coefficient", friction}}, "--friction");
      }
      {
        std::ofstream add(case_file, std::ios::app);
        if (!lubricant.empty()) {
          std::stringstream ss(lubricant);
          std::string nu40, nu100, temperature;
          std::getline(ss, nu40, ',');
          std::getline(ss, nu100, ',');
          std::getline(ss, temperature, ',');
          add << "\n[lubricant]\nkind = \"oil\"\nviscosity_40C_mm2_s = " << nu40 << "\nviscosity_100C_mm2_s = " << nu100
              << "\ntemperature_C = " << temperature << "\n";
        }
      }
      const auto start = std::chrono::steady_clock::now();
      const auto run = sw::testing::run_strainwave("datasheet --quiet " + case_file.string() + " --out " + out.string());
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (run.exit_code != 0) {
        std::printf("%d %d | datasheet failed: %s", size, ratio, run.output.c_str());
        continue;
      }
      const nlohmann::json f = sw::testing::read_json(out / "datasheet.json")["figures"];
      std::printf("%d %d | %s %s %s | %s, %s, %s | %s | %s | %s | %s | %s | %s | %s | %s | %s / %s, %s | %s, %s | "
                  "%.1f\n", size, ratio,
                  figure(f, "K1_Nm_per_rad", "%.2f", 1e-4).c_str(), figure(f, "K2_Nm_per_rad", "%.2f", 1e-4).c_str(),
                  figure(f, "K3_Nm_per_rad", "%.2f", 1e-4).c_str(), figure(f, "lost_motion_arcmin", "%.2f").c_str(),
                  figure(f, "play_arcmin", "%.2f").c_str(), figure(f, "hysteresis_loss_arcmin", "%.3f").c_str(),
                  figure(f, "buckling_torque_Nm", "%.0f").c_str(), figure(f, "ratcheting_torque_Nm", "%.0f").c_str(),
                  figure(f, "first_yield_torque_Nm", "%.0f").c_str(), figure(f, "momentary_limit_Nm", "%.0f").c_str(),
                  figure(f, "infinite_life_torque_Nm", "%.0f").c_str(),
                  figure(f, "tooth_root_limit_Nm", "%.0f").c_str(), figure(f, "bearing_life_L10_h", "%.0f").c_str(),
                  figure(f, "bearing_life_exponent", "%.2f").c_str(), figure(f, "efficiency", "%.2f").c_str(),
                  figure(f, "efficiency_1000rpm", "%.2f").c_str(), figure(f, "efficiency_half_rated", "%.2f").c_str(),
                  figure(f, "no_load_running_torque_Nm", "%.0f", 1e3).c_str(),
                  figure(f, "starting_torque_Nm", "%.2g", 1e3).c_str(), seconds);
      std::fflush(stdout);
    }
  fs::remove_all(dir);
  return 0;
}
