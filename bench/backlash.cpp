// bench_backlash — performance target: a full wave-generator revolution at 0.1° steps (3600 steps) over all
// engaged tooth pairs, both flanks, must take < 1 s on this machine.
//
// Builds the backlash model as `strainwave backlash` does (app/cmd_backlash.cpp: generator_neutral_curve on
// rim_mean_radius, make_backlash_model) and times, with wall and process CPU clocks:
//   1. sweep_revolution(model, phi0, steps): what the app runs; it solves each distinct generator position once
//      (the pair set repeats every circular-spline pitch 2π/z_c) — this is the figure the target is about;
//   2. a brute-force revolution: pair_clearances() at every one of the steps, no periodicity shortcut (the cost of
//      solving every step; only with --brute, it takes ~50x longer).
// Prints steps, distinct positions, engaged pairs per step, pairs evaluated (each = both flanks solved to 1e-12 m)
// and the target. Printed figures only, never asserted.
//
//   build-bench/bench/bench_backlash                              # cases/seed_190_192.toml, 3600 steps, phi0 = 0
//   build-bench/bench/bench_backlash cases/cup_size17.toml --steps 3600 --phi0 1e-4 --brute
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <numbers>
#include <set>
#include <string>

#include <CLI/CLI.hpp>

#include "common/error.hpp"
#include "common/progress.hpp"
#include "io/case.hpp"
#include "kinematics/backlash.hpp"
#include "kinematics/neutral_curve.hpp"

#ifndef SW_SOURCE_DIR
#define SW_SOURCE_DIR "."
#endif

namespace {
constexpr double kPi = std::numbers::pi;
/// Process CPU time (all threads), seconds.
double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_backlash: time a wave-generator revolution of the backlash model"};
  std::string case_path = std::string(SW_SOURCE_DIR) + "/cases/seed_190_192.toml";
  int steps = 3600;
  double phi0 = 0.0;
  bool brute = false;
  app.add_option("case", case_path, "case file (TOML) with [gear] and wave_generator.radial_deformation_mm");
  app.add_option("--steps", steps, "wave-generator steps per revolution (3600 = 0.1 deg)")->check(CLI::Range(1, 10000000));
  app.add_option("--phi0", phi0, "flexspline wind-up, rad");
  app.add_flag("--brute", brute, "also time the brute-force revolution (every step solved; ~30 s on this machine)");
  CLI11_PARSE(app, argc, argv);
  try {
    sw::quiet_progress() = true;
    const sw::Case c = sw::load_case(case_path);
    if (!c.gear) throw sw::InputError(case_path + ": [gear] is missing");
    if (!c.wave_generator || !c.wave_generator->radial_deformation_m)
      throw sw::InputError(case_path + ": wave_generator.radial_deformation_mm is missing");
    const double rm = sw::rim_mean_radius(c.flexspline);
    const sw::NeutralCurve curve = sw::generator_neutral_curve(rm, *c.wave_generator->radial_deformation_m, *c.wave_generator);
    const sw::BacklashModel m = sw::make_backlash_model(*c.gear, curve);
    std::printf("bench_backlash %s: %d/%d teeth, %s, r_m = %.4f mm, phi0 = %.3e rad, %d steps (%.4g deg)\n",
                case_path.c_str(), c.gear->teeth_flexspline, c.gear->teeth_circular, curve.source.c_str(), rm * 1e3,
                phi0, steps, 360.0 / steps);

    double c0 = cpu_seconds();
    sw::Stopwatch watch;
    const sw::RevolutionSweep s = sw::sweep_revolution(m, phi0, steps);
    double wall = watch.lap(), cpu = cpu_seconds() - c0;
    // Pairs the sweep solved: the engaged pairs at each distinct position, the residues of the generator angle
    // modulo 2π/z_c exactly as sweep_revolution keys them (counted outside the timing).
    long swept_pairs = 0;
    {
      const double period = 2.0 * kPi / c.gear->teeth_circular;
      std::set<long long> seen;
      for (int i = 0; i < steps; ++i) {
        double r = std::fmod(2.0 * kPi * i / steps, period);
        if (period - r < 1e-12) r = 0.0;
        if (seen.insert(std::llround(r * 1e12)).second)
          swept_pairs += static_cast<long>(sw::pair_clearances(m, r, phi0, true).size());
      }
    }
    std::printf("  sweep_revolution : wall %.3f s, CPU %.3f s; %d steps, %d distinct positions, %d..%d engaged pairs "
                "per step, %ld pairs evaluated (both flanks); min backlash %.4f um at %.2f deg  [target < 1 s: %s]\n",
                wall, cpu, steps, s.distinct_positions, s.engaged_pairs_min, s.engaged_pairs_max, swept_pairs,
                s.min_m * 1e6, s.min_at_rad * 180.0 / kPi, wall < 1.0 ? "met" : "NOT met");

    if (brute) {
      long pairs = 0;
      double best = 1e300;
      c0 = cpu_seconds();
      watch.lap();
      for (int i = 0; i < steps; ++i) {
        for (const auto& p : sw::pair_clearances(m, 2.0 * kPi * i / steps, phi0, true)) {
          ++pairs;
          best = std::min(best, p.backlash_m());
        }
      }
      wall = watch.lap();
      cpu = cpu_seconds() - c0;
      std::printf("  every step solved: wall %.3f s, CPU %.3f s; %d steps, %ld pairs evaluated (both flanks), "
                  "%.2f us per pair; min backlash %.4f um  [target < 1 s: %s]\n",
                  wall, cpu, steps, pairs, pairs ? 1e6 * wall / pairs : 0.0, best * 1e6, wall < 1.0 ? "met" : "NOT met");
    }
    std::printf("  target: a full revolution at 0.1 deg over all engaged pairs, both flanks, < 1 s "
                "(timings on a busy machine are noisy)\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_backlash: %s\n", e.what());
    return 1;
  }
  return 0;
}
