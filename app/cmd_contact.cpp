// `strainwave contact CASE.toml`: the FEM of the flexspline, then the loaded tooth contact on its system: how the
// teeth share the torque and the drive's torque–twist curve from −rated to +rated torque.
#include <filesystem>

#include "app/commands.hpp"
#include "app/contact_job.hpp"
#include "app/fem_job.hpp"
#include "common/progress.hpp"
#include "io/case.hpp"

namespace sw::app {

void add_contact_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("contact", "loaded tooth contact: load sharing, the drive's torque-twist curve, "
                                            "lost motion");
  static std::string case_path, out;
  static FemJobOptions fem_options;
  cmd->add_option("case", case_path, "case file (TOML)")->required();
  add_fem_job_options(cmd, fem_options);
  cmd->add_option("--out", out, "output directory (default out/<case stem>/)");
  cmd->callback([] {
    Case c = load_case(case_path);
    apply_solver_option(c, "tet10");
    check_contact_case(c);  // before any work: nothing is written for a case contact cannot take
    progress("case:\n" + describe_case(c));
    const std::filesystem::path dir = out.empty() ? default_out_dir(c) : std::filesystem::path(out);
    const FemJobResult fem = run_fem_job(c, dir, fem_options);
    run_contact_job(c, fem, dir);
  });
}

}  // namespace sw::app
