// Designs the tool has never seen run to the end: `contact` on the designed cups of sizes 14 to 40, each with its rim
// (under the same teeth), body wall or diaphragm at 0.8×, 1.0× and 1.2× the design rule's thickness (42 runs), on a
// coarse mesh (element size d/20, one layer: the convergence of the iterations is what is tested, not the figures).
// Each run must end with its torque balanced at every step; a stop for a tolerance finer than anything physical (a size-20, ratio-120 cup with its
// rim 15 % thinner once died on a 0.05 nm mismatch of the generator bearing's secant at T = 5e-5 N·m) is a failure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sw::testing;

struct Variant {
  int size;
  const char* key;  ///< flexspline key scaled ("" for the design as it is)
  double factor;
};

/// The case text with `key = v` replaced by `key = factor·v`.
std::string scaled(const std::string& text, const std::string& key, double factor) {
  const std::regex line("(^|\n)" + key + " = ([0-9.eE+-]+)");
  std::smatch m;
  if (!std::regex_search(text, m, line)) throw std::runtime_error("the designed case has no " + key);
  std::ostringstream v;
  v.precision(12);
  v << std::stod(m[2].str()) * factor;
  return m.prefix().str() + m[1].str() + key + " = " + v.str() + m.suffix().str();
}

/// The case text with its [mesh] table (if any) replaced by a coarse one: element size d/20, one layer, no grading
/// toward the clamp corner (the corner is not what these runs test).
std::string coarse(const std::string& text, int size) {
  std::string out;
  std::istringstream in(text);
  bool in_mesh = false;
  for (std::string l; std::getline(in, l);) {
    if (!l.empty() && l[0] == '[') in_mesh = l == "[mesh]";
    if (!in_mesh) out += l + "\n";
  }
  std::ostringstream mesh;
  mesh << "\n[mesh]\nsize_mm = " << size * 2.54 / 20 << "\nwall_layers = 1\ncorner_levels = 0\n";
  return out + mesh.str();
}

/// The value of `key` in the case text.
double value_of(const std::string& text, const std::string& key) {
  const std::regex line("(^|\n)" + key + " = ([0-9.eE+-]+)");
  std::smatch m;
  if (!std::regex_search(text, m, line)) throw std::runtime_error("the designed case has no " + key);
  return std::stod(m[2].str());
}

/// The case text with the rim thickness scaled under the same teeth: the bore moves, the root circle stays (the teeth
/// sit on the rim's outside).
std::string scaled_rim(const std::string& text, double factor) {
  const double rim = value_of(text, "rim_thickness_mm"), bore = value_of(text, "inner_radius_mm");
  return scaled(scaled(text, "rim_thickness_mm", factor), "inner_radius_mm", (bore + (1 - factor) * rim) / bore);
}

class DesignVariant : public ::testing::TestWithParam<Variant> {};

TEST_P(DesignVariant, ContactRunsToTheEnd) {
  const Variant p = GetParam();
  const fs::path dir = fs::temp_directory_path() / ("sw_robust_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path designed = dir / "designed.toml", case_file = dir / "variant.toml";
  const CommandRun d = run_strainwave("design --size " + std::to_string(p.size) + " --out " + designed.string());
  ASSERT_EQ(d.exit_code, 0) << d.output;
  std::string text = read_text(designed);
  if (std::string(p.key) == "rim_thickness_mm") text = scaled_rim(text, p.factor);
  else if (*p.key) text = scaled(text, p.key, p.factor);
  std::ofstream(case_file) << coarse(text, p.size);
  const fs::path out = dir / "out";
  const CommandRun r = run_strainwave("contact --quiet --no-vtk " + case_file.string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto k = read_json(out / "contact.json");
  // The flanks' moments against the applied torque at every step: the contact solve's round-off, far below 1e-6.
  EXPECT_LT(k["torque_balance_error_rel"].get<double>(), 1e-6);
  const double twist = k["twist_at_rated_arcmin"].get<double>();
  EXPECT_TRUE(std::isfinite(twist) && twist > 0) << twist;
  std::printf("size %d, %s x %.1f: twist at rated %.3f arcmin, lost motion %.3f arcmin\n", p.size,
              *p.key ? p.key : "design", p.factor, twist, k["lost_motion_arcmin"].get<double>());
  fs::remove_all(dir);
}

std::vector<Variant> variants() {
  std::vector<Variant> v;
  for (int size : {14, 17, 20, 25, 32, 40}) {
    v.push_back({size, "", 1.0});
    for (const char* key : {"rim_thickness_mm", "wall_thickness_mm", "diaphragm_thickness_mm"})
      for (double f : {0.8, 1.2}) v.push_back({size, key, f});
  }
  return v;
}

INSTANTIATE_TEST_SUITE_P(Sizes14To40, DesignVariant, ::testing::ValuesIn(variants()),
                         [](const ::testing::TestParamInfo<Variant>& i) {
                           std::string key = *i.param.key ? i.param.key : "design";
                           key = key.substr(0, key.find("_thickness"));
                           return "size" + std::to_string(i.param.size) + "_" + key + "_" +
                                  std::to_string(static_cast<int>(std::lround(i.param.factor * 10)));
                         });

}  // namespace
