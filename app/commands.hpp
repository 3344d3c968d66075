#pragma once
// Each subcommand of `strainwave` lives in its own app/cmd_<name>.cpp and registers itself on the CLI11 app here.
#include <CLI/CLI.hpp>

namespace sw::app {

void add_fem_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_backlash_command(CLI::App& app);
void add_reconcile_command(CLI::App& app);
void add_synth_command(CLI::App& app);
void add_dynamics_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_contact_command(CLI::App& app);
void add_design_command(CLI::App& app);

}  // namespace sw::app
