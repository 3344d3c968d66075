// bench_buckling: the flexspline's torsion buckling on the TET10 model of a case (fem/tet10_buckling.hpp), the
// generator idealised three ways, with this machine's DGEMM rate in the same run:
//   1. free: the torque case's prestress (the case's torque load, e.g. at the engagement zones) and nothing else;
//   2. the generator's band held radially all round (bilateral stations, in the prestress and the buckling);
//   3. held, and on the generator's deformation as a base state: its stress's geometric stiffness added to K
//      (K + K_σ(generator) + λ·K_σ(torque)), what the generator's prestress changes.
// Each row: the smallest positive λ among the --modes smallest |λ| (the signed ones found beside it: with the band
// held and the torque at the zones the two signs differ) × the case's torque, the wall clock of its solve.
#include <algorithm>
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "common/error.hpp"
#include "common/progress.hpp"
#include "dgemm.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/tet10_buckling.hpp"
#include "io/case.hpp"
#include "mesh/flexspline.hpp"

int main(int argc, char** argv) {
  CLI::App app{"bench_buckling: TET10 torsion buckling, free, generator held, and on the generator's prestress"};
  std::string path;
  int modes = 4;
  app.add_option("case", path, "case file (TOML) with a [wave_generator]")->required();
  app.add_option("--modes", modes, "eigenpairs per solve (smallest |lambda|)");
  CLI11_PARSE(app, argc, argv);
  using namespace sw;
  try {
    std::printf("DGEMM (n = 2000): %.1f GF/s\n", bench::dgemm_gflops(2000, 3));
    Case c = load_case(path);
    c.solver.method = SolverMethod::Tet10;
    const FlexsplineModel model = flexspline_model(c);
    if (!model.wave_generator) throw InputError(path + ": the bench needs a [wave_generator]");
    Stopwatch clock;
    const TetMesh mesh = mesh_flexspline(c.flexspline, c.gear, c.mesh);
    const FlexsplineSystem system = assemble_and_factorise(model, mesh);
    const FlexsplineSolution s = analyse_flexspline(model, mesh, system);
    const LoadCaseSolution* generator = nullptr;
    for (const LoadCaseSolution& lc : s.cases)
      if (lc.name == "generator") generator = &lc;
    if (!generator) throw InputError(path + ": the solution has no generator case");
    std::printf("%s: %zu nodes, %lld equations, mesh + factor + load cases %.1f s; torque %.4g N·m\n", path.c_str(),
                mesh.n_nodes(), static_cast<long long>(system.dofs.n_equations), clock.lap(), model.load.torque_Nm);
    Tet10BucklingOptions o;
    o.modes = modes;
    const double T = model.load.torque_Nm != 0 ? model.load.torque_Nm : 1.0;
    const auto row = [&](const char* what, const BucklingResultTet10& b) {
      std::string found;
      for (const double l : b.load_factors) found += (found.empty() ? "" : ", ") + std::to_string(l);
      std::printf("  %-58s smallest positive lambda %.6f: %.1f N·m (largest residual %.1e; found %s) %.1f s\n", what,
                  b.smallest_positive, b.smallest_positive * T,
                  *std::max_element(b.residuals.begin(), b.residuals.end()), found.c_str(), clock.lap());
      std::fflush(stdout);
    };
    row("free (the torque case's prestress alone)", torsion_buckling_tet10(model, mesh, system, false, o));
    row("generator's band held radially", torsion_buckling_tet10(model, mesh, system, true, o));
    row("held, on the generator's prestress (K + K_sigma(generator))",
        torsion_buckling_tet10(model, mesh, system, true, o, generator->u));
    row("free, on the generator's prestress", torsion_buckling_tet10(model, mesh, system, false, o, generator->u));
  } catch (const InputError& e) {
    std::fprintf(stderr, "bench_buckling: %s\n", e.what());
    return 1;
  }
  return 0;
}
