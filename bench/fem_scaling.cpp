// bench_fem_scaling: how the TET10 solver scales with mesh size, on the tube of cases/tube_torsion.toml
// (r_i 18.5, r_o 19.5, L 30 mm, steel, 100 N·m as the exact torsion shear τ = T·r/J on the free end, clamped at z = 0).
//
// What it measures, per mesh (each mesh runs in a forked child, so its peak RSS is its own):
//   DOF (free equations), nnz(K) (stored upper triangle), nnz(L), the factor's GF, seconds per phase
//     mesh      mesh_tube (TetGen + layers + midside projection)
//     assemble  dof map + assemble_stiffness (CSC upper triangle)
//     analyse   CHOLMOD symbolic analysis (ordering) — CholmodFactor stats
//     factor    CHOLMOD numeric supernodal factorisation — CholmodFactor stats
//     solve     torque load vector + forward/back substitution + φ₀ reading
//     post      recovered nodal stresses (what `strainwave fem` computes for its VTU)
//     output    write_fem_vtk (cylindrical components + VTU via io/vtu.hpp's write_vtu + PVD) into a temp dir
//   factor GF/s and its efficiency = factor GF/s ÷ DGEMM GF/s, where DGEMM is the loaded BLAS's dgemm_ on two n×n
//   matrices (default 2000) measured in the same run with the same thread count (best of 3);
//   assemble/factor (target < 20 %); peak RSS (getrusage of the child) and peak RSS ÷ (nnz(L)·16 B + mesh arrays)
//   (target < 1.5; the process's baseline RSS before meshing is printed too, it dominates small meshes);
//   φ₀ (least-squares rigid rotation of the free end face) and its error against T·L/(G·J).
//
// Run (Release build):
//   cmake -S . -B build-bench && cmake --build build-bench -j2 --target bench_fem_scaling
//   build-bench/bench/bench_fem_scaling          # default meshes 2/1,1/1,1/2,0.5/2: 67k, 134k, 436k, 873k DOF
//   OPENBLAS_NUM_THREADS=1 build-bench/bench/bench_fem_scaling --meshes 2/1,1.5/1     # small (< 100k DOF)
//   build-bench/bench/bench_fem_scaling --mesh-only --meshes ...     # only mesh and count DOF, to choose sizes
// A mesh is SIZE_MM/LAYERS: mesh.size_mm and mesh.wall_layers (the along-wall edge is at most 2× the layer
// thickness, so refine both). DOF does not grow smoothly with them (0.45/2 gives 2.0M DOF, 0.7/3 1.4M and 11 GB
// peak): check new sizes with --mesh-only first. The BLAS threads come from the environment (OPENBLAS_NUM_THREADS); the header line
// says what was loaded. Run the big meshes on a quiet machine: the figures are wall-clock.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bench/bench_util.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "fem/assembly.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/post.hpp"
#include "io/case.hpp"
#include "io/fem_output.hpp"
#include "dgemm.hpp"


namespace sw::bench {
namespace {

/// One mesh's figures. Plain data: a forked child writes it through a pipe.
struct Row {
  MeshSpec spec;
  bool ok = false;
  char error[512] = {};
  long long nodes = 0, tets = 0, dofs = 0, nnz_K = 0;
  double nnz_L = 0, gflop = 0, min_dihedral_deg = 0;
  double mesh_s = 0, assemble_s = 0, analyse_s = 0, factor_s = 0, solve_s = 0, post_s = 0, output_s = 0;
  long baseline_rss = 0, peak_rss = 0;
  double mesh_bytes = 0;
  double phi0_rad = 0, phi0_theory_rad = 0;
};

std::vector<MeshSpec> parse_meshes(const std::string& text) {
  std::vector<MeshSpec> out = parse_mesh_specs(text, "--meshes", false);
  if (out.empty()) throw InputError("--meshes: empty list; expected e.g. 1.0/2,0.5/3");
  return out;
}

/// Everything for one mesh, in this process.
Row run_one(Case c, const MeshSpec& spec, const std::filesystem::path& out_dir, bool mesh_only) {
  Row row;
  row.spec = spec;
  row.baseline_rss = current_rss_bytes();
  c.mesh.size_m = spec.size_mm * 1e-3;
  c.mesh.wall_layers = spec.layers;

  Stopwatch clock;
  const TetMesh mesh = mesh_for_bench(c);
  row.mesh_s = clock.lap();
  row.nodes = static_cast<long long>(mesh.n_nodes());
  row.tets = static_cast<long long>(mesh.tets.size());
  row.min_dihedral_deg = mesh.quality.min_dihedral_deg;
  row.mesh_bytes = mesh_bytes(mesh);
  progress("mesh " + std::to_string(spec.size_mm) + "/" + std::to_string(spec.layers) + ": " +
           std::to_string(row.nodes) + " nodes, " + std::to_string(row.tets) + " TET10");

  const std::vector<bool> fixed_node = clamped_nodes(mesh);
  std::vector<bool> fixed(3 * mesh.n_nodes());
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) fixed[3 * i] = fixed[3 * i + 1] = fixed[3 * i + 2] = fixed_node[i];
  const DofMap dofs = make_dof_map(fixed);
  if (mesh_only) {
    row.dofs = dofs.n_equations;
    row.peak_rss = peak_rss_bytes();
    row.ok = true;
    return row;
  }
  const SymmetricCsc K = assemble_stiffness(mesh, c.material, dofs);
  row.assemble_s = clock.lap();
  row.dofs = dofs.n_equations;
  row.nnz_K = static_cast<long long>(K.nnz());
  progress("assembled " + std::to_string(row.dofs) + " equations");

  const CholmodFactor factor(K, equation_nodes(dofs));  // as the fem job orders it: METIS on the node graph
  clock.lap();
  const FactorStats& st = factor.stats();
  row.nnz_L = st.factor_nnz;
  row.gflop = st.factor_gflop;
  row.analyse_s = st.analyse_s;
  row.factor_s = st.factor_s;
  progress("factorised: " + std::to_string(st.factor_gflop) + " GF in " + std::to_string(st.factor_s) + " s");

  const double T = c.load.torque_Nm;
  const Eigen::VectorXd f = torque_load_vector(flexspline_model(c), mesh, T);
  const Eigen::VectorXd x = factor.solve(restrict_to_free(dofs, f));
  FlexsplineSolution s;
  s.cases.push_back({"torque", expand_to_full(dofs, x, Eigen::VectorXd::Zero(3 * mesh.n_nodes())), {}, 0.0});
  row.phi0_rad = reading_rotation(flexspline_model(c), mesh, s.cases[0].u);
  row.solve_s = clock.lap();
  const auto& fl = c.flexspline;
  const double ri = fl.inner_radius_m, ro = fl.inner_radius_m + fl.wall_thickness_m;
  const double J = std::numbers::pi / 2 * (std::pow(ro, 4) - std::pow(ri, 4));
  row.phi0_theory_rad = T * fl.length_m / (c.material.shear_modulus_Pa() * J);

  s.cases[0].stress = nodal_stress(mesh, c.material, s.cases[0].u);
  row.post_s = clock.lap();
  write_fem_vtk(out_dir, mesh, s.cases);
  row.output_s = clock.lap();
  row.peak_rss = peak_rss_bytes();
  row.ok = true;
  return row;
}

/// Runs run_one in a forked child (fresh peak RSS, a crash stays contained) and returns its row.
Row run_in_child(const Case& c, const MeshSpec& spec, const std::filesystem::path& out_dir, bool mesh_only) {
  int fd[2];
  if (pipe(fd) != 0) throw InputError("pipe() failed");
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) throw InputError("fork() failed");
  if (pid == 0) {
    close(fd[0]);
    Row row;
    row.spec = spec;
    try {
      row = run_one(c, spec, out_dir, mesh_only);
    } catch (const std::exception& e) {
      std::snprintf(row.error, sizeof row.error, "%s", e.what());
    }
    const char* p = reinterpret_cast<const char*>(&row);
    std::size_t left = sizeof row;
    while (left > 0) {
      const ssize_t w = write(fd[1], p, left);
      if (w <= 0) break;
      p += w;
      left -= static_cast<std::size_t>(w);
    }
    close(fd[1]);
    _exit(row.ok ? 0 : 1);
  }
  close(fd[1]);
  Row row;
  row.spec = spec;
  char* p = reinterpret_cast<char*>(&row);
  std::size_t got = 0;
  while (got < sizeof row) {
    const ssize_t r = read(fd[0], p + got, sizeof row - got);
    if (r <= 0) break;
    got += static_cast<std::size_t>(r);
  }
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (got != sizeof row) {
    row = Row{};
    row.spec = spec;
    std::snprintf(row.error, sizeof row.error, "child died (%s %d)",
                  WIFSIGNALED(status) ? "signal" : "exit status",
                  WIFSIGNALED(status) ? WTERMSIG(status) : WEXITSTATUS(status));
  }
  return row;
}

void print_tables(const std::vector<Row>& rows, double dgemm) {
  const double MB = 1e6;
  std::printf("\nSize and memory\n");
  std::printf("%-9s %9s %9s %10s %11s %12s %7s %9s %9s %9s %6s %8s\n", "mesh", "nodes", "TET10", "DOF", "nnz(K)",
              "nnz(L)", "GF", "base MB", "peak MB", "L+mesh MB", "ratio", "min dih");
  for (const auto& r : rows) {
    char mesh[32];
    std::snprintf(mesh, sizeof mesh, "%g/%d", r.spec.size_mm, r.spec.layers);
    if (!r.ok) {
      std::printf("%-9s FAILED: %s\n", mesh, r.error);
      continue;
    }
    const double factor_mesh = r.nnz_L * 16.0 + r.mesh_bytes;
    std::printf("%-9s %9lld %9lld %10lld %11lld %12.0f %7.1f %9.0f %9.0f %9.0f %6.2f %8.1f\n", mesh, r.nodes, r.tets,
                r.dofs, r.nnz_K, r.nnz_L, r.gflop, r.baseline_rss / MB, r.peak_rss / MB, factor_mesh / MB,
                r.peak_rss / factor_mesh, r.min_dihedral_deg);
  }
  std::printf("\nSeconds per phase, rates, accuracy\n");
  std::printf("%-9s %10s %7s %8s %8s %8s %7s %7s %7s %8s %7s %6s %7s %12s %10s\n", "mesh", "DOF", "mesh", "assemble",
              "analyse", "factor", "solve", "post", "output", "total", "GF/s", "eff", "asm/fac", "phi0 rad",
              "err");
  for (const auto& r : rows) {
    if (!r.ok) continue;
    char mesh[32];
    std::snprintf(mesh, sizeof mesh, "%g/%d", r.spec.size_mm, r.spec.layers);
    const double rate = r.factor_s > 0 ? r.gflop / r.factor_s : 0.0;
    const double total = r.mesh_s + r.assemble_s + r.analyse_s + r.factor_s + r.solve_s + r.post_s + r.output_s;
    std::printf("%-9s %10lld %7.2f %8.2f %8.2f %8.2f %7.2f %7.2f %7.2f %8.2f %7.1f %5.0f%% %6.1f%% %12.6e %+10.2e\n",
                mesh, r.dofs, r.mesh_s, r.assemble_s, r.analyse_s, r.factor_s, r.solve_s, r.post_s, r.output_s, total,
                rate, 100 * rate / dgemm, r.factor_s > 0 ? 100 * r.assemble_s / r.factor_s : 0.0, r.phi0_rad,
                r.phi0_rad / r.phi0_theory_rad - 1);
  }
  if (!rows.empty() && rows.front().ok)
    std::printf("\nphi0 theory T·L/(G·J) = %.6e rad. eff = factor GF/s ÷ DGEMM GF/s; asm/fac = assemble ÷ factor "
                "(target < 20 %%); ratio = peak RSS ÷ (nnz(L)·16 B + mesh) (target < 1.5; base = RSS before meshing)."
                "\n",
                rows.front().phi0_theory_rad);
}

int run(int argc, char** argv) {
  CLI::App app{"TET10 solver scaling on the tube of cases/tube_torsion.toml (see the header of bench/fem_scaling.cpp)"};
  std::string case_path = SW_SOURCE_DIR "/cases/tube_torsion.toml";
  std::string meshes = "2/1,1/1,1/2,0.5/2";
  int dgemm_n = 2000;
  bool keep = false, mesh_only = false;
  app.add_option("--case", case_path, "tube case file (TOML)")->capture_default_str();
  app.add_option("--meshes", meshes, "comma-separated SIZE_MM/LAYERS (mesh.size_mm / mesh.wall_layers)")
      ->capture_default_str();
  app.add_option("--dgemm-n", dgemm_n, "order of the DGEMM reference matrices")->capture_default_str();
  app.add_flag("--keep", keep, "keep the temp dir with the VTU files");
  app.add_flag("--mesh-only", mesh_only, "only mesh and count DOF (to choose --meshes); no solve, no DGEMM");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  const Case c = load_case(case_path);
  if (c.flexspline.shape != FlexsplineShape::Tube || c.flexspline.teeth != TeethModel::None)
    throw InputError(case_path + ": flexspline must be shape = \"tube\" with teeth = \"none\" (the torsion theory "
                     "check assumes the plain tube)");
  const std::vector<MeshSpec> specs = parse_meshes(meshes);
  TempDir tmp("sw_fem_scaling_");
  if (keep) tmp.keep();

  if (mesh_only) {
    std::printf("%-9s %9s %9s %10s %8s %9s\n", "mesh", "nodes", "TET10", "DOF", "mesh s", "peak MB");
    for (const auto& spec : specs) {
      const Row r = run_in_child(c, spec, tmp.path(), true);
      char mesh[32];
      std::snprintf(mesh, sizeof mesh, "%g/%d", spec.size_mm, spec.layers);
      if (!r.ok)
        std::printf("%-9s FAILED: %s\n", mesh, r.error);
      else
        std::printf("%-9s %9lld %9lld %10lld %8.2f %9.0f\n", mesh, r.nodes, r.tets, r.dofs, r.mesh_s, r.peak_rss / 1e6);
      std::fflush(stdout);
    }
    return 0;
  }
  const BlasInfo blas = detect_blas();
  std::printf("bench_fem_scaling: %s, T = %g N·m\nBLAS: %s%s\n", case_path.c_str(), c.load.torque_Nm,
              blas.description.c_str(), blas.is_reference ? "  ** REFERENCE BLAS: install libopenblas0-pthread **" : "");
  progress("DGEMM " + std::to_string(dgemm_n) + "x" + std::to_string(dgemm_n));
  const double dgemm = dgemm_gflops(dgemm_n, 3);
  std::printf("DGEMM %dx%d: %.1f GF/s (best of 3, same BLAS and threads)\n", dgemm_n, dgemm_n, dgemm);
  std::fflush(stdout);

  std::vector<Row> rows;
  for (std::size_t k = 0; k < specs.size(); ++k) {
    const std::filesystem::path out = tmp.path() / ("mesh" + std::to_string(k));
    rows.push_back(run_in_child(c, specs[k], out, false));
    if (!rows.back().ok) std::fprintf(stderr, "bench_fem_scaling: mesh %zu failed: %s\n", k, rows.back().error);
  }
  print_tables(rows, dgemm);
  if (keep) std::printf("VTU files kept in %s\n", tmp.path().c_str());
  return std::all_of(rows.begin(), rows.end(), [](const Row& r) { return r.ok; }) ? 0 : 1;
}

}  // namespace
}  // namespace sw::bench

int main(int argc, char** argv) {
  try {
    return sw::bench::run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_fem_scaling: %s\n", e.what());
    return 1;
  }
}
