// The torque–twist curve read back from contact.json: the middle line of the loop is exact for piecewise-linear
// branches (any torque, not only the points), a dead band stays a step, and bad files give one line naming the key.
// twist_at on the one curve type (contact/torque_twist.hpp): a step's middle, the first segment holding a torque, the
// ends extended only within the tolerance asked for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "contact/torque_twist.hpp"
#include "io/contact_output.hpp"

namespace fs = std::filesystem;
using sw::InputError;

namespace {

// The size-17 catalog law (shared/reference: K1 1.0e4, K2 1.4e4, K3 1.6e4 N*m/rad; T1 3.9, T2 12 N*m; rated 31 N*m).
constexpr double kK1 = 1.0e4, kK2 = 1.4e4, kK3 = 1.6e4, kT1 = 3.9, kT2 = 12.0, kRated = 31.0;
/// Interpolation of straight segments and the mean of two of them: exact but for rounding.
constexpr double kExact = 1e-14;

double law(double T) {
  const double a = std::abs(T);
  const double phi = std::min(a, kT1) / kK1 + std::clamp(a - kT1, 0.0, kT2 - kT1) / kK2 + std::max(a - kT2, 0.0) / kK3;
  return T < 0 ? -phi : phi;
}

/// A contact.json with the given points (torque, twist) in order.
fs::path write_contact(const std::string& name, const std::vector<std::pair<double, double>>& points) {
  nlohmann::json j;
  j["rated_torque_Nm"] = kRated;
  j["catalog"] = {{"T1_Nm", kT1}, {"T2_Nm", kT2}, {"K1_Nm_per_rad", kK1}, {"K2_Nm_per_rad", kK2}, {"K3_Nm_per_rad", kK3}};
  j["torque_twist"] = nlohmann::json::array();
  for (const auto& [t, phi] : points)
    j["torque_twist"].push_back({{"torque_Nm", t}, {"twist_rad", phi}, {"pairs_in_contact", 10}, {"max_pair_force_N", 1.0}});
  const fs::path p = fs::temp_directory_path() / ("sw_contact_curve_" + name + ".json");
  std::ofstream(p) << j.dump(1);
  return p;
}

std::string message_of(const std::string& path) {
  try {
    sw::read_contact_curve(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(TorqueTwistCurve, LoopOfTwoShiftedBranchesOnDifferentTorquesHasTheLawAsItsMiddleLine) {
  // Loading branch the law minus h/2 on one torque grid, unloading the law plus h/2 on another (from the top, where
  // the twist steps up by h): each branch is straight between its points only where the law is, so both grids hold
  // the breakpoints ±T1, ±T2.
  const double h = 1e-4;
  std::vector<std::pair<double, double>> pts;
  for (double t : {-31.0, -20.0, -12.0, -3.9, 0.0, 3.9, 7.0, 12.0, 31.0}) pts.emplace_back(t, law(t) - h / 2);
  for (double t : {31.0, 25.0, 12.0, 3.9, -3.9, -8.0, -12.0, -31.0}) pts.emplace_back(t, law(t) + h / 2);
  const sw::ContactCurve read = sw::read_contact_curve(write_contact("loop", pts));
  EXPECT_EQ(read.rated_torque_Nm, kRated);
  EXPECT_EQ(read.catalog_t1_Nm, kT1);
  EXPECT_EQ(read.catalog_t2_Nm, kT2);
  const sw::TorqueTwist& c = read.middle_line;
  EXPECT_EQ(c.torque_Nm.front(), -31.0);
  EXPECT_EQ(c.torque_Nm.back(), 31.0);
  for (double t = -31.0; t <= 31.0; t += 0.37) EXPECT_NEAR(sw::twist_at(c, t), law(t), kExact) << t;
  EXPECT_NEAR(sw::twist_at(c, 31.0), law(31.0), kExact);
}

TEST(TorqueTwistCurve, ALoadingBranchAloneIsTheCurve) {
  std::vector<std::pair<double, double>> pts;
  for (double t : {-31.0, -12.0, -3.9, 0.0, 3.9, 12.0, 31.0}) pts.emplace_back(t, law(t));
  const sw::TorqueTwist c = sw::read_contact_curve(write_contact("loading", pts)).middle_line;
  ASSERT_EQ(c.torque_Nm.size(), 7u);
  for (double t : {-30.0, -5.0, 0.1, 2.0, 11.9, 30.9}) EXPECT_NEAR(sw::twist_at(c, t), law(t), kExact) << t;
}

TEST(TorqueTwistCurve, ADeadBandAtZeroTorqueStaysAStep) {
  // Play of width p: the twist jumps by p at zero torque on the loading branch (two points at T = 0).
  const double p = 5e-5;
  auto with_play = [&](double t, bool upper) { return law(t) + (t > 0 || (t == 0 && upper) ? p / 2 : -p / 2); };
  std::vector<std::pair<double, double>> pts;
  for (double t : {-31.0, -3.9, 0.0}) pts.emplace_back(t, with_play(t, false));
  for (double t : {0.0, 3.9, 31.0}) pts.emplace_back(t, with_play(t, true));
  const sw::TorqueTwist c = sw::read_contact_curve(write_contact("play", pts)).middle_line;
  EXPECT_NEAR(sw::twist_at(c, -1e-9), -p / 2, 1e-12);
  EXPECT_NEAR(sw::twist_at(c, 1e-9), p / 2, 1e-12);
  EXPECT_NEAR(sw::twist_at(c, 0.0), 0.0, kExact);  // at the step: its middle
  EXPECT_NEAR(sw::twist_at(c, 2.0), law(2.0) + p / 2, kExact);
}

TEST(TorqueTwistCurve, BeyondItsEndsIsAnErrorNamingTheRangeUnlessWithinTheTolerance) {
  const sw::TorqueTwist c =
      sw::read_contact_curve(write_contact("ends", {{-31.0, law(-31.0)}, {0.0, 0.0}, {31.0, law(31.0)}})).middle_line;
  try {
    sw::twist_at(c, 35.0);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("torque 35 N*m is beyond the torque-twist curve, which covers [-31, 31] N*m"), std::string::npos) << m;
  }
  // Within the tolerance the last segment goes on straight.
  EXPECT_NEAR(sw::twist_at(c, 31.2, 0.31), law(31.0) * 31.2 / 31.0, kExact);
  EXPECT_THROW(sw::twist_at(c, -31.4, 0.31), InputError);
}

TEST(TorqueTwistCurve, BadFilesGiveOneLineNamingTheKey) {
  EXPECT_NE(message_of("/nonexistent/contact.json").find("/nonexistent/contact.json: cannot be read; give the "
                                                         "contact.json written by `strainwave contact"),
            std::string::npos);
  const fs::path no_rated = fs::temp_directory_path() / "sw_contact_curve_no_rated.json";
  std::ofstream(no_rated) << R"({"torque_twist": [{"torque_Nm": 0, "twist_rad": 0}, {"torque_Nm": 1, "twist_rad": 1e-4}]})";
  EXPECT_NE(message_of(no_rated.string()).find(no_rated.string() + ": rated_torque_Nm is missing; expected the "
                                                "contact.json of `strainwave contact`"), std::string::npos)
      << message_of(no_rated.string());
  const fs::path no_twist = fs::temp_directory_path() / "sw_contact_curve_no_twist.json";
  std::ofstream(no_twist) << R"({"rated_torque_Nm": 31, "torque_twist": [{"torque_Nm": 0, "twist_rad": 0}, {"torque_Nm": 1}]})";
  EXPECT_NE(message_of(no_twist.string()).find("torque_twist[1].twist_rad is missing"), std::string::npos)
      << message_of(no_twist.string());
  const fs::path text_twist = fs::temp_directory_path() / "sw_contact_curve_text_twist.json";
  std::ofstream(text_twist)
      << R"({"rated_torque_Nm": 31, "torque_twist": [{"torque_Nm": 0, "twist_rad": 0}, {"torque_Nm": 1, "twist_rad": "x"}]})";
  EXPECT_NE(message_of(text_twist.string()).find(text_twist.string() + ": torque_twist[1].twist_rad = \"x\"; expected "
                                                 "a finite number"), std::string::npos)
      << message_of(text_twist.string());
  // Rising, falling, then rising again: not one loop.
  const std::string zigzag =
      write_contact("zigzag", {{-31, 0}, {0, 0}, {31, 1e-3}, {0, 0}, {10, 1e-4}, {-31, -1e-3}}).string();
  EXPECT_NE(message_of(zigzag).find("torque_twist[4].torque_Nm = 10 after 0 rises again on the unloading branch"),
            std::string::npos)
      << message_of(zigzag);
  // Starting at the top and falling: the loading branch must come first.
  const std::string falling = write_contact("falling", {{31, 1e-3}, {0, 0}, {-31, -1e-3}}).string();
  EXPECT_NE(message_of(falling).find("torque_twist[1].torque_Nm = 0 after 31 falls at the start"), std::string::npos)
      << message_of(falling);
  const fs::path not_json = fs::temp_directory_path() / "sw_contact_curve_not_json.json";
  std::ofstream(not_json) << "torque,twist\n";
  EXPECT_NE(message_of(not_json.string()).find("not valid JSON"), std::string::npos);
}

// The analysis samples its curve with two points at zero torque (the dead band's limits): between them twist_at gives
// the step's middle, and at one of its own points the segment that ends there, as the curve's readings (lost motion,
// the segment law) have always read it.
TEST(TorqueTwist, TwistAtReadsAStepByItsMiddleAndAPointByTheSegmentEndingThere) {
  const sw::TorqueTwist c{{-2.0, -1.0, 0.0, 0.0, 1.0, 3.0}, {-4e-4, -3e-4, -1e-4, 1e-4, 2e-4, 5e-4}};
  EXPECT_EQ(sw::twist_at(c, 0.0), 0.0);                  // the step's middle
  EXPECT_EQ(sw::twist_at(c, 1.0), 1e-4 + 1.0 * (2e-4 - 1e-4));  // along (0, 1], at its end
  EXPECT_NEAR(sw::twist_at(c, 2.0), 3.5e-4, kExact);     // inside a segment
  EXPECT_EQ(sw::twist_at(c, -2.0), -4e-4);               // an end: its own point
  EXPECT_EQ(sw::twist_at(c, 3.0), 5e-4);
  const auto [left, right] = sw::twist_limits(c, 0.0);
  EXPECT_EQ(left, -1e-4);
  EXPECT_EQ(right, 1e-4);
}

// Without a point at zero torque the curve is read as everywhere else: linearly between its neighbours.
TEST(TorqueTwist, TwistAtZeroWithoutAPointThereInterpolates) {
  const sw::TorqueTwist c{{-1.0, 3.0}, {-1e-4, 3e-4}};
  EXPECT_NEAR(sw::twist_at(c, 0.0), 0.0, kExact);
}
