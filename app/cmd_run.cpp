// `strainwave run CASE.toml [--curve fem|generator]`: the main job. fem (φ₀, C_τ, neutral curve) then backlash fed
// with that φ₀ and, by default, the FEM's own generator-deformed neutral curve; both sets of files under one folder.
#include <filesystem>

#include "app/backlash_job.hpp"
#include "app/commands.hpp"
#include "app/fem_job.hpp"
#include "common/progress.hpp"
#include "io/case.hpp"

namespace sw::app {

void add_run_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("run", "fem then backlash fed with its phi0: the main job");
  static std::string case_path, out, solver, curve = "fem";
  cmd->add_option("case", case_path, "case file (TOML)")->required();
  cmd->add_option("--curve", curve,
                  "neutral curve for the backlash: fem (the FEM's generator-deformed rim, default) or generator "
                  "(the generator model's thin-ring/cam curve)")
      ->check(CLI::IsMember({"generator", "fem"}));
  cmd->add_option("--out", out, "output directory (default out/<case stem>/)");
  cmd->add_option("--solver", solver, "tet10 | fourier (overrides [solver] method)")
      ->check(CLI::IsMember({"tet10", "fourier"}));
  cmd->callback([] {
    Case c = load_case(case_path);
    apply_solver_option(c, solver);
    progress("case:\n" + describe_case(c));
    const std::filesystem::path dir = out.empty() ? default_out_dir(c) : std::filesystem::path(out);
    const FemJobResult fem = run_fem_job(c, dir);
    if (!c.gear || !c.wave_generator) {
      std::printf("run: no backlash for this case (it needs [gear] and [wave_generator])\n");
      return;
    }
    BacklashJobOptions options;
    options.fem_result = fem.result_json_path;
    options.fem_curve = curve == "fem";
    run_backlash_job(c, options, dir);
  });
}

}  // namespace sw::app
