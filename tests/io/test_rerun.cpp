// A run again from the resolved case stored in its own output (`strainwave <command> out/X/result.json`) gives the
// same figures: the tube (fem) and the seed cup (run: fem, backlash on the FEM's neutral curve, contact), each on a
// coarse mesh, every output compared figure by figure by scripts/diff_outputs.py (relative 1e-12; timings, the paths
// a run was given and the tool's version aside).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/cli.hpp"
#include "tests/io/output_samples.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sw::testing;

/// A shipped case with its mesh coarsened (each `from` text replaced by its `to`), written as dir/<stem>.toml.
fs::path coarse_case(const std::string& shipped, const fs::path& dir,
                     const std::vector<std::pair<std::string, std::string>>& replacements) {
  std::string text = read_text(shipped);
  for (const auto& [from, to] : replacements) text.replace(text.find(from), from.size(), to);
  const fs::path path = dir / fs::path(shipped).filename();
  std::ofstream(path) << text;
  return path;
}

/// Runs `command` on the case file, then on the result.json it wrote; the two runs' outputs compare equal.
void expect_rerun_gives_the_same_figures(const std::string& command, const fs::path& case_file, const fs::path& dir,
                                         int files) {
  const std::string stem = case_file.stem().string();
  const fs::path first = dir / "first" / stem, again = dir / "again" / stem;
  const std::string options = " --quiet --no-vtk ";
  const CommandRun r1 = run_strainwave(command + options + case_file.string() + " --out " + first.string());
  ASSERT_EQ(r1.exit_code, 0) << r1.output;
  const fs::path stored = first / "result.json";
  const CommandRun r2 = run_strainwave(command + options + stored.string() + " --out " + again.string());
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  const CommandRun diff =
      run_shell("python3 scripts/diff_outputs.py " + (dir / "first").string() + " " + (dir / "again").string());
  EXPECT_EQ(diff.exit_code, 0) << diff.output;
  EXPECT_NE(diff.out.find(std::to_string(files) + " files compared, no figure moved"), std::string::npos)
      << diff.output;
  EXPECT_EQ(read_json(again / "result.json")["case"], read_json(stored)["case"]);
  EXPECT_EQ(read_json(again / "result.json")["case_file"], stored.string());
}

TEST(Rerun, TheTubeFromItsResultJsonGivesTheSameFigures) {
  const fs::path dir = scratch_dir("rerun_tube");
  const fs::path tube = coarse_case("cases/tube_torsion.toml", dir,
                                    {{"size_mm = 1.5", "size_mm = 4"}, {"wall_layers = 2", "wall_layers = 1"}});
  expect_rerun_gives_the_same_figures("fem", tube, dir, 1);
  fs::remove_all(dir);
}

TEST(Rerun, TheSeedCupFromItsResultJsonGivesTheSameFiguresInEveryOutput) {
  const fs::path dir = scratch_dir("rerun_seed");
  const fs::path seed = coarse_case("cases/seed_190_192.toml", dir,
                                    {{"size_mm = 0.6", "size_mm = 1.2"}, {"wall_layers = 2", "wall_layers = 1"}});
  expect_rerun_gives_the_same_figures("run", seed, dir, 3);  // result.json, backlash.json, contact.json
  fs::remove_all(dir);
}

}  // namespace
