// `strainwave contact CASE.toml [--fem DIR/result.json]`: the FEM of the flexspline, then the loaded tooth contact on
// its system: how the teeth share the torque and the drive's torque–twist curve from −rated to +rated torque.
#include <cstdio>
#include <stdexcept>
#include <filesystem>
#include <memory>
#include <optional>

#include "app/commands.hpp"
#include "app/contact_job.hpp"
#include "app/fem_job.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "io/case.hpp"
#include "io/fem_output.hpp"

namespace sw::app {
namespace {

/// What the contact solves on: the TET10 model factorised, and the FEM's readout.
struct ContactFem {
  ContactFem() = default;
  ContactFem(ContactFem&&) = default;  // a move keeps the readout's field pointer: the cases' buffer moves with it
  ContactFem(const ContactFem&) = delete;
  std::shared_ptr<const TetMesh> mesh;
  std::shared_ptr<const FlexsplineSystem> system;
  FemJobResult job;     ///< the FEM solved now (empty when read back)
  FemReadout readout;   ///< of `job`'s solution, or read back
};

/// The FEM of an earlier run of the same case (--fem): the model is meshed and factorised again (the influence
/// coefficients need the factor, which no file carries) and must have as many equations as that run's; the
/// generator-deformed neutral curve and C_τ are read back instead of solving the load cases again (no field: the
/// face is taken at its centre).
ContactFem fem_from_run(const Case& c, const std::filesystem::path& result_json, double max_memory_gb) {
  const FemRunForContact run = read_fem_run_for_contact(result_json);
  const WaveGeneratorParams& w = *c.wave_generator;
  const std::string model = model_name(w.model);
  if (run.generator_model != model)
    throw InputError(result_json.string() + ": made with generator.model = \"" + run.generator_model + "\", " +
                     c.path + " has \"" + model + "\"; run `strainwave fem` on this case again");
  if (std::holds_alternative<Rollers>(w.model))
    throw InputError(c.path + ": --fem cannot take rollers (their set-out comes from the FEM's generator case); run "
                              "contact without --fem");
  progress("mesh: " + c.path + " (the model of " + result_json.string() + ")");
  auto mesh = std::make_shared<const TetMesh>(mesh_for_case(c, max_memory_gb));
  auto system = std::make_shared<const FlexsplineSystem>(assemble_and_factorise(flexspline_model(c), *mesh));
  if (system->dofs.n_equations != run.equations)
    throw InputError(result_json.string() + ": made from a model of " + std::to_string(run.equations) +
                     " equations, " + c.path + " gives " + std::to_string(system->dofs.n_equations) +
                     "; run `strainwave fem` on this case again or leave out --fem");
  ContactFem fem;
  fem.readout.compliance_rad_per_Nm = run.compliance_rad_per_Nm;
  fem.readout.neutral_curve = run.neutral_curve;
  fem.readout.generator_model = model;
  if (cam_of(w)) fem.readout.generator_obstacle_m = generator_stations(flexspline_model(c), *mesh).obstacle_m;
  fem.mesh = mesh;
  fem.system = system;
  return fem;
}

/// The FEM solved now on TET10, its files written into `out`.
ContactFem fem_solved(const Case& c, OutputSet& out, const FemJobOptions& options) {
  ContactFem fem;
  fem.job = run_fem_job(c, out, options);
  if (!fem.job.system || !fem.job.mesh)  // contact_model_gap refuses the cases that leave none
    throw std::logic_error("contact: the FEM job left no factorised TET10 model");
  fem.mesh = fem.job.mesh;
  fem.system = fem.job.system;
  fem.readout = fem_readout(fem.job.solution);
  return fem;
}

}  // namespace

void add_contact_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("contact", "loaded tooth contact: load sharing, the drive's torque-twist curve, "
                                            "lost motion");
  static std::string case_path, out, fem_json;
  static FemJobOptions fem_options;
  cmd->add_option("case", case_path, "case file (TOML)")->required();
  add_fem_job_options(cmd, fem_options);
  cmd->add_option("--fem", fem_json, "result.json of an earlier `fem` run of this case: its neutral curve and C_tau "
                                     "are used and its load cases not solved again (the model is still factorised)");
  cmd->add_option("--out", out, "output directory (default out/<case stem>/)");
  cmd->callback([] {
    Case c = load_case(case_path);
    if (c.solver.method == SolverMethod::Fourier) {  // reported, not dropped silently
      std::printf("note: %s: solver.method = \"fourier\" is not used by contact: the loaded contact reads its "
                  "influence coefficients from the factorised TET10 model, which it solves here\n", c.path.c_str());
      c.solver.method = SolverMethod::Tet10;
    }
    naming_file(c.path, [&] { check_contact_model(flexspline_model(c)); });  // before any work: nothing is written for a case contact cannot take
    progress("case:\n" + describe_case(c));
    OutputSet outputs(out.empty() ? default_out_dir(c) : std::filesystem::path(out));
    const ContactFem fem = fem_json.empty() ? fem_solved(c, outputs, fem_options)
                                            : fem_from_run(c, fem_json, fem_options.max_memory_gb);
    run_contact_job(c, *fem.mesh, *fem.system, fem.readout, outputs);
    outputs.commit();
    std::printf("  wrote %s\n", outputs.dir().string().c_str());
  });
}

}  // namespace sw::app
