// bench_fem_convergence CASE.toml [--ratio 0.8] [--levels 3]
// Mesh convergence of φ₀ for any case: solves the case at its own mesh.size_mm and at sizes × ratio, × ratio², ...
// (wall_layers and corner_levels as the case gives or derives them: the corner edge, a fraction of the diaphragm's
// layer, shrinks with the size), prints φ₀ per mesh, the observed order p from the last three, the Richardson
// extrapolated φ₀ and each mesh's estimated discretisation error relative to it. The case's default mesh (level 0) is
// to be within 0.5 % of the extrapolated value. Runs one solve at a time, BLAS threads as the environment says.
// bench_fourier_vs_tet10 gives the converged value of a body of revolution more cheaply (harmonic sections).
#include <cmath>
#include <cstdio>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/error.hpp"
#include "common/progress.hpp"
#include "fem/flexspline_analysis.hpp"
#include "io/case.hpp"
#include "mesh/flexspline.hpp"

int main(int argc, char** argv) {
  CLI::App app{"mesh convergence of phi0 for a case"};
  std::string case_path;
  double ratio = 0.8;
  int levels = 3;
  app.add_option("case", case_path, "case file")->required();
  app.add_option("--ratio", ratio, "size ratio between levels (< 1)")->check(CLI::Range(0.3, 0.95));
  app.add_option("--levels", levels, "number of meshes (>= 3)")->check(CLI::Range(3, 6));
  CLI11_PARSE(app, argc, argv);
  sw::quiet_progress() = true;
  try {
    const sw::Case base = sw::load_case(case_path);
    std::vector<double> h, phi;
    std::printf("%-10s %-8s %-8s %-10s %-16s %-10s\n", "size_mm", "layers", "levels", "nodes", "phi0_rad", "time_s");
    for (int k = 0; k < levels; ++k) {
      sw::Case c = base;
      c.mesh.size_m = base.mesh.size_m * std::pow(ratio, k);
      sw::Stopwatch clock;
      const sw::TetMesh mesh = sw::mesh_flexspline(c.flexspline, c.gear, c.mesh);
      const sw::FlexsplineSolution s = sw::analyse_flexspline(flexspline_model(c), mesh);
      h.push_back(c.mesh.size_m);
      phi.push_back(s.compliance_rad_per_Nm * (c.load.torque_Nm != 0 ? c.load.torque_Nm : 1.0));
      std::printf("%-10.4f %-8d %-8d %-10zu %-16.9e %-10.1f\n", c.mesh.size_m * 1e3, c.mesh.wall_layers,
                  sw::corner_levels(c.flexspline, c.mesh), mesh.n_nodes(), phi.back(), clock.lap());
      std::fflush(stdout);
    }
    const std::size_t n = phi.size();
    const double d1 = phi[n - 2] - phi[n - 3], d2 = phi[n - 1] - phi[n - 2];
    if (d1 == 0 || d2 == 0 || d1 / d2 <= 0) {
      std::printf("non-monotone convergence (differences %.3e, %.3e): no extrapolation; spread %.3e relative\n", d1, d2,
                  std::abs(d2) / std::abs(phi.back()));
      return 0;
    }
    const double p = std::log(d1 / d2) / std::log(1.0 / ratio);
    if (!(p > 0.5)) {
      std::printf("differences do not shrink (%.3e then %.3e, order %.2f): not in the asymptotic range, no "
                  "extrapolation; the finest mesh differs from the coarsest by %.3f %%\n",
                  d1, d2, p, 100 * (phi[n - 1] / phi[0] - 1));
      return 0;
    }
    const double extrapolated = phi[n - 1] + d2 / (std::pow(1.0 / ratio, p) - 1.0);
    std::printf("observed order p = %.2f, extrapolated phi0 = %.9e rad\n", p, extrapolated);
    for (std::size_t k = 0; k < n; ++k)
      std::printf("  size %.4f mm: estimated error %+.3f %%\n", h[k] * 1e3, 100 * (phi[k] / extrapolated - 1));
    const bool meets = std::abs(phi[0] / extrapolated - 1) < 0.005;
    std::printf("default mesh %s the 0.5 %% target\n", meets ? "meets" : "MISSES");
  } catch (const sw::InputError& e) {
    std::fprintf(stderr, "bench_fem_convergence: error: %s\n", e.what());
    return 2;
  }
  return 0;
}
