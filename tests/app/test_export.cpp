// The CalculiX/Abaqus deck a user exports (`fem --export-inp`) solves, in Debian's ccx, to the same φ₀ as ours; and the
// same case run twice gives the same result.json apart from timings and memory.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "fem/flexspline_analysis.hpp"
#include "io/case.hpp"
#include "io/inp.hpp"
#include "mesh/flexspline.hpp"
#include "tests/cli.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sw::testing;

/// A copy of a shipped case with some lines replaced, in a fresh folder.
fs::path variant(const std::string& name, const std::string& base,
                 const std::vector<std::pair<std::string, std::string>>& edits) {
  const fs::path dir = fs::temp_directory_path() / ("sw_export_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ifstream in(base);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& [from, to] : edits) {
    EXPECT_NE(text.find(from), std::string::npos) << from;
    text.replace(text.find(from), from.size(), to);
  }
  std::ofstream(dir / (name + ".toml")) << text;
  return dir;
}

TEST(ExportInp, CalculixSolvesTheDeckToOurPhi0) {
  const fs::path dir = variant("tube", "cases/tube_torsion.toml",
                               {{"size_mm = 1.5", "size_mm = 2.0"}, {"wall_layers = 2", "wall_layers = 1"},
                                {"length_mm = 30.0", "length_mm = 10.0"}});
  const std::string bin = strainwave_binary();
  const CommandRun fem = run_shell(bin + " --quiet fem " + (dir / "tube.toml").string() + " --solver tet10 --no-vtk --export-inp " +
                                   (dir / "job.inp").string() + " --out " + (dir / "out").string());
  ASSERT_EQ(fem.exit_code, 0) << fem.output;
  ASSERT_TRUE(fs::exists(dir / "job.inp"));
  ASSERT_EQ(run_shell("cd " + dir.string() + " && OMP_NUM_THREADS=1 ccx -i job > ccx.log 2>&1").exit_code, 0)
      << "ccx failed; see " << (dir / "ccx.log");
  // φ₀ from ccx's displacements, read on our own (deterministic) mesh of the same case.
  const sw::Case c = sw::load_case((dir / "tube.toml").string());
  const sw::TetMesh mesh = sw::mesh_flexspline(c.flexspline, c.gear, c.mesh);  // what `fem` meshes
  const Eigen::VectorXd u = sw::read_frd_displacements(dir / "job.frd", mesh.n_nodes());
  const double phi0_ccx = sw::reading_rotation(flexspline_model(c), mesh, u);
  const double phi0_ours = read_json(dir / "out" / "result.json")["phi0_rad"].get<double>();
  // 1e-5: the same linear system solved by two direct solvers; the deck's 14 significant digits are far below it.
  EXPECT_NEAR(phi0_ccx / phi0_ours, 1.0, 1e-5) << phi0_ccx << " vs " << phi0_ours;
  fs::remove_all(dir);
}

TEST(Determinism, TheSameCaseTwiceGivesTheSameResultApartFromTimingsAndMemory) {
  const fs::path dir = variant("seed", "cases/seed_190_192.toml",
                               {{"size_mm = 0.6", "size_mm = 1.2"},
                                {"wall_layers = 2", "wall_layers = 1\ncorner_levels = 0"}});  // coarse, uniform
  const std::string bin = strainwave_binary();
  for (const char* run : {"a", "b"}) {
    const CommandRun r = run_shell(bin + " --quiet fem " + (dir / "seed.toml").string() + " --no-vtk --out " +
                                   (dir / run).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  auto strip = [](nlohmann::json j) {
    j.erase("timings_s");
    j.erase("peak_rss_bytes");
    j["solver"].erase("factor_gflop_per_s");
    for (auto& h : j["solver"]["harmonics_solved"]) h.erase("factor_s");  // the harmonic solver's per-harmonic times
    return j;
  };
  const auto a = strip(read_json(dir / "a" / "result.json")), b = strip(read_json(dir / "b" / "result.json"));
  EXPECT_EQ(a, b) << nlohmann::json::diff(a, b).dump(1);
  std::ifstream ca(dir / "a" / "neutral_curve.csv"), cb(dir / "b" / "neutral_curve.csv");
  const std::string ta((std::istreambuf_iterator<char>(ca)), {}), tb((std::istreambuf_iterator<char>(cb)), {});
  EXPECT_EQ(ta, tb);
  fs::remove_all(dir);
}

}  // namespace
