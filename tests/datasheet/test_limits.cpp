// The datasheet's limits that stand on the loaded contact: the generator's ball loads from its stations' forces, and
// the teeth's pulsating allowable root stress.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>

#include "datasheet/limits.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;

BodyStations stations_over_half_turn(int pairs) {
  BodyStations s;
  s.unilateral = true;
  s.half_width_rad = kPi / pairs;
  for (int j = 0; j < pairs; ++j) s.angle_rad.push_back(j * s.half_width_rad);
  return s;
}

// Equal station forces P: the line load is P/Δ everywhere, each ball carries (P/Δ)·2π/Z, and the balls carry the
// stations' whole force 2·m·P exactly (round-off).
TEST(BallLoads, EqualStationForcesSpreadEquallyOverTheBalls) {
  const BodyStations s = stations_over_half_turn(24);
  const std::vector<double> p(24, 150.0);
  const std::vector<double> Q = ball_loads_N(s, p, 23);
  for (double q : Q) EXPECT_NEAR(q, 150.0 / s.half_width_rad * 2 * kPi / 23, 1e-9);
  EXPECT_NEAR(std::accumulate(Q.begin(), Q.end(), 0.0), 2 * 24 * 150.0, 1e-9);
}

// A generator's two-lobed load p(θ) = max(0, cos 2θ)·P on 48 stations: the balls carry the stations' whole force (each
// its arc's share, exactly up to round-off), the largest ball sits at the major axis and the minor axis carries nothing.
TEST(BallLoads, ATwoLobedLoadKeepsItsTotalAndItsPeakAtTheMajorAxis) {
  const BodyStations s = stations_over_half_turn(48);
  std::vector<double> p;
  for (double a : s.angle_rad) p.push_back(std::max(0.0, std::cos(2 * a)) * 200.0);
  const std::vector<double> Q = ball_loads_N(s, p, 24);
  const double stations = 2 * std::accumulate(p.begin(), p.end(), 0.0);
  EXPECT_NEAR(std::accumulate(Q.begin(), Q.end(), 0.0) / stations, 1.0, 1e-12);
  EXPECT_EQ(std::max_element(Q.begin(), Q.end()) - Q.begin(), 0);
  EXPECT_NEAR(Q[6], 0.0, 1e-9);  // the minor axis (a quarter turn on) carries nothing
}

// Goodman's line under a pulsating cycle 0..σ (σ_a = σ_m = σ/2): σ = 2/(1/S_e + 1/S_u).
TEST(ToothRoot, PulsatingAllowableIsOnGoodmansLine) {
  const double s = pulsating_allowable_stress_Pa(500e6, 1100e6);
  EXPECT_NEAR(s / 2 / 500e6 + s / 2 / 1100e6, 1.0, 1e-12);
  EXPECT_NEAR(s, 687.5e6, 1e-3);
}

}  // namespace
}  // namespace sw
