// bench_dynamics — performance target: 0.1 s of simulated time for the seed gear with every pair moving, output at
// 1e-5 s, must take < 10 s of wall time on this machine.
//
// Builds the model as `strainwave dynamics` does (app/dynamics_job: the case's [dynamics] table; moving pairs coupled
// through the FEM's flexspline body when the case says rim = "fem", which solves the FEM and the loaded-contact phases
// first, untimed), forces duration 0.1 s and output step 1e-5 s unless told otherwise, and times simulate() alone
// (wall and process CPU clocks). Prints the pair model, integrator steps / RHS / Jacobian evaluations, output samples,
// wall time, the real-time factor (simulated s / wall s) and the target. Printed figures only, never asserted.
//
//   build/bench/bench_dynamics                                   # cases/seed_190_192.toml as the case says (FEM rim)
//   build/bench/bench_dynamics --rim rigid                       # the same teeth on a rigid rim
//   build/bench/bench_dynamics cases/mbd_26_28.toml --duration 0.02 --output-step 1e-4
#include <algorithm>
#include <cmath>
#include <memory>
#include <cstdio>
#include <filesystem>
#include <ctime>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/dynamics_job.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "dynamics/simulate.hpp"
#include "io/case.hpp"

#ifndef SW_SOURCE_DIR
#define SW_SOURCE_DIR "."
#endif

namespace {

/// Process CPU time (all threads), seconds.
double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_dynamics: time the multibody simulation of a gear"};
  std::string case_path = std::string(SW_SOURCE_DIR) + "/cases/seed_190_192.toml";
  double duration = 0.1, output_step = 1e-5;
  app.add_option("case", case_path, "case file (TOML) with [gear] and a [dynamics] table");
  app.add_option("--duration", duration, "simulated time, s (overrides the case)")->check(CLI::PositiveNumber);
  app.add_option("--output-step", output_step, "output sampling, s (overrides the case)")->check(CLI::PositiveNumber);
  std::string pairs_mode, rim_mode;
  app.add_option("--pairs", pairs_mode, "moving | frozen (overrides dynamics.pairs)")
      ->check(CLI::IsMember({"moving", "frozen"}));
  app.add_option("--rim", rim_mode, "moving pairs: fem (coupled through the flexspline body) | rigid (overrides "
                                    "dynamics.rim)")->check(CLI::IsMember({"fem", "rigid"}));
  CLI11_PARSE(app, argc, argv);
  try {
    sw::quiet_progress() = true;
    const sw::Case c = sw::load_case(case_path);
    if (!c.gear) throw sw::InputError(case_path + ": [gear] is missing");
    sw::DynamicsParams p = c.dynamics ? *c.dynamics : sw::DynamicsParams{};
    p.duration_s = duration;
    p.output_step_s = output_step;
    // The steady window must lie inside the run (validation); the bench times simulate() alone and never uses it.
    p.steady_from_s = std::min(p.steady_from_s, duration / 2);
    if (!pairs_mode.empty()) p.pair_motion = pairs_mode == "moving" ? sw::PairMotion::Moving : sw::PairMotion::Frozen;
    if (!rim_mode.empty()) p.rim = rim_mode == "fem" ? sw::RimCoupling::Fem : sw::RimCoupling::Rigid;
    sw::OutputSet scratch(std::filesystem::temp_directory_path() / "bench_dynamics");  // never brought in
    const sw::app::DynamicsJobModel job = sw::app::dynamics_model(c, p, {}, scratch);
    const sw::DynamicsModel& m = job.model;
    std::printf("bench_dynamics %s: %s, %d/%d teeth, %s; %.3g s simulated, output every %.3g s (sampled %d times per "
                "step)\n", case_path.c_str(), sw::to_string(p.configuration), m.teeth_flexspline, m.teeth_circular,
                job.source.c_str(), p.duration_s, p.output_step_s, p.oversampling);
    const double c0 = cpu_seconds();
    sw::Stopwatch watch;
    const sw::DynamicsSeries s = sw::simulate(m);
    const double wall = watch.lap(), cpu = cpu_seconds() - c0;
    std::printf("  simulate: wall %.3f s, CPU %.3f s; real-time factor %.4g (simulated / wall); %zu pairs, %ld "
                "integrator steps, %ld RHS, %ld Jacobians, %zu output samples  [target < 10 s: %s]\n",
                wall, cpu, p.duration_s / wall, m.moving ? s.pair_force_N.size() : m.pairs.size(), s.stats.steps, s.stats.rhs_evals, s.stats.jac_evals,
                s.time_s.size(), wall < 10.0 ? "met" : "NOT met");
    std::printf("  target: 0.1 s simulated, every pair moving, output at 1e-5 s, < 10 s "
                "(timings on a busy machine are noisy)\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_dynamics: %s\n", e.what());
    return 1;
  }
  return 0;
}
