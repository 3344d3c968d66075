// bench_vs_calculix: our whole fem solve against CalculiX (ccx) on the same TET10 mesh, supports and nodal loads.
//
// What it does and measures:
//   1. ccx: if `ccx` is not on PATH, installs Debian's calculix-ccx (apt-get, non-interactive; sudo when not root).
//   2. Meshes the case once (tube cases; see bench_util.hpp), prints its size. Not counted in either time.
//   3. Ours, timed: analyse_flexspline(case, mesh) = assemble + CHOLMOD analyse/factor + solve of every load case +
//      φ₀ + reaction check + nodal stresses (exactly what `strainwave fem` does between meshing and writing).
//   4. Writes the same mesh as a CalculiX deck in a temp dir: *NODE, *ELEMENT TYPE=C3D10 (VTK quadratic-tetra order
//      is the Abaqus/CalculiX C3D10 order), *BOUNDARY fixing all dofs of the clamped nodes, *MATERIAL/*ELASTIC,
//      *SOLID SECTION, *STATIC, *CLOAD with the nonzero entries of our consistent torque load vector on free nodes,
//      *NODE FILE U. Not counted in either time.
//   5. Runs `ccx -i job` there (OMP_NUM_THREADS = CCX_NPROC_EQUATION_SOLVER = --ccx-threads, default 2), wall clock
//      from exec to exit, so it includes ccx reading its input and writing its .frd. Never at the same time as ours.
//   6. Reads the displacements from the ASCII .frd's last DISP block (" -1", node I10, 3×E12.5), takes φ₀ with our
//      own reading_rotation, and prints both φ₀, their relative difference (target 1e-5), the largest nodal
//      displacement difference, both wall times and the speed-up ccx ÷ ours (target ≥ 3×).
// The .frd holds 6 significant digits, so agreement better than a few 1e-6 cannot be seen through it.
//
// Run (Release build; on a quiet machine for the timing):
//   cmake -S . -B build-bench && cmake --build build-bench -j2 --target bench_vs_calculix
//   build-bench/bench/bench_vs_calculix cases/tube_torsion.toml [--size-mm 0.5] [--layers 3] [--keep]
// Our BLAS threads come from the environment (OPENBLAS_NUM_THREADS); give both sides the same count
// (--ccx-threads) for a fair speed-up. --keep leaves the ccx deck, log and .frd in the temp dir.
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench/bench_util.hpp"
#include "bench/ccx.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "fem/assembly.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/flexspline_analysis.hpp"
#include "io/case.hpp"
#include "io/fem_output.hpp"
#include "io/inp.hpp"

namespace sw::bench {
namespace {

namespace fs = std::filesystem;

int run(int argc, char** argv) {
  CLI::App app{"Our fem solve vs CalculiX on the same TET10 mesh and loads (see the header of bench/vs_calculix.cpp)"};
  std::string case_path;
  double size_mm = 0;
  int layers = 0, ccx_threads = 2;
  bool keep = false;
  app.add_option("case", case_path, "case file (TOML)")->required();
  app.add_option("--size-mm", size_mm, "override mesh.size_mm");
  app.add_option("--layers", layers, "override mesh.wall_layers");
  app.add_option("--ccx-threads", ccx_threads, "OMP_NUM_THREADS and CCX_NPROC_EQUATION_SOLVER for ccx")
      ->capture_default_str();
  app.add_flag("--keep", keep, "keep the temp dir with the ccx deck, log and .frd");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  Case c = load_case(case_path);
  if (size_mm > 0) c.mesh.size_m = size_mm * 1e-3;
  if (layers > 0) c.mesh.wall_layers = layers;
  // The deck holds the clamp and the torque only: compare with our torque case without a generator (with one, ours
  // keeps the generator in place and the band is held).
  c.wave_generator.reset();
  if (c.load.torque_Nm == 0.0) throw InputError(case_path + ": load.torque_Nm = 0; the comparison needs a torque");
  const std::string ccx = ensure_ccx();
  TempDir tmp("sw_vs_ccx_");
  if (keep) tmp.keep();

  const BlasInfo blas = detect_blas();
  std::printf("bench_vs_calculix: %s (mesh.size_mm %g, wall_layers %d, T = %g N·m)\nBLAS (ours): %s\nccx: %s, %d "
              "threads\n",
              case_path.c_str(), c.mesh.size_m * 1e3, c.mesh.wall_layers, c.load.torque_Nm, blas.description.c_str(),
              ccx.c_str(), ccx_threads);

  Stopwatch clock;
  const TetMesh mesh = mesh_for_bench(c);
  const double mesh_s = clock.lap();
  std::printf("mesh: %zu nodes, %zu TET10, min dihedral %.1f deg, %.2f s (shared, not timed below)\n",
              mesh.n_nodes(), mesh.tets.size(), mesh.quality.min_dihedral_deg, mesh_s);
  std::fflush(stdout);

  progress("ours: analyse_flexspline");
  clock.lap();
  const FlexsplineSolution ours = analyse_flexspline(flexspline_model(c), mesh);
  const double ours_s = clock.lap();
  const FactorStats& factor = ours.timings.factor;
  const Eigen::VectorXd* u_ours = nullptr;
  for (const auto& lc : ours.cases)
    if (lc.name == "torque") u_ours = &lc.u;
  if (!u_ours) throw InputError("analyse_flexspline returned no torque case");

  const std::vector<bool> fixed_node = clamped_nodes(mesh);
  const Eigen::VectorXd load = torque_load_vector(flexspline_model(c), mesh, c.load.torque_Nm);
  const fs::path inp = tmp.path() / "job.inp";
  write_inp_deck(inp, c, mesh, fixed_node, load, "bench_vs_calculix");
  const double inp_s = clock.lap();
  progress("ccx deck " + inp.string() + " written in " + std::to_string(inp_s) + " s; running ccx");

  const double ccx_s = run_ccx(ccx, tmp.path(), ccx_threads);
  progress("ccx done in " + std::to_string(ccx_s) + " s; reading job.frd");
  const Eigen::VectorXd u_ccx = read_frd_displacements(tmp.path() / "job.frd", mesh.n_nodes());
  const double phi_ccx = reading_rotation(flexspline_model(c), mesh, u_ccx);
  const double phi_ours = ours.phi0_rad;
  const double du = (u_ccx - *u_ours).reshaped(3, mesh.n_nodes()).colwise().norm().maxCoeff();
  const double umax = u_ours->reshaped(3, mesh.n_nodes()).colwise().norm().maxCoeff();

  const CcxLog ccx_log = read_ccx_log(tmp.path() / "ccx.log");
  std::printf("\n%-30s %16s %16s\n", "", "strainwave", "CalculiX");
  std::printf("%-30s %16lld %16lld\n", "equations", static_cast<long long>(factor.equations),
              ccx_log.equations);
  std::printf("%-30s %16.9e %16.9e\n", "phi0 (rad)", phi_ours, phi_ccx);
  std::printf("%-30s %16.3f %16.3f\n", "wall time (s)", ours_s, ccx_s);
  std::printf("%-30s %16.2e   (target <= 1e-5)\n", "phi0 relative difference", std::abs(phi_ours - phi_ccx) /
              std::abs(phi_ccx));
  std::printf("%-30s %16.2e   (max over nodes of |u_ours - u_ccx| / max |u|)\n", "displacement difference",
              du / umax);
  std::printf("%-30s %16.2f   (target >= 3)\n", "speed-up (ccx / ours)", ccx_s / ours_s);
  std::printf("%-30s %16.2e   (phi0 theory %.6e rad)\n", "ours vs T·L/(G·J)",
              phi_ours / ours.checks.phi0_theory_rad - 1, ours.checks.phi0_theory_rad);
  std::printf("ours: factor %.2f GF in %.2f s (%.1f GF/s), nnz(L) %.0f, assemble %.2f s, solve %.2f s, peak RSS %.0f MB"
              "\n",
              factor.factor_gflop, factor.factor_s, factor.factor_s > 0 ? factor.factor_gflop / factor.factor_s : 0.0,
              factor.factor_nnz, ours.timings.assemble_s, ours.timings.solve_s, peak_rss_bytes() / 1e6);
  std::printf("%s", ccx_log.summary.c_str());
  if (keep) std::printf("ccx files kept in %s\n", tmp.path().c_str());
  return 0;
}

}  // namespace
}  // namespace sw::bench

int main(int argc, char** argv) {
  try {
    return sw::bench::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_vs_calculix: %s\n", e.what());
    return 1;
  }
}
