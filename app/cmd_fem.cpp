// `strainwave fem CASE.toml`: mesh the flexspline, solve every load case on one factorisation, write result.json,
// neutral_curve.csv and the VTK files; `strainwave run` chains fem and backlash.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/fem_job.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/petsc_solver.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "io/fem_output.hpp"
#include "io/inp.hpp"
#include "mesh/estimate.hpp"
#include "mesh/flexspline.hpp"

namespace sw::app {

namespace fs = std::filesystem;

fs::path default_out_dir(const Case& c) { return fs::path("out") / c.stem; }

std::string case_headline(const Case& c) {
  const std::string derived = describe_derived(c);
  return "case " + c.path + " (resolved, every key with its default: resolved_case.toml in the output folder)" +
         (derived.empty() ? "" : "; values not in the file:\n" + derived.substr(0, derived.size() - 1));
}

void write_resolved_case(const Case& c, OutputSet& out) {
  out.own({"resolved_case.toml"});
  write_file_atomic(out.staging() / "resolved_case.toml", describe_case(c));
}

void add_fem_job_options(CLI::App* cmd, FemJobOptions& o) {
  cmd->add_flag("--no-vtk", [&o](std::int64_t) { o.write_vtk = false; },
                "leave out flexspline.pvd and the .vtu files (an earlier run's go with the new set)");
  cmd->add_option_function<std::string>(
      "--export-inp", [&o](const std::string& f) { o.export_inp = f; },
      "also write the mesh, clamp and torque loads as a CalculiX/Abaqus deck (C3D10); the generator's contact is not "
      "in the deck");
  cmd->add_option("--max-memory", o.max_memory_gb, "refuse a model whose estimated peak exceeds this (GB; "
                                                   "default: the machine's available memory)")
      ->check(CLI::PositiveNumber);
}

TetMesh mesh_for_case(const Case& c, double max_memory_gb) {
  // Seconds, not minutes: refused from the geometry before TetGen runs.
  // The petsc backend spreads the factor over its ranks' machines: the budget is one machine's times their number.
  const int machines = c.solver.backend == SolverBackend::Petsc ? parallel::nodes() : 1;
  const double per_machine = max_memory_gb > 0 ? max_memory_gb * 1e9 : machines > 1 ? available_memory_bytes() : 0.0;
  refuse_if_too_large(estimate_model_size(c.flexspline, c.gear, c.mesh), per_machine * machines, c.path);
  return mesh_flexspline(c.flexspline, c.gear, c.mesh);
}

void take_tet10_under_auto(Case& c, const std::string& why) {
  if (!c.derived_from.count("solver.method")) return;
  c.solver.method = SolverMethod::Tet10;
  c.derived_from["solver.method"] = "\"auto\": " + why;
}

void apply_solver_option(Case& c, const std::string& solver, const std::string& backend) {
  if (!backend.empty()) c.solver.backend = backend == "petsc" ? SolverBackend::Petsc : SolverBackend::Cholmod;
  if (!solver.empty()) {
    c.solver.method = solver == "fourier" ? SolverMethod::Fourier : SolverMethod::Tet10;
    c.derived_from.erase("solver.method");
  } else if (backend == "petsc") {
    take_tet10_under_auto(c, "the petsc backend solves the TET10 model");
  }
  if (solver.empty() && backend.empty()) return;
  if (c.solver.method == SolverMethod::Fourier && c.flexspline.teeth == TeethModel::Explicit)
    throw InputError(c.path + ": --solver fourier needs a body of revolution; flexspline.teeth = \"explicit\" is not "
                              "one (use teeth = \"ring\" or \"none\", or --solver tet10)");
  if (c.solver.method == SolverMethod::Tet10 && c.flexspline.teeth == TeethModel::Layer)
    throw InputError(c.path + ": --solver tet10 meshes the teeth as solids or a ring; flexspline.teeth = \"layer\" is "
                              "the harmonic solver's (use --solver fourier, or teeth = \"explicit\")");
  if (c.solver.method == SolverMethod::Fourier && c.solver.backend == SolverBackend::Petsc)
    throw InputError(c.path + ": the petsc backend solves the TET10 model; the fourier solver runs in one process "
                              "(use --solver tet10, or --backend cholmod)");
}

void add_solver_options(CLI::App* cmd, std::string& solver, std::string& backend) {
  cmd->add_option("--solver", solver, "tet10 | fourier (overrides [solver] method)")
      ->check(CLI::IsMember({"tet10", "fourier"}));
  add_backend_option(cmd, backend);
}

Case load_case_with_solver(const std::string& path, const std::string& solver, const std::string& backend,
                           const std::string& tet10_needed_for) {
  Case c = load_case(path);
  apply_solver_option(c, solver, backend);
  if (solver.empty() && !tet10_needed_for.empty()) take_tet10_under_auto(c, tet10_needed_for);
  progress(case_headline(c));
  return c;
}

void add_backend_option(CLI::App* cmd, std::string& backend) {
  cmd->add_option("--backend", backend,
                  "cholmod | petsc (overrides [solver] backend); petsc under mpirun -np N distributes the TET10 solve, "
                  "PETSc options (-ksp_type cg -pc_type gamg, -mat_mumps_icntl_14 50, ...) go last on the line")
      ->check(CLI::IsMember({"cholmod", "petsc"}));
}

namespace {

/// The BLAS CHOLMOD runs on, with a warning when it is the reference one.
BlasInfo blas_for_the_factor() {
  BlasInfo blas = detect_blas();
  progress("BLAS: " + blas.description);
  if (blas.is_reference)
    std::fprintf(stderr,
                 "strainwave: warning: CHOLMOD runs on the reference BLAS (%s), which is 10-50x slower; install "
                 "libopenblas0-pthread (scripts/setup.sh does)\n",
                 blas.description.c_str());
  return blas;
}

/// The VTK files, the CalculiX deck (--export-inp) and neutral_curve.csv.
void write_fem_files(const Case& c, const OutputSet& out, const FemJobOptions& options,
                     const FlexsplineModel& model, const TetMesh& mesh, const FlexsplineSolution& s) {
  progress("output: " + out.dir().string());
  if (options.write_vtk) write_fem_vtk(out.staging(), mesh, s.cases);
  if (options.export_inp) {
    write_inp_deck(*options.export_inp, c, mesh, clamped_nodes(mesh), torque_load_vector(model, mesh, c.load.torque_Nm),
                   "fem --export-inp (clamp and torque only; no generator)");
    progress("deck: " + options.export_inp->string());
  }
  if (s.neutral_curve) write_file_atomic(out.staging() / "neutral_curve.csv", neutral_curve_csv(*s.neutral_curve));
}

/// The model's size and cost, φ₀ against the closed form, the torque balance.
void print_fem_headline(const Case& c, const TetMesh& mesh, const FlexsplineSolution& s, const RunInfo& run) {
  const FactorStats& factor = s.timings.factor;
  std::printf("fem %s: %zu nodes, %lld equations, factor %.2f GF in %.2f s (%.1f GF/s), total %.1f s, peak %.0f MB\n",
              c.path.c_str(), mesh.n_nodes(), static_cast<long long>(factor.equations), factor.factor_gflop,
              factor.factor_s, factor.factor_s > 0 ? factor.factor_gflop / factor.factor_s : 0.0, run.total_s,
              run.peak_rss_bytes / 1e6);
  const auto& th = s.checks.phi0_theory_cup;
  std::printf("  phi0 = %.6e rad at T = %g N·m (C_tau = %.6e rad/N·m), over the engagement zones %.6e rad\n",
              s.phi0_rad, s.torque_Nm, s.compliance_rad_per_Nm, s.phi0_engaged_rad);
  std::printf("  closed form %.6e rad (FEM/closed form %.4f) = diaphragm %.4e (annular plate %.2f..%.2f mm) + body wall "
              "%.4e (%.2f mm) + rim %.4e (%.2f mm); body wall alone T·L/(G·J) %.6e rad\n",
              th.total_rad(), th.total_rad() != 0 ? s.phi0_rad / th.total_rad() : 0.0, th.diaphragm_rad,
              th.diaphragm_inner_radius_m * 1e3, th.diaphragm_outer_radius_m * 1e3, th.body_rad,
              th.body_length_m * 1e3, th.rim_rad, th.rim_length_m * 1e3, s.checks.phi0_theory_rad);
  std::printf("  reaction torque %.9g N·m (clamp and generator) vs applied %.9g N·m\n", s.checks.reaction_torque_Nm,
              s.checks.applied_torque_Nm);
}

/// What the generator does: its forces and zones, the rim's shape, the bearing, the hoop stress it causes.
void print_generator(const FlexsplineSolution& s) {
  const auto& g = *s.generator;
  std::string zones;
  for (const auto& [from, to] : g.zones_wg_deg) {
    char z[64];
    std::snprintf(z, sizeof z, "%s[%.0f, %.0f]", zones.empty() ? "" : " ", from, to);
    zones += z;
  }
  std::printf("  generator (%s, %s): total radial force %.1f N, smallest contact force %.3g N, zones (deg from "
              "the major axis) %s\n",
              g.model.c_str(), g.unilateral ? "unilateral contact" : "the paper's given forces",
              g.total_radial_force_N, g.min_contact_force_N, zones.c_str());
  std::printf("  generator: w at the major axis %.4f mm, at the minor axis %.4f mm, net rim rotation %.2e rad; "
              "it carries %.4g N·m of the torque\n",
              g.w_major_m * 1e3, g.w_minor_m * 1e3, s.checks.generator_rotation_rad, g.reaction_torque_Nm);
  if (g.bearing_max_ball_load_N > 0)
    std::printf("  generator bearing in series: largest ball load %.0f N, its Hertzian approach %.2f um\n",
                g.bearing_max_ball_load_N, g.bearing_max_approach_m * 1e6);
  std::printf("  hoop stress (generator): nominal bending %+.1f MPa at the minor axis, z = %.1f mm (thin ring theory "
              "%+.1f MPa), membrane %+.1f MPa; local peaks %+.1f MPa at %.0f deg, z = %.2f mm and %+.1f MPa at "
              "%.0f deg, z = %.2f mm\n",
              s.hoop.nominal_bending_Pa / 1e6, s.hoop.profile_z_m * 1e3, s.hoop.ring_theory_bending_Pa / 1e6,
              s.hoop.nominal_membrane_Pa / 1e6, s.hoop.max_tensile_Pa / 1e6, s.hoop.max_tensile_angle_deg,
              s.hoop.max_tensile_z_m * 1e3, s.hoop.max_compressive_Pa / 1e6, s.hoop.max_compressive_angle_deg,
              s.hoop.max_compressive_z_m * 1e3);
}

/// The hoop stress around the rim and the fatigue of its worst points.
void print_hoop_profile_and_fatigue(const FlexsplineSolution& s) {
  if (!s.hoop.inner_Pa.empty())
    std::printf("  hoop stress at z = %.1f mm (%s case), inner/outer wall, MPa: 0 deg %+.0f/%+.0f, 30 deg %+.0f/%+.0f, "
                "45 deg %+.0f/%+.0f, 90 deg %+.0f/%+.0f\n",
                s.hoop.profile_z_m * 1e3, s.cases.front().name.c_str(), s.hoop.inner_Pa[0] / 1e6,
                s.hoop.outer_Pa[0] / 1e6, s.hoop.inner_Pa[30] / 1e6, s.hoop.outer_Pa[30] / 1e6,
                s.hoop.inner_Pa[45] / 1e6, s.hoop.outer_Pa[45] / 1e6, s.hoop.inner_Pa[90] / 1e6,
                s.hoop.outer_Pa[90] / 1e6);
  if (!s.fatigue) return;
  std::vector<const FatiguePoint*> points{&s.fatigue->rim};
  if (s.fatigue->diaphragm) points.push_back(&*s.fatigue->diaphragm);
  for (const FatiguePoint* p : points) {
    std::printf("  fatigue over a generator revolution (%s case), %s at r = %.2f mm, z = %.2f mm: hoop %.1f ± %.1f "
                "MPa, meridional %.1f ± %.1f MPa",
                s.cases.back().name.c_str(), p->place.c_str(), p->r_m * 1e3, p->z_m * 1e3, p->hoop.mean_Pa / 1e6,
                p->hoop.alternating_Pa / 1e6, p->meridional.mean_Pa / 1e6, p->meridional.alternating_Pa / 1e6);
    if (p->safety_factor > 0) std::printf(", Goodman safety factor %.2f", p->safety_factor);
    std::printf("\n");
  }
}

}  // namespace

FemJobResult run_fem_job(const Case& c, OutputSet& out, const FemJobOptions& options) {
  out.own(kFemJobFiles);
  if (c.solver.method == SolverMethod::Fourier) {
    if (options.export_inp)
      throw InputError("--export-inp writes a TET10 deck; it needs [solver] method = \"tet10\" (or --solver tet10)");
    return run_fourier_fem_job(c, out, options.write_vtk, options.max_memory_gb);
  }
  const double t_start = elapsed_s();
  RunInfo run;
  run.blas = blas_for_the_factor();
  Stopwatch clock;
  progress("mesh: " + c.path);
  const auto mesh_ptr = std::make_shared<const TetMesh>(mesh_for_case(c, options.max_memory_gb));
  const TetMesh& mesh = *mesh_ptr;
  run.mesh_s = clock.lap();
  progress("mesh: " + std::to_string(mesh.n_nodes()) + " nodes, " + std::to_string(mesh.tets.size()) +
           " TET10, min dihedral " + std::to_string(mesh.quality.min_dihedral_deg) + " deg");
  FemJobResult job;
  const FlexsplineModel model = flexspline_model(c);
  auto system = std::make_shared<const FlexsplineSystem>(assemble_and_factorise(model, mesh));
  job.solution = analyse_flexspline(model, mesh, *system);
  job.mesh = mesh_ptr;
  job.system = system;
  clock.lap();
  write_fem_files(c, out, options, model, mesh, job.solution);
  run.output_s = clock.lap();
  run.total_s = elapsed_s() - t_start;
  run.peak_rss_bytes = peak_rss_bytes();
  job.result_json_path = out.dir() / "result.json";
  write_file_atomic(out.staging() / "result.json", fem_result_json(fem_result(c, mesh, job.solution, run)));
  print_fem_headline(c, mesh, job.solution, run);
  if (job.solution.generator) print_generator(job.solution);
  print_hoop_profile_and_fatigue(job.solution);
  return job;
}

void add_fem_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("fem", "mesh the flexspline, solve every load case, extract phi0 and C_tau");
  static std::string case_path, out, solver, backend;
  static FemJobOptions options;
  cmd->add_option("case", case_path, "case file (TOML)")->required();
  add_fem_job_options(cmd, options);
  cmd->add_option("--out", out, "output directory (default out/<case stem>/)");
  add_solver_options(cmd, solver, backend);
  cmd->callback([] {
    const Case c =
        load_case_with_solver(case_path, solver, backend, options.export_inp ? "--export-inp writes a TET10 deck" : "");
    OutputSet outputs(out.empty() ? default_out_dir(c) : fs::path(out));
    write_resolved_case(c, outputs);
    run_fem_job(c, outputs, options);
    outputs.commit();
    std::printf("  wrote %s\n", outputs.dir().string().c_str());
  });
}

}  // namespace sw::app
