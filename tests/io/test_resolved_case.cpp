// The resolved case as a run prints it (describe_case, TOML) and as its outputs store it (case_json): every shipped
// case, every designed size and a case setting every key read back from either to the same case (written again, the
// same text), every key a case file gives stands in it with the file's own value, and an output of the tool is read
// as its case file (load_case), bad ones in one line naming the output.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include "common/error.hpp"
#include "design/proportions.hpp"
#include "io/case.hpp"
#include "tests/cli.hpp"
#include "tests/io/output_samples.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sw::testing::read_text;
using sw::testing::scratch_dir;

/// describe_case's text without its comments (the file it came from, where a value came from: the catalog's rated
/// torque, once written, comes from the case).
std::string tables_of(const sw::Case& c) {
  std::istringstream text(sw::describe_case(c));
  std::string tables, line;
  while (std::getline(text, line))
    if (line[0] != '#') tables += line.substr(0, line.find("  #")) + "\n";
  return tables;
}

/// An output holding `resolved_case` (a JSON object's text) under "case", beside a figure, in a fresh folder.
fs::path output_holding(const std::string& resolved_case, const std::string& folder) {
  const fs::path d = scratch_dir(folder);
  std::ofstream(d / "result.json") << R"({"phi0_rad": 1e-4, "case": )" << resolved_case << "}\n";
  return d / "result.json";
}

/// `c` written as TOML and as JSON reads back to the same case: written again, the same text.
void expect_reads_back(const sw::Case& c, const std::string& name) {
  const sw::Case from_toml = sw::parse_case(sw::describe_case(c), name + " as written");
  EXPECT_EQ(sw::case_json(from_toml), sw::case_json(c)) << name;
  EXPECT_EQ(tables_of(from_toml), tables_of(c)) << name;
  const fs::path file = output_holding(sw::case_json(c), "stored_case");
  const sw::Case from_json = sw::load_case(file.string());
  EXPECT_EQ(sw::case_json(from_json), sw::case_json(c)) << name;
  EXPECT_EQ(tables_of(from_json), tables_of(c)) << name;
  fs::remove_all(file.parent_path());
}

/// A value of the case file and the same key of the written case: the same text, the same number to the last bit,
/// tables and lists element by element.
void expect_same_value(const toml::node& given, const json& written, const std::string& key) {
  if (const toml::table* t = given.as_table()) {
    ASSERT_TRUE(written.is_object()) << key;
    for (const auto& [k, v] : *t) {
      const std::string sub(k.str());
      ASSERT_TRUE(written.contains(sub)) << key << "." << sub << " is not written";
      expect_same_value(v, written.at(sub), key + "." + sub);
    }
  } else if (const toml::array* a = given.as_array()) {
    ASSERT_TRUE(written.is_array() && written.size() == a->size()) << key;
    for (std::size_t i = 0; i < a->size(); ++i)
      expect_same_value(*a->get(i), written.at(i), key + "[" + std::to_string(i) + "]");
  } else if (const auto text = given.value_exact<std::string>()) {
    EXPECT_EQ(written, *text) << key;
  } else {
    ASSERT_TRUE(written.is_number()) << key << " = " << written;
    EXPECT_EQ(written.get<double>(), *given.value<double>()) << key;
  }
}

/// Every key of the case file `text` stands in the written case with the file's value.
void expect_file_keys_written(const std::string& text, const sw::Case& c, const std::string& name) {
  const json written = json::parse(sw::case_json(c));
  for (const auto& [table, keys] : toml::parse(text)) {
    const std::string t(table.str());
    ASSERT_TRUE(written.contains(t)) << name << ": [" << t << "] is not written";
    expect_same_value(keys, written.at(t), name + ": " + t);
  }
}

TEST(ResolvedCase, EveryShippedCaseReadsBackWithTheFileKeysValues) {
  int cases = 0;
  for (const auto& entry : fs::directory_iterator("cases")) {
    if (entry.path().extension() != ".toml") continue;
    ++cases;
    const std::string text = read_text(entry.path());
    const sw::Case c = sw::parse_case(text, entry.path().string());
    expect_reads_back(c, entry.path().string());
    expect_file_keys_written(text, c, entry.path().string());
  }
  EXPECT_GE(cases, 6);
}

TEST(ResolvedCase, EveryDesignReadsBackWithTheDesignsValues) {
  for (const int size : {sw::kDesignSizeMin, 14, 17, 20, 25, 32, 40, 50, sw::kDesignSizeMax})
    for (const int ratio : {sw::kDesignRatioMin, 100, sw::kDesignRatioMax}) {
      const std::string name = "design size " + std::to_string(size) + " ratio " + std::to_string(ratio);
      const std::string text = sw::design_case_toml(sw::design_cup(size, ratio));
      const sw::Case c = sw::parse_case(text, name);
      expect_reads_back(c, name);
      expect_file_keys_written(text, c, name);
    }
}

// Every key the reader takes, none at its default but circular_spline.mounting (the other value takes no bolt
// circles); the generator's models in turn (each takes its own keys).
constexpr const char* kEveryKey = R"([gear]
module_mm = 0.2
teeth_flexspline = 190
teeth_circular = 192
pressure_angle_deg = 20.5
profile_shift_flexspline = 1.52
profile_shift_circular = 1.57
cutter_teeth = 76
addendum_coefficient_flexspline = 0.6
addendum_coefficient_circular = 0.62
dedendum_coefficient_flexspline = 0.95
dedendum_coefficient_circular = 0.97
tip_rounding_flexspline_mm = 0.01
tip_rounding_circular_mm = 0.012
[flexspline]
shape = "cup"
inner_radius_mm = 18.4
wall_thickness_mm = 0.55
length_mm = 14.7
rim_width_mm = 6.5
rim_thickness_mm = 0.7
teeth = "ring"
diaphragm_thickness_mm = 1.4
boss_radius_mm = 9.5
fillet_radius_mm = 1.1
[material]
youngs_modulus_Pa = 207e9
poisson_ratio = 0.29
density_kg_m3 = 7800
fatigue_limit_MPa = 480
ultimate_strength_MPa = 1050
yield_strength_MPa = 900
loss_factor = 4e-4
[lubricant]
kind = "oil"
viscosity_40C_mm2_s = 100
viscosity_100C_mm2_s = 11
temperature_C = 35
[load]
torque_Nm = 20
torque_loading = "uniform"
engagement_half_angle_deg = 25
rated_torque_Nm = 30
[catalog]
size = 17
[circular_spline]
outer_radius_mm = 28.5
width_mm = 5.5
mounting = "bolted_face"
bolt_circle_inner_mm = 21.5
bolt_circle_outer_mm = 25
[contact]
face_slices = 3
friction_coefficient = 0.05
generator_angle_deg = 0.45
[mesh]
size_mm = 0.9
wall_layers = 1
corner_levels = 2
max_radius_edge_ratio = 1.8
min_dihedral_deg = 10
[solver]
method = "fourier"
harmonics = 32
backend = "cholmod"
[dynamics]
configuration = "fs_fixed"
ramp = "cubic"
pairs = "frozen"
pair_stiffness = "constant"
rim = "rigid"
compliance_phases = 6
oversampling = 4
drive_speed_rpm = 1200
drive_ramp_start_s = 0.001
drive_ramp_end_s = 0.012
load_torque_Nm = 80
load_ramp_start_s = 0.013
load_ramp_end_s = 0.025
stiffness_N_per_m = 7e7
stiffness_variation_N_per_m = 1e7
stiffness_phase_deg = 15
damping_Ns_per_m = 900
exponent_stiffness = 1.5
exponent_damping = 0.5
exponent_indentation = 0.25
flexspline_compliance_rad_per_Nm = 2e-5
flexspline_torsion_damping_Nms_per_rad = 0.01
circular_spline_drag_Nms_per_rad = 800
load_inertia_kgm2 = 1e-4
output_drag_coulomb_Nm = 0.5
output_drag_viscous_Nms_per_rad = 0.002
drag_smoothing_rad_per_s = 0.002
circular_spline_outer_radius_mm = 27
circular_spline_width_mm = 6
base_clearance_mm = 0.003
duration_s = 0.08
output_step_s = 2e-5
steady_from_s = 0.04
relative_tolerance = 1e-7
absolute_tolerance_rad = 1e-12
[wave_generator]
axial_position_mm = 3.5
band_width_mm = 3.8
)";

constexpr const char* kGenerators[] = {
    "model = \"cam\"\nprofile = \"list\"\nfit_um = -2\nprofile_points = [{angle_deg = 0, radius_mm = 18.6}, "
    "{angle_deg = 45, radius_mm = 18.41}, {angle_deg = 90, radius_mm = 18.2}, {angle_deg = 135, radius_mm = 18.41}]\n"
    "bearing = {balls = 23, ball_diameter_mm = 3.969, inner_groove_conformity = 0.515, "
    "outer_groove_conformity = 0.54}\n",
    "model = \"cam\"\nprofile = \"ellipse\"\nradial_deformation_mm = 0.21\nfit_um = 1.5\n",
    "model = \"four_force\"\nbeta_deg = 25\nradial_deformation_mm = 0.2\nforce_N = 150\n",
    "model = \"two_force\"\nforce_N = 120\n",
    "model = \"forces\"\nradial_deformation_mm = 0.2\nforces = [{angle_deg = 20, weight = 0.7}, {angle_deg = -20, "
    "weight = 0.3}]\n",
    "model = \"rollers\"\nbeta_deg = 35\nradial_deformation_mm = 0.19\n"};

TEST(ResolvedCase, EveryKeyReadsBackWithItsValue) {
  for (const char* generator : kGenerators) {
    const std::string text = std::string(kEveryKey) + generator;
    const std::string model(generator, std::string(generator).find('\n'));
    const std::string name = "every key, " + model;
    const sw::Case c = sw::parse_case(text, name);
    expect_reads_back(c, name);
    expect_file_keys_written(text, c, name);
  }
}

/// The section of a Markdown file from its heading line `heading` to the next heading of the same level.
std::string section_of(const std::string& text, const std::string& heading) {
  const auto start = text.find("\n" + heading + "\n");
  if (start == std::string::npos) return "";
  const auto end = text.find("\n## ", start + 1);
  return text.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

/// Whether `key` stands in `text` as a word (not inside a longer name).
bool names(const std::string& text, const std::string& key) {
  auto is_name = [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; };
  for (auto at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
    const bool before = at > 0 && is_name(text[at - 1]);
    const bool after = at + key.size() < text.size() && is_name(text[at + key.size()]);
    if (!before && !after) return true;
  }
  return false;
}

// Every key the reader takes is documented: the resolved case of the every-key case (each generator model in turn)
// names each table's keys, and each must stand in its table's section of docs/case-keys.md, the keys of inline tables
// and lists of tables included. A key added to a reader without its line in the documentation fails here.
TEST(ResolvedCase, EveryKeyTheReaderTakesIsDocumented) {
  const std::string docs = read_text("docs/case-keys.md");
  ASSERT_FALSE(docs.empty());
  std::set<std::string> missing;
  int keys = 0;
  for (const char* generator : kGenerators) {
    const sw::Case c = sw::parse_case(std::string(kEveryKey) + generator, "every key");
    const toml::table written = toml::parse(sw::describe_case(c));
    for (const auto& [table_name, node] : written) {
      const std::string table(table_name.str());
      const std::string where = section_of(docs, "## `[" + table + "]`");
      EXPECT_FALSE(where.empty()) << "no section for [" << table << "] in docs/case-keys.md";
      auto check = [&](const std::string& key) {
        ++keys;
        if (!names(where, key)) missing.insert("[" + table + "] " + key);
      };
      for (const auto& [key, value] : *node.as_table()) {
        check(std::string(key.str()));
        if (const toml::table* inline_table = value.as_table())
          for (const auto& [sub, unused] : *inline_table) check(std::string(sub.str()));
        if (const toml::array* list = value.as_array())
          for (const toml::node& item : *list)
            if (const toml::table* t = item.as_table())
              for (const auto& [sub, unused] : *t) check(std::string(sub.str()));
      }
    }
  }
  std::string list;
  for (const auto& m : missing) list += "\n  " + m;
  EXPECT_TRUE(missing.empty()) << missing.size() << " keys without their documentation:" << list;
  EXPECT_GT(keys, 100);  // the every-key case's tables were read
}

// The every-key case is what its name says: each table's reader, asked for a key it does not know, lists the keys it
// asks for (its "allowed" list); over the generator models every one of them is set by the every-key case and stands in
// its table's section of docs/case-keys.md. A key added to a reader and to neither fails here.
TEST(ResolvedCase, EveryKeyCaseSetsEveryKeyTheReaderAsksFor) {
  const std::string docs = read_text("docs/case-keys.md");
  std::map<std::string, std::set<std::string>> asked, given;
  for (const char* generator : kGenerators) {
    const std::string text = std::string(kEveryKey) + generator;
    const toml::table parsed = toml::parse(text);
    for (const auto& [table_name, node] : parsed) {
      const std::string table(table_name.str());
      for (const auto& [key, unused] : *node.as_table()) given[table].insert(std::string(key.str()));
      std::string probed = text;
      const std::string header = "[" + table + "]\n";
      probed.insert(probed.find(header) + header.size(), "zz_probe = 1\n");
      try {
        sw::parse_case(probed, "probe");
        ADD_FAILURE() << "[" << table << "] took an unknown key";
      } catch (const sw::InputError& e) {
        const std::string what = e.what(), tag = "(allowed: ";
        const auto at = what.find(tag);
        ASSERT_NE(at, std::string::npos) << what;
        std::istringstream list(what.substr(at + tag.size(), what.rfind(')') - at - tag.size()));
        for (std::string key; std::getline(list >> std::ws, key, ',');) asked[table].insert(key);
      }
    }
  }
  int keys = 0;
  for (const auto& [table, names_asked] : asked)
    for (const std::string& key : names_asked) {
      ++keys;
      EXPECT_TRUE(given[table].count(key)) << "[" << table << "] " << key << ": the every-key case does not set it";
      EXPECT_TRUE(names(section_of(docs, "## `[" + table + "]`"), key))
          << "[" << table << "] " << key << ": not in docs/case-keys.md";
    }
  EXPECT_GT(keys, 90);  // every table's list was read (99 keys of the top level today)
}

// The keys a case leaves out are written with the value the reader gave them: a tube's derived rim, the default mesh,
// the solver's harmonics beside TET10, the catalog's rated torque (with where it came from, as a comment).
TEST(ResolvedCase, DefaultsAndDerivedValuesAreWritten) {
  const sw::Case tube = sw::parse_case("[flexspline]\nshape = \"tube\"\nwall_thickness_mm = 1.25\nteeth = \"none\"\n"
                                       "[catalog]\nsize = 17\n", "t.toml");
  const json written = json::parse(sw::case_json(tube));
  EXPECT_EQ(written["flexspline"]["rim_thickness_mm"], 1.25);  // a tube without teeth: its wall
  EXPECT_EQ(written["flexspline"]["inner_radius_mm"], 18.4);
  EXPECT_EQ(written["mesh"]["size_mm"].get<double>() * 1e-3, tube.mesh.size_m);
  EXPECT_EQ(written["solver"]["harmonics"], tube.solver.harmonics);
  EXPECT_EQ(written["load"]["rated_torque_Nm"], 31.0);
  EXPECT_FALSE(written["flexspline"].contains("boss_radius_mm"));  // a tube has none: the reader refuses it
  EXPECT_NE(sw::describe_case(tube).find("rated_torque_Nm = 31  # from catalog size 17\n"), std::string::npos)
      << sw::describe_case(tube);
  expect_reads_back(tube, "tube");
}

// A default derived in SI may lie where no decimal in millimetres lands (the reader multiplies by 1e-3): it is
// written as the nearest value one reaches, 1 ulp away, and that value is written the same again.
TEST(ResolvedCase, AValueNoDecimalReachesIsWrittenOneUlpAwayAndThenStays) {
  sw::Case c = sw::parse_case(sw::design_case_toml(sw::design_cup(17, 100)), "d.toml");
  double& r = c.circular_spline->outer_radius_m;
  const double first = r;
  for (int i = 0; i < 4096 && r / 1e-3 * 1e-3 == r; ++i) r = std::nextafter(r, 1.0);
  ASSERT_NE(r / 1e-3 * 1e-3, r) << "no value within 4096 ulp of " << first << " misses x / 1e-3 * 1e-3";
  const sw::Case back = sw::parse_case(sw::describe_case(c), "d.toml");
  EXPECT_LE(std::abs(back.circular_spline->outer_radius_m - r), std::nextafter(r, 1.0) - r);
  EXPECT_EQ(sw::case_json(sw::parse_case(sw::describe_case(back), "d.toml")), sw::case_json(back));
}

TEST(ResolvedCase, AnOutputRunsAsItsCaseNamedAfterItsFolder) {
  const sw::Case c = sw::load_case("cases/cup_size14.toml");
  const fs::path file = output_holding(sw::case_json(c), "stored_stem");
  const sw::Case again = sw::load_case(file.string());
  EXPECT_EQ(again.path, file.string());
  EXPECT_EQ(again.stem, file.parent_path().filename().string());
  EXPECT_EQ(sw::case_json(again), sw::case_json(c));
  EXPECT_EQ(sw::case_file_toml(file.string()), sw::describe_case(again));
  EXPECT_EQ(sw::case_file_toml("cases/cup_size14.toml"), read_text("cases/cup_size14.toml"));
  fs::remove_all(file.parent_path());
}

/// The one-line message load_case gives for an output holding `text`.
std::string stored_case_error(const std::string& text) {
  const fs::path d = scratch_dir("stored_case_error");
  std::ofstream(d / "result.json") << text;
  std::string message = "no error";
  try {
    (void)sw::load_case((d / "result.json").string());
  } catch (const sw::InputError& e) {
    message = e.what();
  }
  fs::remove_all(d);
  return (d / "result.json").string() + " -> " + message;
}

TEST(ResolvedCase, ABadStoredCaseIsOneLineNamingTheOutputAndTheKey) {
  const auto expect_error = [](const std::string& text, const std::string& expected) {
    const std::string m = stored_case_error(text);
    const std::string file = m.substr(0, m.find(" -> "));
    EXPECT_NE(m.find(" -> " + file + ": " + expected), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  };
  expect_error(R"({"phi0_rad": 1e-4})", "case is missing; expected an output of strainwave holding its resolved case");
  expect_error(R"({"case": "cases/x.toml"})",
               "case = \"cases/x.toml\"; expected the resolved case, a table of tables (an output written before");
  expect_error(R"({"case": {"flexspline": {"shape": "tube", "length_mm": null}}})",
               "case.flexspline.length_mm = null; expected a number, text, true/false, list or table");
  expect_error(R"({"case": {"flexspline": {"shape": "tube", "wall_thickness_mm": -1}}})",
               "flexspline.wall_thickness_mm = -1; must be > 0");
  expect_error(R"({"case": {"flexspline": {"shape": "tube", "teeth": "none", "colour": "red"}}})",
               "flexspline.colour = 'red'; unknown key");
  expect_error(R"({"case": {"flexspline": 3}})", "flexspline must be a table");
  expect_error(R"({"case": {"gearbox": {}}})", "[gearbox] is not a known table");
  expect_error("{\"case\": ", "not valid JSON");
  EXPECT_NE(stored_case_error("").find("not valid JSON"), std::string::npos);
  try {
    (void)sw::load_case("no/such/result.json");
    FAIL() << "no error";
  } catch (const sw::InputError& e) {
    EXPECT_EQ(std::string(e.what()), "no/such/result.json: cannot open the output file (does it exist?)");
  }
}

}  // namespace
