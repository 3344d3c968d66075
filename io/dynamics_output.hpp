#pragma once
// dynamics.json, the typed result of `strainwave dynamics` (dynamics/run_summary.hpp's DynamicsResult): its writer and its
// reader side by side, one key for one field. Keys in SPEC.md ("Dynamics result"); objects' keys sorted. The path of
// the case file the run read is "case_file".
#include <filesystem>
#include <optional>
#include <string>

#include "dynamics/run_summary.hpp"
#include "io/provenance.hpp"

namespace sw {

/// dynamics.json text (two-space indent, a newline at the end); with `provenance` (the tool always gives it), its
/// "case" (the resolved case) and "version" beside the figures.
std::string dynamics_json(const DynamicsResult& r, const std::optional<Provenance>& provenance = std::nullopt);

/// The result in dynamics.json text `text`; `source` names it in errors. Throws InputError naming the source and the
/// key when a key is missing or of the wrong type, or a configuration, ramp or pair motion is not one of the spellings.
/// "case" and "version" are accepted and left to load_case (the case runs again from the file).
DynamicsResult parse_dynamics_json(const std::string& text, const std::string& source);

/// The result in the dynamics.json file at `path`. Throws InputError when it cannot be read or parsed.
DynamicsResult read_dynamics_json(const std::filesystem::path& path);

}  // namespace sw
