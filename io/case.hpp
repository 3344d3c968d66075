#pragma once
// A case file (TOML) parsed into option structs. Lengths are millimetres in the file and metres here: converted once,
// in load_case(). Unknown keys, wrong types and inconsistent values throw sw::InputError naming file, key, value and
// the expectation.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/lubricant.hpp"
#include "common/material.hpp"
#include "contact/circular_spline.hpp"
#include "contact/contact_params.hpp"
#include "dynamics/dynamics_params.hpp"
#include "fem/fem_params.hpp"
#include "fem/flexspline_model.hpp"
#include "gear/gear.hpp"
#include "generator/wave_generator.hpp"
#include "io/provenance.hpp"
#include "mesh/flexspline_params.hpp"

namespace sw {

/// A whole case: every stage's own options, as the file gives them (defaults filled in). Only the command line (app/)
/// holds a Case; each stage takes its own part (flexspline_model() below for the FEM, the contact's and the dynamics'
/// inputs from their own tables).
struct Case {
  std::string path;      ///< the file it came from (for messages)
  std::string stem;      ///< file name without directory and extension (default output folder)
  std::optional<GearParams> gear;
  FlexsplineParams flexspline;
  Material material;
  std::optional<WaveGeneratorParams> wave_generator;
  LoadParams load;
  MeshParams mesh;
  SolverParams solver;
  /// [catalog] size: the catalog size the case stands for (a row of design/catalog.hpp).
  std::optional<int> catalog_size;
  /// [circular_spline]: the given keys, else the defaults of contact/circular_spline.hpp; absent without [gear], and
  /// absent without a toothed face (rim_width 0: a tube without teeth) unless the table is given (its default width
  /// is the toothed face's).
  std::optional<CircularSplineParams> circular_spline;
  ContactParams contact;
  /// [lubricant]: the oil or grease (base oil) the drive runs in and its temperature (common/lubricant.hpp); absent
  /// when the table is (the datasheet's losses are then not computed).
  std::optional<Lubricant> lubricant;
  /// [dynamics]: the dynamics stage's own options (dynamics/dynamics_params.hpp), absent when the table is.
  std::optional<DynamicsParams> dynamics;
  /// Keys the file leaves out whose value is derived from other keys: "table.key" → what it was derived from. A
  /// stage's message about such a value says so and names the key that sets it.
  std::map<std::string, std::string> derived_from;
};

/// The case's tables the FEM reads, copied (the one place a Case becomes the FEM's input).
inline FlexsplineModel flexspline_model(const Case& c) {
  return {c.flexspline, c.gear, c.material, c.wave_generator, c.load, c.mesh, c.solver};
}


/// Parses and validates a case file. Throws InputError (one line: "file: key = value; expectation"). A `.json` file is
/// an output of the tool (result.json, backlash.json, contact.json, dynamics.json, reconcile.json): the resolved case
/// it stores under "case" is read as its case file would be, the messages name the JSON file, and the case's stem
/// (its default output folder) is the name of the folder holding the file.
Case load_case(const std::string& path);

/// Same, from TOML text (path is used in messages only).
Case parse_case(const std::string& toml_text, const std::string& path);

/// A case file's text as TOML: a TOML file's own text, or, for an output of the tool (`.json`), its stored case as
/// describe_case writes it. Throws InputError as load_case.
std::string case_file_toml(const std::string& path);

/// The resolved case as a case file (TOML): every key the reader accepts, with its value (defaults included), in the
/// file's units, a comment beside a value that came from elsewhere (the catalog's rated torque). parse_case reads it
/// back to the same case (printed at the start of a run).
std::string describe_case(const Case& c);

/// Every key of every table from the stages' schemas (common/case_keys.hpp): unit, default or the rule that derives it,
/// range and meaning, as a Markdown page (`strainwave keys`, docs/keys.md).
std::string case_keys_reference();

/// The keys whose value came from elsewhere than the file (derived from other keys, the catalog's rated torque, the
/// solver "auto" chose), one line each as "  table.key = value  # where it came from"; empty when there are none.
std::string describe_derived(const Case& c);

/// The same tables and keys as a JSON object's text (the "case" the outputs store); load_case reads it back from an
/// output. A number is the shortest decimal that reads back to the same value; a default derived in SI that no
/// decimal reaches is written 1 ulp away, and the same again once read back.
std::string case_json(const Case& c);

/// The provenance of a run of `c` by this build: its case_json and tool_version().
Provenance provenance_of(const Case& c);

}  // namespace sw
