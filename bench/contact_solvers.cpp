// bench_contact_solvers: the loaded contact end to end on both models of the flexspline, side by side in one run.
//   1. DGEMM rate of the loaded BLAS (the limit for the TET10 factor).
//   2. `strainwave contact CASE --solver fourier` and `--solver tet10` for each case (default: the seed cup and
//      cup_size17): wall clock of the whole command, and the answers beside each other (twist at T1, T2 and rated
//      torque, K1..K3 at the same breakpoints, the largest flank force at rated and the flank forces' largest
//      difference over it, the generator's station forces at rated).
//   3. `strainwave run` on the seed cup (the harmonic path: fem, backlash, contact).
//   4. The frictional loop's cost on cup_size17, as designed (straight teeth in three face sections, a little play) and
//      preloaded (its circular spline cut for the face's centre, which the coning presses), at μ = 0.05 and 0.1:
//      the loop's own wall clock at the default steps a quarter beside the frictionless curve's contact stage, in one
//      process on one harmonic pass (target: within 5×).
//   5. A drive sweep (`sweep --contact`) of --sweep-points designs of cup_size17 (its rim thickness ±20 %).
// `--friction` runs only 4. and the loop's step study on cup_size17 (both variants, μ = 0.05 and 0.1, 5 to 80 steps a
// quarter). Each command is a child process; wall clock, so say so when the machine was shared.
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/contact_job.hpp"
#include "bench_util.hpp"
#include "common/progress.hpp"
#include "contact/harmonic_body.hpp"
#include "contact/loaded_contact.hpp"
#include "dgemm.hpp"
#include "fem/fourier_analysis.hpp"
#include "fem/fourier_solver.hpp"
#include "io/case.hpp"

namespace {

namespace fs = std::filesystem;
constexpr double kArcmin = 10800.0 / 3.141592653589793;

/// Runs `strainwave ARGS` quietly; its wall clock (s). Throws when it fails.
double timed(const std::string& args) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string cmd = std::string(SW_STRAINWAVE_BINARY) + " " + args + " --quiet > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  if (rc != 0) throw std::runtime_error("failed (" + std::to_string(WEXITSTATUS(rc)) + "): " + cmd);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

/// Twist (rad) of a contact.json curve at torque T (linear between its points).
double twist_at(const nlohmann::json& k, double T) {
  const auto& c = k["torque_twist"];
  for (std::size_t i = 1; i < c.size(); ++i) {
    const double t0 = c[i - 1]["torque_Nm"], t1 = c[i]["torque_Nm"];
    if (T >= t0 && T <= t1 && t1 > t0)
      return c[i - 1]["twist_rad"].get<double>() +
             (T - t0) / (t1 - t0) * (c[i]["twist_rad"].get<double>() - c[i - 1]["twist_rad"].get<double>());
  }
  return NAN;
}

/// K1..K3 of a curve at breakpoints T1, T2 and rated torque TR (the catalog's three secant segments).
std::array<double, 3> stiffness(const nlohmann::json& k, double T1, double T2, double TR) {
  const double p1 = twist_at(k, T1), p2 = twist_at(k, T2), p3 = twist_at(k, TR);
  return {T1 / p1, (T2 - T1) / (p2 - p1), (TR - T2) / (p3 - p2)};
}

/// The largest flank force at +rated, and the largest difference of the two runs' flank forces (same flanks by tooth,
/// flank and slice) over it.
std::pair<double, double> flank_forces(const nlohmann::json& a, const nlohmann::json& b) {
  double largest = 0, diff = 0;
  for (const auto& f : b["flanks"]) largest = std::max(largest, f["force_at_plus_rated_N"].get<double>());
  for (const auto& f : a["flanks"])
    for (const auto& g : b["flanks"])
      if (f["tooth"] == g["tooth"] && f["flank"] == g["flank"] && f["slice"] == g["slice"])
        diff = std::max(diff, std::abs(f["force_at_plus_rated_N"].get<double>() -
                                       g["force_at_plus_rated_N"].get<double>()));
  return {largest, diff};
}

void compare(const std::string& case_path, const fs::path& dir) {
  const std::string stem = fs::path(case_path).stem().string();
  const fs::path hf = dir / (stem + "_fourier"), ht = dir / (stem + "_tet10");
  const double t_f = timed("contact " + case_path + " --solver fourier --no-vtk --out " + hf.string());
  const double t_t = timed("contact " + case_path + " --solver tet10 --no-vtk --out " + ht.string());
  const nlohmann::json f = read_json(hf / "contact.json"), t = read_json(ht / "contact.json");
  const double T1 = t["catalog"]["T1_Nm"], T2 = t["catalog"]["T2_Nm"], TR = t["rated_torque_Nm"];
  std::printf("%s: contact end to end fourier %.2f s, tet10 %.2f s (%.1fx)\n", case_path.c_str(), t_f, t_t, t_t / t_f);
  std::printf("  %-28s %12s %12s %9s\n", "", "fourier", "tet10", "diff");
  for (const auto& [name, T] : {std::pair<const char*, double>{"twist at T1 (arcmin)", T1}, {"twist at T2", T2},
                                {"twist at rated", TR}}) {
    const double a = twist_at(f, T) * kArcmin, b = twist_at(t, T) * kArcmin;
    std::printf("  %-28s %12.4f %12.4f %+8.2f%%\n", name, a, b, 100 * (a / b - 1));
  }
  const auto kf = stiffness(f, T1, T2, TR), kt = stiffness(t, T1, T2, TR);
  for (int i = 0; i < 3; ++i)
    std::printf("  K%d at T1 %.3g, T2 %.3g (N·m/rad) %10.4g %12.4g %+8.2f%%\n", i + 1, T1, T2, kf[i], kt[i],
                100 * (kf[i] / kt[i] - 1));
  const auto [largest, diff] = flank_forces(f, t);
  std::printf("  flank forces at rated: largest %.1f N, the runs' largest difference %.2f N (%.2f %% of it)\n", largest,
              diff, 100 * diff / largest);
  std::printf("  play %.4f vs %.4f arcmin, lost motion %.4f vs %.4f arcmin, split body %.3f vs %.3f\n",
              f["play_arcmin"].get<double>(), t["play_arcmin"].get<double>(), f["lost_motion_arcmin"].get<double>(),
              t["lost_motion_arcmin"].get<double>(), f["compliance_split"]["body"].get<double>(),
              t["compliance_split"]["body"].get<double>());
}

/// A case solved once on the harmonic path, with its series parts, for loaded contacts of any friction and loop steps.
struct SolvedCase {
  sw::Case c;
  sw::FlexsplineModel m;
  sw::FourierSolution fourier;
  sw::SeriesParts series;
};

/// The case as it is, or with its circular spline cut for the face's centre alone (`centre_cut`: x_c − x_f = 0.0328,
/// the designed size 17's cut before its teeth were straight in three sections), which the cup's coning then preloads
/// at the face's ends: no play.
SolvedCase solve_case(const std::string& path, bool centre_cut) {
  SolvedCase s;
  s.c = sw::load_case(path);
  if (centre_cut) s.c.gear->profile_shift_circular = s.c.gear->profile_shift_flexspline + 0.03277929;
  s.m = sw::flexspline_model(s.c);
  s.fourier = sw::analyse_flexspline_fourier(s.m, sw::contact_band_request(s.m, s.c.contact.face_slices));
  s.series = sw::app::series_parts(s.c);
  return s;
}

sw::ContactAnalysis contact_of(const SolvedCase& s, double mu, int loop_steps) {
  sw::ContactOptions o;
  o.rated_torque_Nm = s.c.load.rated_torque_Nm.value_or(s.c.load.torque_Nm);
  o.series = s.series;
  o.contact.face_slices = s.c.contact.face_slices;
  o.contact.friction_coefficient = mu;
  o.loop_steps_per_quarter = loop_steps;
  return sw::analyse_contact(s.m, sw::HarmonicBody(s.m, s.fourier), sw::fem_readout(s.fourier.figures), o);
}

/// The loop's twist at +rated torque (its top).
double twist_at_rated(const sw::FrictionLoop& f) {
  double psi = NAN;
  for (const sw::TorqueStep& s : f.steps)
    if (s.branch == "loading") psi = s.twist_rad;  // the loading branch ends at +rated
  return psi;
}

/// The frictional loop's cost against the frictionless curve's, in one process on one harmonic pass: the contact
/// stage at μ = 0 (the curve, its readings and checks), and at μ = 0.05 and 0.1 the loop's own wall clock at the
/// default steps a quarter, with its figures; each time the best of three runs. The target: the loop within 5× the
/// frictionless curve's stage.
void friction_cost(const SolvedCase& s, const std::string& label) {
  constexpr int kRuns = 3;
  double t0 = INFINITY;
  for (int r = 0; r < kRuns; ++r) t0 = std::min(t0, contact_of(s, 0.0, 1).contact_s);
  const int N = sw::ContactOptions{}.loop_steps_per_quarter;
  for (const double mu : {0.05, 0.1}) {
    sw::FrictionLoop f = *contact_of(s, mu, N).friction;
    for (int r = 1; r < kRuns; ++r) f.seconds = std::min(f.seconds, contact_of(s, mu, N).friction->seconds);
    std::printf("%s, mu %.2f: frictionless curve's stage %.3f s, the loop %.3f s (%.1fx; target 5x): %d cycles x %d "
                "steps a quarter, hysteresis loss %.4f arcmin, area %.4e J, friction work %.4e J, lost motion %.3f "
                "arcmin\n", label.c_str(), mu, t0, f.seconds, f.seconds / t0, f.cycles, f.steps_per_quarter,
                f.hysteresis_loss_rad * kArcmin, f.dissipated_energy_J, f.friction_work_J, f.lost_motion_rad * kArcmin);
  }
}

/// The loop's step study on a case: at μ = 0.05 and 0.1 the steady loop at 5, 10, 20, 40 and 80 steps a quarter, its
/// figures and their differences from the finest level's, and the loop's wall clock.
void loop_step_study(const SolvedCase& s, const std::string& label) {
  for (const double mu : {0.05, 0.1}) {
    std::vector<sw::FrictionLoop> levels;
    for (const int N : {5, 10, 20, 40, 80}) levels.push_back(*contact_of(s, mu, N).friction);
    const sw::FrictionLoop& fine = levels.back();
    std::printf("%s, mu %.2f: steps, cycles, loss (arcmin), area (J), friction work (J), area/work - 1, lost motion "
                "(arcmin), twist at rated (arcmin), widest width (arcmin) at (N m); in () the change from %d steps; the "
                "loop's time\n", label.c_str(), mu, fine.steps_per_quarter);
    const auto rel = [](double a, double b) { return b != 0 ? 100 * (a / b - 1) : 0.0; };
    for (const sw::FrictionLoop& f : levels)
      std::printf("  %3d %d  %.5f (%+.2f %%)  %.5e (%+.2f %%)  %.5e (%+.2f %%)  %+.2f %%  %.4f (%+.2f %%)  "
                  "%.4f (%+.3f %%)  %.4f (%+.2f %%) at %.4g  %.3f s\n", f.steps_per_quarter, f.cycles, f.hysteresis_loss_rad * kArcmin,
                  rel(f.hysteresis_loss_rad, fine.hysteresis_loss_rad), f.dissipated_energy_J,
                  rel(f.dissipated_energy_J, fine.dissipated_energy_J), f.friction_work_J,
                  rel(f.friction_work_J, fine.friction_work_J), rel(f.dissipated_energy_J, f.friction_work_J),
                  f.lost_motion_rad * kArcmin, rel(f.lost_motion_rad, fine.lost_motion_rad),
                  twist_at_rated(f) * kArcmin, rel(twist_at_rated(f), twist_at_rated(fine)),
                  f.widest.width_rad * kArcmin, rel(f.widest.width_rad, fine.widest.width_rad), f.widest.torque_Nm,
                  f.seconds);
  }
}

/// The friction loop's cost (and its step study) on cup_size17 as designed (a little play) and preloaded (cut for the
/// face's centre).
void friction_loops(bool step_study) {
  for (const bool centre_cut : {false, true}) {
    const SolvedCase s = solve_case("cases/cup_size17.toml", centre_cut);
    const std::string label =
        std::string("cases/cup_size17.toml (") + (centre_cut ? "cut for the face's centre: preloaded" : "as designed") + ")";
    friction_cost(s, label);
    if (step_study) loop_step_study(s, label);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_contact_solvers: the loaded contact on the harmonic solver and on TET10, side by side"};
  std::vector<std::string> cases = {"cases/seed_190_192.toml", "cases/cup_size17.toml"};
  int sweep_points = 20;
  bool friction_only = false;
  app.add_option("cases", cases, "case files (TOML)");
  app.add_option("--sweep-points", sweep_points, "designs in the drive sweep (0: none)");
  app.add_flag("--friction", friction_only, "only the friction loop on cup_size17 (as designed, and preloaded by a cut "
               "for the face's centre): its cost beside the frictionless curve's, then its step study");
  CLI11_PARSE(app, argc, argv);
  try {
    sw::quiet_progress() = true;
    if (friction_only) {
      friction_loops(true);
      return 0;
    }
    std::printf("DGEMM (n = 2000): %.1f GF/s\n", sw::bench::dgemm_gflops(2000, 3));
    sw::bench::TempDir dir("bench_contact_solvers_");
    for (const std::string& c : cases) compare(c, dir.path());
    friction_loops(false);
    std::printf("run cases/seed_190_192.toml (fourier: fem, backlash, contact): %.2f s\n",
                timed("run cases/seed_190_192.toml --out " + (dir.path() / "run").string()));
    if (sweep_points > 0) {
      const std::string set = "flexspline.rim_thickness_mm=0.484:0.726:" + std::to_string(sweep_points);
      std::printf("sweep --contact of %d designs (cup_size17, %s): %.1f s\n", sweep_points, set.c_str(),
                  timed("sweep cases/cup_size17.toml --contact --set " + set + " --out " +
                        (dir.path() / "sweep").string()));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_contact_solvers: %s\n", e.what());
    return 1;
  }
  return 0;
}
