// `strainwave contact CASE.toml [--fem DIR/result.json]`: the FEM of the flexspline, then the loaded tooth contact on
// its system: how the teeth share the torque and the drive's torque–twist curve from −rated to +rated torque.
#include <cstdio>
#include <stdexcept>
#include <filesystem>
#include <memory>
#include <optional>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "app/contact_job.hpp"
#include "app/fem_job.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "contact/harmonic_body.hpp"
#include "fem/fourier_analysis.hpp"
#include "io/case.hpp"
#include "io/fem_output.hpp"

namespace sw::app {
namespace {

/// What the contact solves on: the FEM's model (the harmonic solution, or the TET10 model factorised), and its
/// readout.
struct ContactFem {
  ContactFem() = default;
  ContactFem(ContactFem&&) = default;  // a move keeps the readout's field pointer: the cases' buffer moves with it
  ContactFem(const ContactFem&) = delete;
  FemJobResult job;     ///< the FEM solved now, or (read back) its model solved again
  FemReadout readout;   ///< of `job`'s solution, or read back
};

/// The refusal of an earlier run's result.json made from another model than the case's.
InputError model_mismatch(const Case& c, const std::filesystem::path& result_json, std::int64_t made_from,
                          std::int64_t gives) {
  return InputError(result_json.string() + ": made from a model of " + std::to_string(made_from) + " equations, " +
                    c.path + " gives " + std::to_string(gives) +
                    "; run `strainwave fem` on this case again or leave out --fem");
}

/// The FEM of an earlier run of the same case (--fem): the model is meshed and factorised again, or its harmonics
/// solved again (the influence coefficients need the factor or the bands' responses, which no file carries), and must
/// have as many equations as that run's; the
/// generator-deformed neutral curve and C_τ are read back instead of solving the load cases again (no field: the
/// face is taken at its centre).
ContactFem fem_from_run(const Case& c, const std::filesystem::path& result_json, double max_memory_gb) {
  const FemRunForContact run = read_fem_run_for_contact(result_json);
  const std::string method = c.solver.method == SolverMethod::Fourier ? "fourier" : "tet10";
  if (run.method != method)
    throw InputError(result_json.string() + ": solved with solver.method = \"" + run.method + "\", " + c.path +
                     " takes \"" + method + "\"; run `strainwave fem` on this case again (or --solver " + run.method +
                     ")");
  ContactFem fem;
  const WaveGeneratorParams& w = *c.wave_generator;
  const std::string model = model_name(w.model);
  if (run.generator_model != model)
    throw InputError(result_json.string() + ": made with generator.model = \"" + run.generator_model + "\", " +
                     c.path + " has \"" + model + "\"; run `strainwave fem` on this case again");
  if (std::holds_alternative<Rollers>(w.model))
    throw InputError(c.path + ": --fem cannot take rollers (their set-out comes from the FEM's generator case); run "
                              "contact without --fem");
  fem.readout.compliance_rad_per_Nm = run.compliance_rad_per_Nm;
  fem.readout.neutral_curve = run.neutral_curve;
  fem.readout.generator_model = model;
  if (c.solver.method == SolverMethod::Fourier) {  // the harmonic pass is seconds: solved again for its bands
    progress("fourier: " + c.path + " (the model of " + result_json.string() + ")");
    const FlexsplineModel m = flexspline_model(c);
    auto harmonic = std::make_shared<FourierSolution>(
        analyse_flexspline_fourier(m, contact_band_request(m, c.contact.face_slices)));
    std::int64_t equations = 0;
    for (const HarmonicStats& h : harmonic->harmonics) equations += h.equations;
    if (equations != run.equations) throw model_mismatch(c, result_json, run.equations, equations);
    if (harmonic->stations) fem.readout.generator_obstacle_m = harmonic->figures.generator->obstacle_m;
    fem.job.harmonic = std::move(harmonic);
    return fem;
  }
  progress("mesh: " + c.path + " (the model of " + result_json.string() + ")");
  auto mesh = std::make_shared<const TetMesh>(mesh_for_case(c, max_memory_gb));
  auto system = std::make_shared<const FlexsplineSystem>(assemble_and_factorise(flexspline_model(c), *mesh));
  if (system->dofs.n_equations != run.equations)
    throw model_mismatch(c, result_json, run.equations, system->dofs.n_equations);
  if (cam_of(w)) fem.readout.generator_obstacle_m = generator_stations(flexspline_model(c), *mesh).obstacle_m;
  fem.job.mesh = mesh;
  fem.job.system = system;
  return fem;
}

/// The FEM solved now, its files written into `out`.
ContactFem fem_solved(const Case& c, OutputSet& out, const FemJobOptions& options) {
  ContactFem fem;
  fem.job = run_fem_job(c, out, options);
  fem.readout = fem_readout(fem.job.solution);
  return fem;
}

}  // namespace

void add_contact_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("contact", "loaded tooth contact: load sharing, the drive's torque-twist curve, "
                                            "lost motion");
  static std::string case_path, out, fem_json, solver, backend;
  static FemJobOptions fem_options;
  cmd->add_option("case", case_path, "case file (TOML)")->required();
  add_fem_job_options(cmd, fem_options);
  cmd->add_option("--fem", fem_json, "result.json of an earlier `fem` run of this case: its neutral curve and C_tau "
                                     "are used and its load cases not solved again (the model is still factorised)");
  cmd->add_option("--out", out, "output directory (default out/<case stem>/)");
  add_solver_options(cmd, solver, backend);
  static ContactJobOptions job;
  cmd->add_option("--accuracy-class", job.accuracy_class,
                  "also the band over drives whose teeth deviate within this ISO 1328-1:2013 tolerance class (1-11)")
      ->check(CLI::Range(1, 11));
  cmd->add_option("--accuracy-drives", job.accuracy_drives, "drives the band draws (default 16)")
      ->check(CLI::Range(2, 1000));
  cmd->callback([] {
    const Case c = load_case_with_solver(case_path, solver, backend);
    naming_file(c.path, [&] { check_contact_model(flexspline_model(c)); });  // before any work: nothing is written for a case contact cannot take
    OutputSet outputs(out.empty() ? default_out_dir(c) : std::filesystem::path(out));
    write_resolved_case(c, outputs);
    const ContactFem fem = fem_json.empty() ? fem_solved(c, outputs, fem_options)
                                            : fem_from_run(c, fem_json, fem_options.max_memory_gb);
    run_contact_job(c, *contact_body(c, fem.job, fem.readout.generator_u), fem.readout, outputs, job);
    outputs.commit();
    std::printf("  wrote %s\n", outputs.dir().string().c_str());
  });
}

}  // namespace sw::app
