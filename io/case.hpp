#pragma once
// A case file (TOML) parsed into option structs. Lengths are millimetres in the file and metres here: converted once,
// in load_case(). Unknown keys, wrong types and inconsistent values throw sw::InputError naming file, key, value and
// the expectation.
#include <optional>
#include <string>
#include <vector>

#include "common/params.hpp"
#include "dynamics/dynamics_params.hpp"  // [dynamics] (header-only, standard library only)

namespace sw {


/// Parses and validates a case file. Throws InputError (one line: "file: key = value; expectation").
Case load_case(const std::string& path);

/// Same, from TOML text (path is used in messages only).
Case parse_case(const std::string& toml_text, const std::string& path);

/// The resolved case, defaults included, as TOML-like text (printed at the start of a run).
std::string describe_case(const Case& c);

}  // namespace sw
