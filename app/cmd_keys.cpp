// `strainwave keys [--out FILE.md]`: every key of a case file, by table, with its unit, default or the rule that
// derives it, range and meaning, from the stages' schemas (common/case_keys.hpp); docs/keys.md is its output.
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"

namespace sw::app {

void add_keys_command(CLI::App& app) {
  auto* cmd = app.add_subcommand("keys", "print every case key: unit, default, range and meaning (Markdown)");
  auto out = std::make_shared<std::string>();
  cmd->add_option("--out", *out, "write the reference to this file instead of printing it");
  cmd->callback([out] {
    const std::string page = case_keys_reference();
    if (out->empty())
      std::fputs(page.c_str(), stdout);
    else
      write_file_atomic(*out, page);
  });
}

}  // namespace sw::app
