// bench_dynamics — performance target: 0.1 s of simulated time for the seed gear with all engaged tooth pairs,
// output at 1e-5 s, must take < 10 s of wall time on this machine.
//
// Builds the model as `strainwave dynamics` does (app/cmd_dynamics.cpp, default options: clearances from the basic
// kinematic model at wave-generator angle 0, φ₀ = 0, every engaged pair, interference kept as preload; the case's
// [dynamics] table), forces duration 0.1 s and output step 1e-5 s unless told otherwise, and times simulate() alone
// (wall and process CPU clocks). Prints pairs, integrator steps / RHS / Jacobian evaluations, output samples, wall
// time, the real-time factor (simulated s / wall s) and the target. Printed figures only, never asserted.
//
//   build-bench/bench/bench_dynamics                                   # cases/seed_190_192.toml, 0.1 s, 1e-5 s
//   build-bench/bench/bench_dynamics cases/mbd_26_28.toml --duration 0.02 --output-step 1e-4
#include <algorithm>
#include <cmath>
#include <memory>
#include <cstdio>
#include <ctime>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/error.hpp"
#include "common/progress.hpp"
#include "dynamics/model.hpp"
#include "dynamics/moving_mesh_build.hpp"
#include "contact/loaded_contact.hpp"
#include "gear/tooth_stiffness.hpp"
#include "gear/tooth_profile.hpp"
#include "dynamics/simulate.hpp"
#include "io/case.hpp"
#include "dynamics/kinematic_pairs.hpp"
#include "kinematics/backlash.hpp"
#include "kinematics/neutral_curve.hpp"

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
  std::string pairs_mode = "moving";
  app.add_option("--pairs", pairs_mode, "moving (every tooth travels, on a rigid rim with the tooth-pair compliance) | "
                                        "frozen (the pairs of generator angle 0)")
      ->check(CLI::IsMember({"moving", "frozen"}));
  CLI11_PARSE(app, argc, argv);
  try {
    sw::quiet_progress() = true;
    const sw::Case c = sw::load_case(case_path);
    if (!c.gear) throw sw::InputError(case_path + ": [gear] is missing");
    sw::DynamicsParams p = c.dynamics ? *c.dynamics : sw::DynamicsParams{};
    p.duration_s = duration;
    p.output_step_s = output_step;
    std::vector<sw::ToothPair> pairs = pairs_from_kinematics(c);
    int interfering = 0;
    for (const auto& t : pairs) interfering += (t.clearance_drive_m < 0 || t.clearance_coast_m < 0) ? 1 : 0;
    sw::DynamicsModel m = sw::make_model(*c.gear, c.flexspline, c.flexspline.shape == sw::FlexsplineShape::Cup,
                                         c.material, p, std::move(pairs), case_path);
    if (pairs_mode == "moving") {  // the rim coupled through the FEM needs the FEM job: `strainwave dynamics` times it
      const sw::GearParams g = *c.gear;
      const sw::ToothCompliance teeth = sw::case_tooth_pair_compliance(c);
      const sw::NeutralCurve curve = sw::generator_neutral_curve(
          sw::rim_mean_radius(c.flexspline), sw::case_radial_deformation_m(c), *c.wave_generator);
      m.moving = std::make_shared<sw::MovingMesh>(sw::rigid_rim_mesh(g, curve, teeth, 16));
      std::printf("bench_dynamics: moving pairs on a rigid rim (every tooth travels; tooth-pair compliance)\n");
    }
    std::printf("bench_dynamics %s: %s, %d/%d teeth, %zu engaged pairs (kinematic clearances, %d with interference "
                "kept as preload), %.3g s simulated, output every %.3g s\n", case_path.c_str(),
                sw::to_string(p.configuration), m.teeth_flexspline, m.teeth_circular, m.pairs.size(), interfering,
                p.duration_s, p.output_step_s);
    const double c0 = cpu_seconds();
    sw::Stopwatch watch;
    const sw::DynamicsSeries s = sw::simulate(m);
    const double wall = watch.lap(), cpu = cpu_seconds() - c0;
    std::printf("  simulate: wall %.3f s, CPU %.3f s; real-time factor %.4g (simulated / wall); %zu pairs, %ld "
                "integrator steps, %ld RHS, %ld Jacobians, %zu output samples  [target < 10 s: %s]\n",
                wall, cpu, p.duration_s / wall, m.moving ? s.pair_force_N.size() : m.pairs.size(), s.stats.steps, s.stats.rhs_evals, s.stats.jac_evals,
                s.time_s.size(), wall < 10.0 ? "met" : "NOT met");
    std::printf("  target: 0.1 s simulated, all engaged pairs, output at 1e-5 s, < 10 s "
                "(timings on a busy machine are noisy)\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_dynamics: %s\n", e.what());
    return 1;
  }
  return 0;
}
