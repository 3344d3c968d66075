#pragma once
// What produced an output: the resolved case and the tool's version, stored beside the figures of every output JSON
// (result.json, backlash.json, contact.json, dynamics.json, reconcile.json) as "case" and "version". Given such a
// file in place of a case file, a command runs the stored case again (io/case.hpp load_case); io/case.hpp makes it
// (provenance_of).
#include <string>

namespace sw {

/// The tool's version: `git describe --always --dirty` of the source tree it was built from, "unknown" for a tree
/// outside git (a tarball). Defined in the build tree's generated version.cpp (cmake/write_version.cmake), which a
/// build rewrites only when the description changes.
const char* tool_version();

/// An output's "case" and "version".
struct Provenance {
  std::string resolved_case;  ///< key "case": the resolved case (case_json) as a JSON object's text, keys sorted
  std::string version;        ///< key "version": tool_version() of the build that wrote the output
  bool operator==(const Provenance&) const = default;
};

}  // namespace sw
