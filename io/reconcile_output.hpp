#pragma once
// reconcile.json (keys in SPEC.md): the writer and the reader of the report `strainwave reconcile` produces
// (reconcile::Report, built by reconcile::report_of from the analysis), with the case it ran and the tool's version
// (io/provenance.hpp).
#include <filesystem>
#include <optional>
#include <string>

#include "io/provenance.hpp"
#include "reconcile/verdict.hpp"

namespace sw {

/// reconcile.json text of a report (two-space indent, keys sorted, a final newline); with `provenance` (the tool
/// always gives it), its "case" (the resolved case) and "version" beside the report.
std::string reconcile_json(const reconcile::Report& report, const std::optional<Provenance>& provenance = std::nullopt);

/// The report a reconcile.json text holds; `where` names the text in messages. Throws InputError naming `where` and
/// the reason when the text is not JSON or a key is missing or of the wrong type. "case" and "version" are accepted and
/// left to load_case (the case runs again from the file).
reconcile::Report parse_reconcile_json(const std::string& text, const std::string& where);

/// Reads reconcile.json. Throws InputError when it cannot be read or is malformed.
reconcile::Report read_reconcile_json(const std::filesystem::path& path);

}  // namespace sw
