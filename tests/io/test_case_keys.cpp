// The schema of the case's keys (common/case_keys.hpp, one per stage) is what the reader, the writer and the range
// checks use: every key the writer writes has its schema line, and every range the schema states is the one the
// reader refuses, with the file, the key's line and the schema's words.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "io/case.hpp"

namespace sw {
namespace {

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

template <class T>
std::set<std::string> names(const std::vector<CaseKey<T>>& keys) {
  std::set<std::string> n;
  for (const auto& k : keys) n.insert(k.name);
  return n;
}

/// The schema's keys of every table ("wave_generator.bearing" for the inline table).
std::map<std::string, std::set<std::string>> schema_names() {
  return {{"gear", names(gear_keys())},
          {"flexspline", names(flexspline_keys())},
          {"material", names(material_keys())},
          {"wave_generator", names(wave_generator_keys())},
          {"wave_generator.bearing", names(generator_bearing_keys())},
          {"load", names(load_keys())},
          {"catalog", {"size"}},
          {"circular_spline", names(circular_spline_keys())},
          {"contact", names(contact_keys())},
          {"lubricant", names(lubricant_keys())},
          {"mesh", names(mesh_keys())},
          {"solver", names(solver_keys())},
          {"dynamics", names(dynamics_keys())}};
}

constexpr const char* kTube =
    "[flexspline]\nshape = \"tube\"\ninner_radius_mm = 18.5\nwall_thickness_mm = 1.0\n"
    "length_mm = 30\nteeth = \"none\"\n";
constexpr const char* kExtras =
    "\n[contact]\nface_slices = 2\n[lubricant]\nviscosity_40C_mm2_s = 100\n"
    "viscosity_100C_mm2_s = 10\ntemperature_C = 40\n[dynamics]\n";

/// The shipped cases, with the optional tables added, and a tube under each generator model.
std::vector<std::pair<std::string, std::string>> case_texts() {
  std::vector<std::pair<std::string, std::string>> texts;
  for (const auto& entry : std::filesystem::directory_iterator("cases"))
    if (entry.path().extension() == ".toml") {
      std::string text = read_text(entry.path());
      if (text.find("[contact]") == std::string::npos && text.find("[dynamics]") == std::string::npos &&
          text.find("[lubricant]") == std::string::npos)
        text += kExtras;
      texts.emplace_back(entry.path().string(), text);
    }
  const std::string size17 = read_text("cases/cup_size17.toml");
  std::string outer = std::regex_replace(size17, std::regex("mounting = \"bolted_face\""), "mounting = \"outer\"");
  outer = std::regex_replace(outer, std::regex("bolt_circle_[a-z]+_mm = [0-9.]+\n"), "");
  texts.emplace_back("outer.toml", outer);
  const std::string wg = std::string(kTube) + "[wave_generator]\n";
  texts.emplace_back("four_force.toml", wg + "model = \"four_force\"\nbeta_deg = 25\n");
  texts.emplace_back("two_force.toml", wg + "model = \"two_force\"\nforce_N = 50\n");
  texts.emplace_back("rollers.toml", wg + "model = \"rollers\"\nradial_deformation_mm = 0.2\n");
  texts.emplace_back("forces.toml", wg + "model = \"forces\"\nforces = [{angle_deg = 10, weight = 1}]\n");
  texts.emplace_back("list_cam.toml", wg +
                                          "model = \"cam\"\nprofile = \"list\"\nfit_um = -2\nprofile_points = "
                                          "[{angle_deg = 0, radius_mm = 18.7}, {angle_deg = 45, radius_mm = 18.6},\n"
                                          "{angle_deg = 90, radius_mm = 18.3}, {angle_deg = 135, radius_mm = 18.6}]\n");
  texts.emplace_back("strengths.toml", std::string(kTube) +
                                           "[material]\nfatigue_limit_MPa = 400\n"
                                           "ultimate_strength_MPa = 900\nyield_strength_MPa = 700\n");
  return texts;
}

// A key the writer writes (the resolved case, the outputs' "case") without a line in its stage's schema fails here:
// the reference, the range checks and the reader would not know it.
TEST(CaseKeys, EveryKeyTheWriterWritesHasItsSchemaLine) {
  const auto schema = schema_names();
  int keys = 0;
  for (const auto& [path, text] : case_texts()) {
    const Case c = parse_case(text, path);
    const nlohmann::json tables = nlohmann::json::parse(case_json(c));
    for (const auto& table : tables.items()) {
      ASSERT_TRUE(schema.count(table.key())) << path << ": table [" << table.key() << "] has no schema";
      for (const auto& key : table.value().items()) {
        EXPECT_TRUE(schema.at(table.key()).count(key.key())) << path << ": " << table.key() << "." << key.key();
        ++keys;
        if (key.key() != "bearing") continue;
        for (const auto& inner : key.value().items())
          EXPECT_TRUE(schema.at("wave_generator.bearing").count(inner.key())) << path << ": bearing." << inner.key();
      }
    }
  }
  EXPECT_GT(keys, 300);  // the cases hold every table: the check looked at something
}

/// The resolved text with one key's value replaced ("table" a [table], or "wave_generator.bearing" inside its
/// inline table); fails the test when the key is not in the text.
std::string with_value(const std::string& text, const std::string& table, const std::string& key,
                       const std::string& value) {
  if (table == "wave_generator.bearing") {
    const std::regex inner("bearing = \\{.*\\b" + key + " = ([^,}]+)");
    std::smatch m;
    EXPECT_TRUE(std::regex_search(text, m, inner)) << key;
    return text.substr(0, m.position(1)) + value + text.substr(m.position(1) + m.length(1));
  }
  std::istringstream in(text);
  std::string out, line, current;
  bool done = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '[') current = line.substr(1, line.find(']') - 1);
    if (current == table && line.rfind(key + " = ", 0) == 0) {
      line = key + " = " + value;
      done = true;
    }
    out += line + "\n";
  }
  EXPECT_TRUE(done) << table << "." << key << " is not in the resolved case";
  return out;
}

/// A value just outside the range (an open bound itself, a closed one a step beyond), as the file's text.
template <class T>
std::string outside(const CaseKey<T>& k) {
  std::ostringstream s;
  s.precision(17);
  const KeyRange& r = k.range;
  const double step = k.kind == KeyKind::Integer ? 1.0 : 0.5;
  if (std::isfinite(r.lo))
    s << (r.lo_open ? r.lo : r.lo - step * std::max(1.0, std::abs(r.lo)));
  else
    s << (r.hi_open ? r.hi : r.hi + step * std::max(1.0, std::abs(r.hi)));
  std::string v = s.str();
  if (k.kind == KeyKind::Number && v.find_first_of(".e") == std::string::npos) v += ".0";
  return v;
}

/// For every bounded key of `keys` that applies to the object `of`: the case with that key just outside its range
/// is refused as "<path>:<line>: <table>.<key> = <value>; must be <range>...". Returns how many keys were probed.
template <class T>
int probe(const std::string& base, const std::string& table, const T& of, const std::vector<CaseKey<T>>& keys) {
  int probed = 0;
  for (const CaseKey<T>& k : keys) {
    if ((k.kind != KeyKind::Number && k.kind != KeyKind::Integer) || !k.range.bounded() || !k.applies_to(of)) continue;
    const std::string value = outside(k);
    std::string error = "no error";
    try {
      parse_case(with_value(base, table, k.name, value), "x.toml");
    } catch (const InputError& e) {
      error = e.what();
    }
    const std::string expected = table + "." + k.name + " = ";
    EXPECT_TRUE(std::regex_search(error, std::regex("^x\\.toml:[0-9]+: "))) << error;
    EXPECT_NE(error.find(expected), std::string::npos) << value << ": " << error;
    EXPECT_NE(error.find("; must be " + k.range.text()), std::string::npos) << value << ": " << error;
    ++probed;
  }
  return probed;
}

// Each stated range is the reader's: a value just outside it is refused with the file, the key's line, the key and
// the schema's words (a range stated in the schema but checked otherwise, or not at all, fails here).
TEST(CaseKeys, EveryRangeTheSchemaStatesIsTheOneTheReaderRefuses) {
  const std::string extras = kExtras;  // but [contact]: the designed case has its own
  const Case c = parse_case(read_text("cases/cup_size17.toml") + "\n" + extras.substr(extras.find("[lubricant]")),
                            "cases/cup_size17.toml");
  ASSERT_TRUE(c.gear && c.wave_generator && c.wave_generator->bearing && c.lubricant && c.dynamics);
  const std::string base = describe_case(c);
  int probed = 0;
  probed += probe(base, "gear", *c.gear, gear_keys());
  probed += probe(base, "material", c.material, material_keys());
  probed += probe(base, "wave_generator", *c.wave_generator, wave_generator_keys());
  probed += probe(base, "wave_generator.bearing", *c.wave_generator->bearing, generator_bearing_keys());
  probed += probe(base, "load", c.load, load_keys());
  probed += probe(base, "contact", c.contact, contact_keys());
  probed += probe(base, "lubricant", *c.lubricant, lubricant_keys());
  probed += probe(base, "mesh", c.mesh, mesh_keys());
  probed += probe(base, "solver", c.solver, solver_keys());
  probed += probe(base, "dynamics", *c.dynamics, dynamics_keys());
  EXPECT_GE(probed, 60);
}

// The reference names every key of the schema once per table, and its defaults are the structs' own.
TEST(CaseKeys, TheReferenceListsEveryKeyWithItsDefault) {
  const std::string page = case_keys_reference();
  for (const auto& [table, keys] : schema_names()) {
    const std::size_t at = page.find("## [" + table + "]");
    ASSERT_NE(at, std::string::npos) << table;
    const std::string section = page.substr(at, page.find("\n## ", at + 1) - at);
    for (const auto& key : keys) EXPECT_NE(section.find("| `" + key + "` |"), std::string::npos) << table << "." << key;
  }
  EXPECT_NE(page.find("| `drive_speed_rpm` | rpm | 1000 | > 0 |"), std::string::npos);
  EXPECT_NE(page.find("| `pressure_angle_deg` | deg | 20 | in (5, 45) |"), std::string::npos);
}

}  // namespace
}  // namespace sw
