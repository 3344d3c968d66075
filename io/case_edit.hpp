#pragma once
// A case file's text with some of its numeric keys set to other values (a sweep's points, the model re-runs of
// reconcile), and the value a numeric key resolves to in a case.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/case.hpp"

namespace sw {

/// Keys "table.key" and their values in the case file's units (lengths in mm).
using CaseKeyValues = std::vector<std::pair<std::string, double>>;

/// The case file's TOML `toml_text` (from `path`, for messages) with each key "table.key" set to its value: a table
/// the text lacks is added; a whole value stays an integer where the text had an integer (a key that takes integers
/// only rejects a fraction with parse_case's message). Returns the TOML text without comments. Throws InputError
/// "OPTION KEY: ..." (`option` names where the key came from, "--set") for a key that is not "table.key" or whose
/// table is not a table, and for malformed TOML.
std::string case_text_with(const std::string& toml_text, const std::string& path, const CaseKeyValues& values,
                           const std::string& option);

/// The value a numeric key "table.key" has in the case (the resolved case of describe_case: keys the file leaves
/// out hold their default or derived value), in the file's units; nullopt when the case has no such key or its
/// value is not a number.
std::optional<double> case_number(const Case& c, const std::string& key);

}  // namespace sw
