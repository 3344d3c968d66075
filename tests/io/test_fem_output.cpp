// neutral_curve.csv: what `strainwave fem` writes is what the backlash stage reads back (reader beside the writer),
// and a file of another shape is refused with its name and line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/error.hpp"
#include "io/fem_output.hpp"

namespace {

TEST(NeutralCurveCsv, ReadsBackWhatTheWriterWrote) {
  sw::NeutralCurveSamples nc;
  nc.radius_m = 18.72e-3;
  nc.z_m = 11.7e-3;
  for (int k = 0; k < 360; ++k) {
    const double p = k * 3.141592653589793 / 180.0;
    nc.phi_rad.push_back(p);
    nc.w_wg_m.push_back(2e-4 * std::cos(2 * p));
    nc.v_wg_m.push_back(-1e-4 * std::sin(2 * p));
    nc.mu_wg_rad.push_back(0.02 * std::sin(2 * p));
    nc.w_comb_m.push_back(2e-4 * std::cos(2 * p) + 1e-7);
    nc.v_comb_m.push_back(-1e-4 * std::sin(2 * p) + 7.7e-6);
    nc.mu_comb_rad.push_back(0.02 * std::sin(2 * p) + 4e-4);
  }
  const auto path = std::filesystem::temp_directory_path() / "sw_test_neutral_curve_roundtrip.csv";
  { std::ofstream(path) << sw::neutral_curve_csv(nc); }
  const sw::NeutralCurveSamples back = sw::read_neutral_curve_csv(path);
  std::filesystem::remove(path);
  ASSERT_EQ(back.phi_rad.size(), 360u);
  EXPECT_NEAR(back.radius_m, nc.radius_m, 1e-12);
  EXPECT_NEAR(back.z_m, nc.z_m, 1e-12);
  // The writer prints 10 significant digits (%.9e): relative 5e-10 of each value.
  for (size_t k = 0; k < 360; k += 17) {
    EXPECT_NEAR(back.w_wg_m[k], nc.w_wg_m[k], 1e-13);
    EXPECT_NEAR(back.v_comb_m[k], nc.v_comb_m[k], 1e-13);
    EXPECT_NEAR(back.mu_comb_rad[k], nc.mu_comb_rad[k], 1e-11);
  }
}

TEST(NeutralCurveCsv, RefusesAWrongHeaderNamingTheFileAndLine) {
  const auto path = std::filesystem::temp_directory_path() / "sw_test_bad_curve.csv";
  { std::ofstream(path) << "phi,w\n0,0\n"; }
  try {
    sw::read_neutral_curve_csv(path);
    FAIL() << "no throw";
  } catch (const sw::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string() + ":1: header must be"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

TEST(NeutralCurveCsv, RefusesANonNumericValueNamingTheLineAndColumn) {
  const auto path = std::filesystem::temp_directory_path() / "sw_test_bad_value.csv";
  { std::ofstream(path) << "phi_rad,w_wg_m,v_wg_m,mu_wg_rad,w_comb_m,v_comb_m,mu_comb_rad\n0,0,0,0,0,0,0\n0,1,x,0,0,0,0\n"; }
  try {
    sw::read_neutral_curve_csv(path);
    FAIL() << "no throw";
  } catch (const sw::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path.string() + ":3: column 3 = 'x'"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}

}  // namespace
