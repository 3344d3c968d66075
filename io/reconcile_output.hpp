#pragma once
// reconcile.json (keys in SPEC.md): the writer and the reader of the report `strainwave reconcile` produces
// (reconcile::Report, built by reconcile::report_of from the analysis).
#include <filesystem>
#include <string>

#include "reconcile/report.hpp"

namespace sw {

/// reconcile.json text of a report (two-space indent, keys sorted, a final newline).
std::string reconcile_json(const reconcile::Report& report);

/// The report a reconcile.json text holds; `where` names the text in messages. Throws InputError naming `where` and
/// the reason when the text is not JSON or a key is missing or of the wrong type.
reconcile::Report parse_reconcile_json(const std::string& text, const std::string& where);

/// Reads reconcile.json. Throws InputError when it cannot be read or is malformed.
reconcile::Report read_reconcile_json(const std::filesystem::path& path);

}  // namespace sw
