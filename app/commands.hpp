#pragma once
// Each subcommand of `strainwave` lives in its own app/cmd_<name>.cpp and registers itself on the CLI11 app here.
#include <filesystem>
#include <string>

#include "io/case.hpp"

namespace CLI {
class App;  // CLI/CLI.hpp costs some 6 s of compile per unit at -O3: only the commands' sources include it
}

namespace sw {
class OutputSet;
}

namespace sw::app {

/// Where every command writes when --out is not given: out/<case file stem>/.
std::filesystem::path default_out_dir(const Case& c);

/// The progress line a command starts with: the case, and the values it did not give (describe_derived).
std::string case_headline(const Case& c);

/// The resolved case the command runs (describe_case: every key, defaults filled in) as resolved_case.toml in its
/// output set: `strainwave <command> OUT/resolved_case.toml` runs it again. (Not case.toml: `sweep` keeps each point's
/// own case under that name in the point's folder.)
void write_resolved_case(const Case& c, OutputSet& out);

void add_fem_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_backlash_command(CLI::App& app);
void add_reconcile_command(CLI::App& app);
void add_synth_command(CLI::App& app);
void add_dynamics_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_contact_command(CLI::App& app);
void add_design_command(CLI::App& app);
void add_datasheet_command(CLI::App& app);
void add_keys_command(CLI::App& app);

}  // namespace sw::app
