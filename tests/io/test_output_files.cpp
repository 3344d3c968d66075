// result.json, backlash.json and contact.json: what the writer writes, the reader reads back into the same typed
// value (written again it is the same text), and a file of another shape is one line naming the file, key and value.
// Every output (those and dynamics.json, reconcile.json) holds the resolved case it ran and the tool's version, which
// names the commit the tool was built from.
// Every <case>/{result,backlash,contact}.json of SW_GOLDEN_DIR (tests/io/data/written: the seed cup's and the tube's,
// as the tool wrote them; the environment or cmake -DSW_GOLDEN_DIR= names another set) is read and written again
// unchanged: the typed values hold every key the tool writes.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "io/case.hpp"
#include "io/dynamics_output.hpp"
#include "io/provenance.hpp"
#include "io/reconcile_output.hpp"
#include "tests/cli.hpp"
#include "tests/io/output_samples.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sw::testing;

/// `value` written to `file` and read back; written again, the read value is the same text.
template <class T>
T round_trip(const fs::path& file, const T& value, std::string (*write)(const T&), T (*read)(const fs::path&)) {
  const std::string text = write(value);
  std::ofstream(file) << text;
  const T back = read(file);
  EXPECT_EQ(write(back), text) << file;
  return back;
}

TEST(OutputFiles, ResultJsonReadsBackToTheSameValues) {
  const fs::path d = scratch_dir("result_round_trip");
  round_trip(d / "result.json", sample_fourier_result(), sw::fem_result_json, sw::read_fem_result);
  const sw::FemResult back = round_trip(d / "result.json", sample_fem_result(), sw::fem_result_json, sw::read_fem_result);
  ASSERT_TRUE(back.fatigue && back.fatigue->diaphragm);
  EXPECT_EQ(back.fatigue->rim.goodman_safety_factor, sample_fem_result().fatigue->rim.goodman_safety_factor);
  EXPECT_FALSE(back.fatigue->diaphragm->goodman_safety_factor);
  ASSERT_TRUE(back.generator && back.generator->bearing);
  ASSERT_EQ(back.generator->stations.size(), 2u);
  EXPECT_FALSE(back.generator->stations[1].force_N);
  fs::remove_all(d);
}

TEST(OutputFiles, BacklashJsonReadsBackToTheSameValues) {
  const fs::path d = scratch_dir("backlash_round_trip");
  const sw::BacklashResult back =
      round_trip(d / "backlash.json", sample_backlash_result(), sw::backlash_json, sw::read_backlash_result);
  // Out of the mesh zone there is no backlash: null, read back as no value.
  ASSERT_EQ(back.table.size(), 2u);
  EXPECT_FALSE(back.table[0].basic_over_m);
  EXPECT_EQ(back.table[1].basic_over_m, sample_backlash_result().table[1].basic_over_m);
  EXPECT_NE(read_text(d / "backlash.json").find("\"basic_over_m\": null"), std::string::npos);
  fs::remove_all(d);
}

TEST(OutputFiles, ContactJsonReadsBackToTheSameValues) {
  const fs::path d = scratch_dir("contact_round_trip");
  const sw::ContactResult back =
      round_trip(d / "contact.json", sample_contact_result(), sw::contact_json, sw::read_contact_result);
  EXPECT_FALSE(back.zone_edges.twist_at_rated_without_them_arcmin);
  EXPECT_NE(read_text(d / "contact.json").find("\"twist_at_rated_without_them_arcmin\": null"), std::string::npos);
  // The reconcile baseline's reader takes the same file: the loop's middle line with its step at zero.
  const sw::ContactCurve curve = sw::read_contact_curve(d / "contact.json");
  EXPECT_EQ(curve.middle_line.torque_Nm.size(), 4u);
  EXPECT_EQ(curve.catalog_t1_Nm, back.catalog.T1_Nm);
  fs::remove_all(d);
}

/// The message of the InputError `read` throws on `text` (written to result.json).
std::string result_json_error(const std::string& text) {
  const fs::path d = scratch_dir("result_error");
  std::ofstream(d / "result.json") << text;
  std::string message = "no error";
  try {
    (void)sw::read_fem_result(d / "result.json");
  } catch (const sw::InputError& e) {
    message = e.what();
  }
  fs::remove_all(d);
  return message;
}

TEST(OutputFiles, AResultJsonOfAnotherShapeIsOneLineNamingFileKeyAndValue) {
  std::string text = sw::fem_result_json(sample_fem_result());
  const std::string key = "\"equations\": ";
  const auto at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  text.replace(at + key.size(), text.find(',', at) - at - key.size(), "\"many\"");
  const std::string m = result_json_error(text);
  EXPECT_NE(m.find("result.json: solver.equations = \"many\"; expected a whole number in the result.json of "
                   "`strainwave fem`"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  std::string ranks = sw::fem_result_json(sample_fem_result());
  ranks.replace(ranks.find("\"ranks\": 2"), 10, "\"ranks\": 99999999999");
  EXPECT_NE(result_json_error(ranks).find("solver.ranks = 99999999999; expected a whole number in range"),
            std::string::npos) << result_json_error(ranks);
  const std::string missing = result_json_error(R"({"case": "x.toml"})");
  EXPECT_NE(missing.find("result.json: torque_Nm is missing; expected the result.json of `strainwave fem`"),
            std::string::npos) << missing;
  EXPECT_NE(result_json_error("[1, 2]").find("not a JSON object"), std::string::npos);
}

// Each output holds "case", the resolved case (load_case runs it again from the output), and "version"; the readers
// take them as written.
TEST(OutputFiles, EveryOutputHoldsTheCaseItRanAndTheToolsVersion) {
  const sw::Case c = sw::load_case("cases/seed_190_192.toml");
  const sw::Provenance p = sw::provenance_of(c);
  EXPECT_EQ(p.version, sw::tool_version());
  sw::FemResult fem = sample_fem_result();
  sw::BacklashResult backlash = sample_backlash_result();
  sw::ContactResult contact = sample_contact_result();
  fem.provenance = backlash.provenance = contact.provenance = p;
  const std::map<std::string, std::string> outputs = {
      {"result.json", sw::fem_result_json(fem)},
      {"backlash.json", sw::backlash_json(backlash)},
      {"contact.json", sw::contact_json(contact)},
      {"dynamics.json", sw::dynamics_json(sw::DynamicsResult{}, p)},
      {"reconcile.json", sw::reconcile_json(sw::reconcile::Report{}, p)}};
  const fs::path d = scratch_dir("provenance");
  for (const auto& [name, text] : outputs) {
    std::ofstream(d / name) << text;
    const nlohmann::json j = nlohmann::json::parse(text);
    EXPECT_EQ(j.at("version"), sw::tool_version()) << name;
    EXPECT_EQ(j.at("case"), nlohmann::json::parse(sw::case_json(c))) << name;
    EXPECT_EQ(sw::case_json(sw::load_case((d / name).string())), sw::case_json(c)) << name;
  }
  EXPECT_EQ(sw::read_fem_result(d / "result.json").provenance, p);
  EXPECT_EQ(sw::read_backlash_result(d / "backlash.json").provenance, p);
  EXPECT_EQ(sw::read_contact_result(d / "contact.json").provenance, p);
  EXPECT_NO_THROW((void)sw::read_dynamics_json(d / "dynamics.json"));
  EXPECT_NO_THROW((void)sw::read_reconcile_json(d / "reconcile.json"));
  fs::remove_all(d);
}

/// What cmake/write_version.cmake writes for the source tree `source` into `out` ("" when it failed).
std::string version_file(const fs::path& source, const fs::path& out) {
  const CommandRun r = run_shell(std::string(SW_CMAKE_COMMAND) + " -DSOURCE_DIR='" + source.string() + "' -DOUTPUT='" +
                                 out.string() + "' -P cmake/write_version.cmake");
  return r.exit_code == 0 ? read_text(out) : "";
}

// The version is `git describe --always --dirty` of the source tree, "unknown" for a tree outside git: a tarball,
// also one unpacked inside another repository. The file is rewritten only when its text changes (no rebuild).
TEST(ToolVersion, NamesTheCommitOrIsUnknownOutsideAGitTree) {
  const std::string version = sw::tool_version();
  ASSERT_FALSE(version.empty());
  const fs::path d = scratch_dir("version");
  const std::string unknown = "return \"unknown\";";
  EXPECT_NE(version_file(d, d / "version.cpp").find(unknown), std::string::npos);
  EXPECT_NE(version_file(fs::current_path() / "tests", d / "inside.cpp").find(unknown), std::string::npos);
  const auto written = fs::last_write_time(d / "version.cpp");
  (void)version_file(d, d / "version.cpp");
  EXPECT_EQ(fs::last_write_time(d / "version.cpp"), written);
  const CommandRun described = run_shell("git describe --always --dirty");
  if (described.exit_code == 0) {  // a git work tree: its description, and the build's names a commit of it
    const std::string now = described.out.substr(0, described.out.find('\n'));
    EXPECT_NE(version_file(fs::current_path(), d / "here.cpp").find("return \"" + now + "\";"), std::string::npos);
    ASSERT_NE(version, "unknown");
    std::string commit = version.substr(0, version.rfind("-dirty"));
    if (const auto g = commit.rfind("-g"); g != std::string::npos) commit = commit.substr(g + 2);
    EXPECT_EQ(run_shell("git cat-file -e '" + commit + "^{commit}'").exit_code, 0) << version;
  }
  fs::remove_all(d);
}

/// "" when the texts are the same, else the first line where they differ, from both.
std::string first_difference(const std::string& a, const std::string& b) {
  if (a == b) return "";
  std::istringstream sa(a), sb(b);
  std::string la, lb;
  for (int line = 1;; ++line) {
    const bool more_a = static_cast<bool>(std::getline(sa, la)), more_b = static_cast<bool>(std::getline(sb, lb));
    if (!more_a && !more_b) return "the same lines, other line ends";
    if (more_a != more_b || la != lb)
      return "line " + std::to_string(line) + ": written again `" + la + "`, the file `" + lb + "`";
  }
}

TEST(OutputFiles, FilesTheToolWroteReadAndWriteBackUnchanged) {
  const char* golden = std::getenv("SW_GOLDEN_DIR");
#ifdef SW_GOLDEN_DIR
  if (!golden) golden = SW_GOLDEN_DIR;
#endif
  if (!golden)
    GTEST_SKIP() << "set SW_GOLDEN_DIR (environment, or cmake -DSW_GOLDEN_DIR=) to a folder of "
                    "<case>/{result,backlash,contact}.json to read back";
  const std::map<std::string, std::function<std::string(const fs::path&)>> again = {
      {"result.json", [](const fs::path& p) { return sw::fem_result_json(sw::read_fem_result(p)); }},
      {"backlash.json", [](const fs::path& p) { return sw::backlash_json(sw::read_backlash_result(p)); }},
      {"contact.json", [](const fs::path& p) { return sw::contact_json(sw::read_contact_result(p)); }}};
  int files = 0;
  for (const auto& entry : fs::directory_iterator(golden)) {
    if (!entry.is_directory()) continue;
    for (const auto& [name, write_again] : again) {
      const fs::path file = entry.path() / name;
      if (!fs::exists(file)) continue;
      ++files;
      EXPECT_EQ(first_difference(write_again(file), read_text(file)), "") << file;
    }
  }
  EXPECT_GT(files, 0) << golden << " holds no <case>/{result,backlash,contact}.json";
}

}  // namespace
