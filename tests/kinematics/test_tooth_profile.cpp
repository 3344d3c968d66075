// Involute tooth geometry: standard relations checked through independent routes (thickness formula vs the flank
// curves, outline vs the flank involute), not by restating the implementation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "gear/tooth_profile.hpp"

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kGeomTol = 1e-12;  // m: pure floating-point geometry on ~2e-2 m coordinates (1e4 ulp margin)

TEST(InverseInvolute, RecoversTwentyDegrees) {
  const double a = 20.0 * kPi / 180.0;
  EXPECT_NEAR(sw::inverse_involute(std::tan(a) - a), a, 1e-14);
}

TEST(GearRadii, SeedSetMatchesHandComputedShaperCutting) {
  // Hand computation (α = 20°, m = 0.2 mm, z_f = 190, z_0 = 80, x_f = 1.52, x_c = 1.57, h_a* = 1, c* = 0.25):
  // inv α_w0 = 0.0149044 + 2·0.3639702·1.52/270 = 0.0190025 → α_w0 = 21.624°, a_0 = 27·cos20°/cos α_w0 = 27.2925 mm,
  // r_rf = a_0 − 8.25 = 19.0425 mm, r_af = 19 + 0.2·2.52 = 19.504 mm, r_ac = 19.2 − 0.2·(1 − 1.57) = 19.314 mm,
  // r_rc = 19.2 + 0.2·2.82 = 19.764 mm.
  const sw::GearRadii r = sw::gear_radii(sw::GearParams{});
  EXPECT_NEAR(r.cutter_pressure_angle_rad * 180 / kPi, 21.624, 1e-3);
  EXPECT_NEAR(r.cutter_centre_distance * 1e3, 27.2925, 1e-4);
  EXPECT_NEAR(r.root_f * 1e3, 19.0425, 1e-4);
  EXPECT_NEAR(r.tip_f * 1e3, 19.504, 1e-12);
  EXPECT_NEAR(r.tip_c * 1e3, 19.314, 1e-12);
  EXPECT_NEAR(r.root_c * 1e3, 19.764, 1e-12);
  EXPECT_GT(r.form_f, r.root_f);
  EXPECT_LT(r.form_f, r.tip_f);
}

TEST(GearRadii, RejectsCircularSplineWithFewerTeeth) {
  sw::GearParams g;
  g.teeth_circular = 188;
  try {
    sw::gear_radii(g);
    FAIL() << "no throw";
  } catch (const sw::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("teeth_circular = 188"), std::string::npos) << e.what();
  }
}

TEST(ToothThickness, EqualsTheChordOfTheFlankCurvesAtEveryRadius) {
  const sw::GearParams g;
  const sw::Involute f = sw::flexspline_flank(g);
  // Reference circle: s = m(π/2 + 2 x tan α).
  EXPECT_NEAR(sw::flexspline_tooth_thickness(g, 0.019), 0.2e-3 * (kPi / 2 + 2 * 1.52 * std::tan(20 * kPi / 180)), kGeomTol);
  for (double u = f.u_min; u <= f.u_max; u += (f.u_max - f.u_min) / 7) {
    const Eigen::Vector2d p = sw::involute_point(f, u);  // ccw flank; tooth symmetric about +x
    const double R = p.norm();
    EXPECT_NEAR(sw::flexspline_tooth_thickness(g, R), 2 * R * std::atan2(p.y(), p.x()), kGeomTol);
  }
}

TEST(InvoluteDistance, IsTheEuclideanDistanceAlongTheNormal) {
  const sw::Involute f = sw::flexspline_flank(sw::GearParams{});
  const double u = 0.5 * (f.u_min + f.u_max);
  const Eigen::Vector2d p = sw::involute_point(f, u);
  const Eigen::Vector2d t = sw::involute_tangent(f, u).normalized();
  const Eigen::Vector2d n(-t.y(), t.x());  // left of the tangent (u increasing = radius increasing): increasing polar angle
  for (double d : {-3e-5, -1e-6, 0.0, 2e-6, 4e-5}) {
    const sw::InvoluteDistance id = sw::involute_signed_distance(f, p + d * n);
    EXPECT_NEAR(id.distance_m, d, kGeomTol);
    EXPECT_NEAR(id.foot_roll, u, 1e-9);
  }
}

TEST(FlexsplineOutline, IsAClosedStarShapedCounterClockwiseCurveOnTheFlanks) {
  const sw::GearParams g;
  const auto r = sw::gear_radii(g);
  const sw::Involute f = sw::flexspline_flank(g);
  const auto pts = sw::flexspline_outline(g, 12);
  ASSERT_GT(pts.size(), static_cast<size_t>(g.teeth_flexspline * 24));
  double area = 0, prev = std::atan2(pts.back().y(), pts.back().x()), turned = 0;
  int on_flank = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const auto& a = pts[i];
    const auto& b = pts[(i + 1) % pts.size()];
    area += 0.5 * (a.x() * b.y() - a.y() * b.x());
    double ang = std::atan2(a.y(), a.x());
    while (ang < prev - kPi) ang += 2 * kPi;
    EXPECT_GE(ang, prev - 1e-12) << "polar angle must not decrease (simple, star-shaped outline) at point " << i;
    turned += ang - prev;
    prev = ang;
    const double R = a.norm();
    EXPECT_GE(R, r.root_f - kGeomTol);
    EXPECT_LE(R, r.tip_f + kGeomTol);
    // Points on a ccw flank of some tooth lie on the involute (rotated to that tooth).
    const double k = std::round(ang / (2 * kPi / g.teeth_flexspline));
    const Eigen::Vector2d q = Eigen::Rotation2Dd(-k * 2 * kPi / g.teeth_flexspline) * a;
    if (R > r.form_f + 1e-9 && q.y() > 0 && std::abs(sw::involute_signed_distance(f, q).distance_m) < 1e-15) ++on_flank;
  }
  EXPECT_NEAR(turned, 2 * kPi, 1e-9);
  EXPECT_GT(area, kPi * r.root_f * r.root_f);
  EXPECT_LT(area, kPi * r.tip_f * r.tip_f);
  EXPECT_GE(on_flank, g.teeth_flexspline * 10);  // 12 flank points per flank, ≥ 10 strictly above the form radius
}

// The tooth layer's solidity φ(r) against two independent statements of the same teeth: on the involute it is the
// circular tooth thickness over the pitch at r (the thickness formula, not the outline); integrated over the layer,
// ∫ φ(r) 2πr dr is the teeth's area above the root circle, the outline polygon's shoelace area less the root disc.
// The polygon's chords (400 points a flank) miss about 1e-6 of the tooth's area; the trapezoid rule on 4000 radii
// about 1e-6 too (the fillet's square-root ends): 1e-4 is loose by two decades and still fails on a wrong fillet.
TEST(FlexsplineSolidity, IsTheToothThicknessOverThePitchAndIntegratesToTheTeethsArea) {
  const sw::GearParams g;
  const auto r = sw::gear_radii(g);
  const double pitch = 2 * kPi / g.teeth_flexspline;
  for (const double R : {r.form_f + 1e-6, 0.5 * (r.form_f + r.tip_f), r.tip_f - 1e-6, r.tip_f})
    EXPECT_NEAR(sw::flexspline_solidity(g, R), sw::flexspline_tooth_thickness(g, R) / (R * pitch), 1e-12) << R;
  EXPECT_EQ(sw::flexspline_solidity(g, r.root_f - 1e-6), 1.0);
  EXPECT_EQ(sw::flexspline_solidity(g, r.tip_f + 1e-6), 0.0);
  const auto pts = sw::flexspline_outline(g, 400);
  double polygon = 0;
  for (size_t i = 0; i < pts.size(); ++i) {
    const auto& a = pts[i];
    const auto& b = pts[(i + 1) % pts.size()];
    polygon += 0.5 * (a.x() * b.y() - a.y() * b.x());
  }
  const double teeth = polygon - kPi * r.root_f * r.root_f;
  const int n = 4000;
  double integral = 0;
  for (int i = 0; i <= n; ++i) {
    const double R = r.root_f + (r.tip_f - r.root_f) * i / n;
    integral += (i == 0 || i == n ? 0.5 : 1.0) * sw::flexspline_solidity(g, R) * 2 * kPi * R;
  }
  integral *= (r.tip_f - r.root_f) / n;
  EXPECT_NEAR(integral / teeth, 1.0, 1e-4);
}

}  // namespace
