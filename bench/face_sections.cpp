// bench_face_sections: what the face's sections cost and what they resolve. The designed drive (`strainwave design`)
// with [contact] face_slices = n for each n, `strainwave contact` end to end (wall clock of the whole command, the
// harmonic FEM and its VTU files included), and the figures that move with n: the twist at rated torque, K1/K2/K3,
// the lost motion and the contacts the solve carries.
//   1. DGEMM rate of the loaded BLAS (this machine's dense limit, measured in the same run).
//   2. For each ratio and n: the design's case with face_slices = n, `contact` --runs times (median wall clock).
//   3. With --before BINARY: the same command with another build of strainwave (an earlier commit's), run in turn
//      with this build's, so that both see the same machine; its wall clock and whether its figures are the same.
// Run by hand: build/bench/bench_face_sections [--size 17] [--ratios 100,30] [--sections 3,5,8,12,16] [--runs 3]
// [--before /path/to/old/strainwave]. Wall clock: say so when the machine was shared.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "io/case_edit.hpp"
#include "dgemm.hpp"
#include "integer_list.hpp"
#include "tests/cli.hpp"

namespace {

namespace fs = std::filesystem;

struct Run {
  double seconds = 0;
  nlohmann::json contact;  ///< contact.json
};

/// `binary contact CASE` into `out`: its wall clock and contact.json. Throws when it fails.
Run contact_run(const std::string& binary, const fs::path& case_file, const fs::path& out) {
  const auto start = std::chrono::steady_clock::now();
  const auto r = sw::testing::run_shell(binary + " contact --quiet " + case_file.string() + " --out " + out.string());
  Run run;
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (r.exit_code != 0) throw std::runtime_error(binary + " contact " + case_file.string() + " failed: " + r.output);
  run.contact = sw::testing::read_json(out / "contact.json");
  return run;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// The figures a row prints, as one comparable string.
std::string figures(const nlohmann::json& c) {
  const nlohmann::json& k = c["catalog"];
  char b[200];
  std::snprintf(b, sizeof b, "%.3f | %.2f / %.2f / %.2f | %.3f | %d", c["twist_at_rated_arcmin"].get<double>(),
                k["K1_Nm_per_rad"].get<double>() / 1e4, k["K2_Nm_per_rad"].get<double>() / 1e4,
                k["K3_Nm_per_rad"].get<double>() / 1e4, c["lost_motion_arcmin"].get<double>(),
                c["unknowns"].get<int>());
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_face_sections: the designed drive's contact at n sections across the face: cost and figures"};
  int size = 17, runs = 1;
  std::string ratios = "100,30", sections = "3,5,8,12,16", before;
  app.add_option("--size", size, "catalog size")->capture_default_str();
  app.add_option("--ratios", ratios, "ratios, comma-separated")->capture_default_str();
  app.add_option("--sections", sections, "[contact] face_slices, comma-separated")->capture_default_str();
  app.add_option("--runs", runs, "runs of each command (the median is printed)")->check(CLI::Range(1, 20));
  app.add_option("--before", before, "another build's strainwave, run in turn with this one's");
  CLI11_PARSE(app, argc, argv);
  const fs::path dir = fs::temp_directory_path() / ("sw_bench_face_sections_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::printf("DGEMM (n = 2000): %.1f GF/s\n", sw::bench::dgemm_gflops(2000, 3));
  std::printf("size %d, `contact` end to end, median of %d run%s\n", size, runs, runs == 1 ? "" : "s");
  std::printf("ratio | n | twist at rated (arcmin) | K1 / K2 / K3 (1e4 N·m/rad) | lost motion (arcmin) | contacts | "
              "s%s\n",
              before.empty() ? "" : " | s before | speed-up | figures before");
  for (const int ratio : sw::bench::integer_list(ratios)) {
    const fs::path design_file = dir / ("design_" + std::to_string(ratio) + ".toml");
    const auto design = sw::testing::run_strainwave("design --size " + std::to_string(size) + " --ratio " +
                                                    std::to_string(ratio) + " --out " + design_file.string());
    if (design.exit_code != 0) {
      std::printf("%d | design failed: %s", ratio, design.output.c_str());
      continue;
    }
    const std::string design_text = sw::testing::read_text(design_file);
    for (const int n : sw::bench::integer_list(sections)) {
      const fs::path case_file = dir / ("case_" + std::to_string(ratio) + "_" + std::to_string(n) + ".toml");
      std::ofstream(case_file) << sw::case_text_with(design_text, design_file.string(),
                                                     {{"contact.face_slices", static_cast<double>(n)}}, "bench");
      std::vector<double> now_s, before_s;
      nlohmann::json now, then;
      for (int r = 0; r < runs; ++r) {
        const Run a = contact_run(sw::testing::strainwave_binary(), case_file, dir / "now");
        now_s.push_back(a.seconds);
        now = a.contact;
        if (before.empty()) continue;
        const Run b = contact_run(before, case_file, dir / "before");
        before_s.push_back(b.seconds);
        then = b.contact;
      }
      std::printf("%d | %d | %s | %.2f", ratio, n, figures(now).c_str(), median(now_s));
      if (!before.empty())
        std::printf(" | %.2f | %.1fx | %s", median(before_s), median(before_s) / median(now_s),
                    figures(then) == figures(now) ? "the same" : ("differ: " + figures(then)).c_str());
      std::printf("\n");
      std::fflush(stdout);
    }
  }
  fs::remove_all(dir);
  return 0;
}
