// strainwave: design and understand strain wave gears. The one main(): builds the CLI from the subcommands in
// app/cmd_*.cpp, runs the chosen one, and turns every error into one line on stderr and a non-zero exit.
#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"

int main(int argc, char** argv) {
  CLI::App app{"strainwave: FEM, backlash, reconciliation and dynamics of strain wave gears"};
  app.require_subcommand(1);
  app.fallthrough();  // --quiet may follow the subcommand too
  app.add_flag("--quiet", sw::quiet_progress(), "no progress lines on stderr");
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
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
  return 0;
}
