// bench_contact: what the loaded tooth contact costs beyond the FEM, on one case (default the seed cup):
//   1. DGEMM rate of the loaded BLAS (the limit for the triangular solves with many right-hand sides).
//   2. The FEM as `run` does it: mesh, assembly + factorisation, every load case (timed, for scale).
//   3. The contact stage: influence coefficients of the flank patterns and generator stations (half solves on the
//      one factor, Yᵀ·Y), then `steps` torque steps each way through the contact problem.
// Wall clock; on a shared machine say so with the figures.
#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "bench_util.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "contact/loaded_contact.hpp"
#include "dgemm.hpp"
#include "fem/flexspline_analysis.hpp"
#include "io/case.hpp"

int main(int argc, char** argv) {
  using namespace sw;
  CLI::App app{"bench_contact: the loaded tooth contact's cost beyond the FEM"};
  std::string case_path = "cases/seed_190_192.toml";
  int steps = 20;
  app.add_option("case", case_path, "case file (TOML)");
  app.add_option("--steps", steps, "torque steps each way");
  CLI11_PARSE(app, argc, argv);
  try {
    quiet_progress() = true;
    std::printf("DGEMM (n = 2000): %.1f GF/s\n", bench::dgemm_gflops(2000, 3));
    const Case c = load_case(case_path);
    Stopwatch clock;
    const TetMesh mesh = bench::mesh_for_bench(c);
    const double t_mesh = clock.lap();
    const FlexsplineSystem system = assemble_and_factorise(flexspline_model(c), mesh);
    const double t_factor = clock.lap();
    const FlexsplineSolution fem = analyse_flexspline(flexspline_model(c), mesh, system);
    const double t_cases = clock.lap();
    ContactOptions o;
    o.rated_torque_Nm = c.load.rated_torque_Nm.value_or(c.load.torque_Nm);
    o.steps = steps;
    const double cpu0 = bench::process_cpu_s();
    const ContactAnalysis a = analyse_contact(sw::flexspline_model(c), mesh, system, sw::fem_readout(fem), o);
    const double t_contact = clock.lap(), cpu_contact = bench::process_cpu_s() - cpu0;
    std::printf("%s: %lld equations; mesh %.1f s, assembly + factor %.1f s (%.1f GF at %.1f GF/s), load cases %.1f s\n",
                case_path.c_str(), static_cast<long long>(fem.timings.factor.equations), t_mesh, t_factor,
                fem.timings.factor.factor_gflop, fem.timings.factor.factor_gflop / fem.timings.factor.factor_s,
                t_cases);
    std::printf("contact: %d contacts (%zu flank patterns + generator stations): patterns and gaps %.2f s, influence "
                "coefficients %.2f s, %zu torque steps %.3f s, independent check (one full solve, reactions) %.2f s; "
                "total beyond the FEM %.2f s wall clock, %.2f s CPU on all threads\n", a.unknowns, a.flanks.size(),
                a.setup_s, a.influence_s, a.steps.size(), a.contact_s, a.check_s, t_contact, cpu_contact);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_contact: %s\n", e.what());
    return 1;
  }
  return 0;
}
