#pragma once
// A recording from a test rig (SPEC.md "Recordings"): `# key: value` metadata lines, one header line, numeric rows.
// Parsing is strict: a missing or non-numeric value, NaN/Inf, unsorted time, an unknown, missing or misplaced column,
// a missing `kind` or format version all throw sw::InputError naming "file:line", the column, the value and the
// expectation.
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace sw::reconcile {

enum class Kind { Torsion, Transmission, Backlash, Dynamics };

/// Every kind, in the order above.
inline constexpr Kind kKinds[] = {Kind::Torsion, Kind::Transmission, Kind::Backlash, Kind::Dynamics};

/// "torsion", "transmission", "backlash", "dynamics".
std::string kind_name(Kind kind);

/// The kind of a name kind_name() gives; nullopt for any other text.
std::optional<Kind> kind_from_name(const std::string& name);

/// The columns of a kind, in file order, without the optional leading `time_s`.
std::vector<std::string> kind_columns(Kind kind);

/// True when the kind's recordings may start with a `time_s` column (all but backlash).
bool kind_has_time(Kind kind);

struct Recording {
  std::string path;                                          ///< for messages
  Kind kind = Kind::Torsion;
  std::vector<std::pair<std::string, std::string>> metadata;  ///< every `# key: value` line, in file order
  std::vector<std::string> columns;                          ///< header names, in file order
  std::vector<std::vector<double>> values;                   ///< values[column][row]
  std::vector<int> lines;                                    ///< 1-based file line of each row

  std::size_t rows() const { return lines.size(); }
  /// The values of a named column; nullptr when the recording has no such column.
  const std::vector<double>* column(const std::string& name) const;
  /// A metadata value by key (exact match); nullopt when absent.
  std::optional<std::string> meta(const std::string& key) const;
  /// A numeric metadata value; nullopt when absent; throws InputError when present but not a number.
  std::optional<double> meta_number(const std::string& key) const;
};

/// Parses recording text. `path` is used in messages only. Throws InputError on any violation of the format.
Recording parse_recording(const std::string& text, const std::string& path);

/// Reads and parses a recording file. Throws InputError when it cannot be read or is malformed.
Recording load_recording(const std::string& path);

/// Writes a recording in the format parse_recording() reads (17 significant digits, metadata in order).
std::string format_recording(const Recording& recording);

}  // namespace sw::reconcile
