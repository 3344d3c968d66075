// strainwave: design and understand strain wave gears. The one main(): builds the CLI from the subcommands in
// app/cmd_*.cpp, runs the chosen one, and turns every error into one line on stderr and a non-zero exit.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "fem/petsc_solver.hpp"
#include "io/provenance.hpp"

namespace {

/// MPI and PETSc for the process (fem/petsc_solver.hpp): rank 0 runs the command, the other ranks of an mpirun launch
/// serve its distributed solves; on every way out of main, rank 0 releases them.
struct ParallelRun {
  bool succeeded = false;
  ~ParallelRun() { sw::parallel::stop(succeeded); }
};

}  // namespace

int main(int argc, char** argv) {
  // PETSc's options (a single dash: -ksp_type cg) go to PETSc, the rest to the command line parser.
  std::vector<std::string> args(argv, argv + argc);
  const std::vector<std::string> petsc_options = sw::parallel::take_petsc_options(args);
  ParallelRun parallel_run;
  try {
    sw::parallel::start(petsc_options);
  } catch (const sw::InputError& e) {
    std::fprintf(stderr, "strainwave: error: %s\n", e.what());
    return 2;
  }
  if (sw::parallel::rank() > 0) return sw::parallel::serve();

  CLI::App app{"strainwave: FEM, backlash, reconciliation and dynamics of strain wave gears"};
  app.require_subcommand(1);
  app.fallthrough();  // --quiet may follow the subcommand too
  app.add_flag("--quiet", sw::quiet_progress(), "no progress lines on stderr");
  app.set_version_flag("--version", std::string("strainwave ") + sw::tool_version());
  sw::app::add_fem_command(app);
  sw::app::add_run_command(app);
  // Subcommands of the later modules register here (backlash, reconcile, synth, dynamics).
  sw::app::add_backlash_command(app);
  sw::app::add_contact_command(app);
  sw::app::add_dynamics_command(app);
  sw::app::add_reconcile_command(app);
  sw::app::add_synth_command(app);
  sw::app::add_sweep_command(app);
  sw::app::add_design_command(app);
  sw::app::add_datasheet_command(app);
  sw::app::add_keys_command(app);
  try {
    std::vector<const char*> kept;
    for (const auto& a : args) kept.push_back(a.c_str());
    app.parse(static_cast<int>(kept.size()), kept.data());
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // one line, as for every other bad input (CLI11's own adds a second)
    std::string what = e.what();
    if (const auto big = what.find(" not in range 0.000000 to 1797"); big != std::string::npos)
      what = what.substr(0, big) + " is not a positive number";  // CLI11's PositiveNumber spells out DBL_MAX
    std::fprintf(stderr, "strainwave: error: %s (strainwave --help)\n", what.c_str());
    return 2;
  } catch (const sw::InputError& e) {
    std::fprintf(stderr, "strainwave: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strainwave: internal error: %s\n", e.what());
    return 3;
  }
  parallel_run.succeeded = true;
  return 0;
}
