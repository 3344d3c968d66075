#pragma once
// dynamics.json, the typed result of `strainwave dynamics` (dynamics/report.hpp's DynamicsResult): its writer and its
// reader side by side, one key for one field. Keys in SPEC.md ("Dynamics result"); objects' keys sorted.
#include <filesystem>
#include <string>

#include "dynamics/report.hpp"

namespace sw {

/// dynamics.json text (two-space indent, a newline at the end).
std::string dynamics_json(const DynamicsResult& r);

/// The result in dynamics.json text `text`; `source` names it in errors. Throws InputError naming the source and the
/// key when a key is missing or of the wrong type, or a configuration, ramp or pair motion is not one of the spellings.
DynamicsResult parse_dynamics_json(const std::string& text, const std::string& source);

/// The result in the dynamics.json file at `path`. Throws InputError when it cannot be read or parsed.
DynamicsResult read_dynamics_json(const std::filesystem::path& path);

}  // namespace sw
