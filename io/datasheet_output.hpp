#pragma once
// What `strainwave datasheet` writes: datasheet.json (figures keyed by name, each {value, unit, method, published},
// with `case` and `version` as every result file) and datasheet.html (the sheet as a page: the table, the published
// figures beside, the idealisations). Writer and reader side by side.
#include <filesystem>
#include <string>

#include "datasheet/datasheet.hpp"
#include "io/case.hpp"

namespace sw {

/// datasheet.json's text for the sheet of case `c`.
std::string datasheet_json(const Datasheet& d, const Case& c);

/// Reads datasheet.json back (figures, their order, catalog size and ratio, idealisations). Throws InputError naming
/// the file, the key and the value when the file is missing, not JSON or lacks a key the writer always writes.
Datasheet read_datasheet(const std::filesystem::path& datasheet_json);

/// The sheet as one self-contained page (no scripts, no network).
std::string datasheet_html(const Datasheet& d, const Case& c);

/// The sheet as the printed table: one line a figure, computed beside published.
std::string datasheet_table(const Datasheet& d);

}  // namespace sw
