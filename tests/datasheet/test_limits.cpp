// The datasheet's limits that stand on the loaded contact: the generator's ball loads from its stations' forces, and
// the teeth's root limit (its pulsating allowable stress, the contact it is read on).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>

#include "common/error.hpp"
#include "datasheet/limits.hpp"
#include "gear/tooth_root.hpp"

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

// A station on the major axis puts its partner's piece at θ = π and the period's closing point at exactly 2π, where
// the last ball's arc ends: the line load there is read from the last piece (it was read one past the list's end, so
// the life of size 14 at ratio 100 came out 23,580 or 31,365 h from run to run with the same loads). A load that is
// linear between the stations gives each ball its arc's share by hand: P(θ) = P0 + P1·cos θ over the half turn's
// stations and their partners, the balls' sum the stations' 2·ΣP and the ball on the major axis the same in a list
// rotated by a whole station (the closing point then falls elsewhere).
TEST(BallLoads, TheClosingPointOfThePeriodIsReadOnTheLastPiece) {
  const BodyStations s = stations_over_half_turn(12);
  std::vector<double> p;
  for (double a : s.angle_rad) p.push_back(100.0 + 40.0 * std::cos(a));
  const std::vector<double> Q = ball_loads_N(s, p, 12);
  const double stations = 2 * std::accumulate(p.begin(), p.end(), 0.0);
  EXPECT_NEAR(std::accumulate(Q.begin(), Q.end(), 0.0) / stations, 1.0, 1e-12);
  BodyStations shifted = s;  // the same stations listed from the second one, the first moved a half turn on
  std::rotate(shifted.angle_rad.begin(), shifted.angle_rad.begin() + 1, shifted.angle_rad.end());
  shifted.angle_rad.back() += kPi;
  std::vector<double> q = p;
  std::rotate(q.begin(), q.begin() + 1, q.end());
  const std::vector<double> R = ball_loads_N(shifted, q, 12);
  for (std::size_t b = 0; b < Q.size(); ++b) EXPECT_NEAR(R[b], Q[b], 1e-9 * Q[0]) << "ball " << b;
}

// Goodman's line under a pulsating cycle 0..σ (σ_a = σ_m = σ/2): σ = 2/(1/S_e + 1/S_u).
TEST(ToothRoot, PulsatingAllowableIsOnGoodmansLine) {
  const double s = pulsating_allowable_stress_Pa(500e6, 1100e6);
  EXPECT_NEAR(s / 2 / 500e6 + s / 2 / 1100e6, 1.0, 1e-12);
  EXPECT_NEAR(s, 687.5e6, 1e-3);
}

// The root limit on a face in three sections (the ends a quarter of the face each, the centre a half), by hand: each
// loaded contact's ISO 6336-3 stress at its own radius over its own band; the largest stands. Here the same force on
// the centre (half the face) and on an end (a quarter) at one radius: the end's, twice the centre's, stands; a larger
// force at a radius below the root's critical section (the method's arm ≤ 0) is left out and counted, not a failure.
TEST(ToothRoot, TheLimitIsTheLargestContactStressOverItsOwnBandOfTheFace) {
  GearParams g;  // the designed size 17 at ratio 100
  g.module_m = 0.2159e-3;
  g.teeth_flexspline = 200;
  g.teeth_circular = 202;
  g.profile_shift_flexspline = 1.52;
  g.profile_shift_circular = 1.69;
  g.addendum_coefficient_flexspline = g.addendum_coefficient_circular = 0.7;
  g.dedendum_coefficient_flexspline = g.dedendum_coefficient_circular = 0.95;
  FlexsplineParams f;
  f.rim_width_m = 6.477e-3;
  f.rim_thickness_m = 0.60452e-3;
  Material m;
  m.fatigue_limit_Pa = 500e6;
  m.ultimate_strength_Pa = 1100e6;
  const SpurTeeth teeth = flexspline_teeth(g);
  const double r_on = spur_tip_radius_m(teeth, false) - 0.05e-3, base = teeth.module_m * 100 * std::cos(g.pressure_angle_rad);
  const double r_low = base * 1.0005;
  EXPECT_THROW(external_root_form(teeth, r_low), InputError);  // the premise: below the critical section
  ContactAnalysis a;
  a.face_slices = 3;
  a.rated_torque_Nm = 31;
  for (const auto& [slice, r] : {std::pair{1, r_on}, std::pair{0, r_on}, std::pair{2, r_low}}) {
    FlankContact c;
    c.slice = slice;
    c.contact_radius_m = r;
    a.flanks.push_back(c);
  }
  TorqueStep rated;
  rated.torque_Nm = 31;
  rated.flank_force_N = {100, 100, 400};
  a.steps = {rated};
  const ToothRootFigure t = tooth_root_limit(g, f, m, a);
  RootStressFactors y;
  y.rim_thickness = rim_thickness_factor(f.rim_thickness_m, 1.65 * g.module_m);
  const double end = nominal_root_stress_Pa(external_root_form(teeth, r_on), g.module_m,
                                            100 * std::cos(g.pressure_angle_rad), f.rim_width_m / 4, y);
  std::printf("root stress at rated %.1f MPa (an end section's contact, by hand %.1f); %s\n", t.root_stress_at_rated_Pa / 1e6,
              end / 1e6, t.method.c_str());
  EXPECT_NEAR(t.root_stress_at_rated_Pa / end, 1.0, 1e-12);
  EXPECT_NEAR(t.torque_Nm, 31 * pulsating_allowable_stress_Pa(500e6, 1100e6) / end, 1e-9 * t.torque_Nm);
  EXPECT_NE(t.method.find("1 loaded contacts below the root's critical section left out"), std::string::npos) << t.method;
  // Only contacts below the critical section: nothing to read, an infinite limit.
  a.steps.front().flank_force_N = {0, 0, 400};
  EXPECT_TRUE(std::isinf(tooth_root_limit(g, f, m, a).torque_Nm));
}

// ISO 6336-3's Y_B is defined for a rim thicker than half the tooth depth. The designed rim (0.014 d) under the teeth of
// ratio 100 is 1.70 of their depth; at ratio 30 (a module 3.33 times larger) the same rim is 0.51 of it, and at the
// thin end of Ivanov's range 0.40: outside the method, which the datasheet then says instead of stopping.
TEST(ToothRoot, ARimThinnerThanHalfTheToothDepthIsOutsideTheMethodAndSaysSo) {
  GearParams g;
  g.addendum_coefficient_flexspline = 0.7;
  g.dedendum_coefficient_flexspline = 0.95;
  FlexsplineParams f;
  g.module_m = 0.2159e-3;  // size 17, ratio 100: depth 0.356 mm
  f.rim_thickness_m = 0.60452e-3;
  EXPECT_EQ(tooth_root_not_covered(g, f), "");
  g.module_m = 0.719666667e-3;  // size 17, ratio 30: depth 1.187 mm
  EXPECT_EQ(tooth_root_not_covered(g, f), "");  // 0.509
  f.rim_thickness_m = 0.47498e-3;  // --rim-per-d 0.011: 0.400
  const std::string why = tooth_root_not_covered(g, f);
  EXPECT_EQ(why, "not computed: the rim under the teeth (0.475 mm) is 0.40 of their depth (1.187 mm), and ISO "
                 "6336-3's rim factor Y_B covers rims thicker than 0.5 of it");
  EXPECT_THROW(rim_thickness_factor(f.rim_thickness_m, 1.65 * g.module_m), InputError);  // the method itself refuses
  f.rim_thickness_m = 0.5 * 1.65 * g.module_m;  // exactly at the limit: outside (the standard's bound is strict)
  EXPECT_NE(tooth_root_not_covered(g, f), "");
}

}  // namespace
}  // namespace sw
