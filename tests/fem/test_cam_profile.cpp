// The cam's surface: a listed cam sampled from the polar or the elliptic form agrees with it (radius and the normal's
// tilt, to the cubic spline's error), and the ellipse lies inside the polar form by 1.5·w0²/r at ±45°, touching it at
// the axes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "generator/cam_profile.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kR = 18.4e-3, kW0 = 0.2e-3;

Cam cam(CamProfile p) { return Cam{p}; }

Cam listed_from(const CamSurface& s, double step_deg) {
  Cam c = cam(CamProfile::List);
  for (double deg = 0; deg < 180 - 1e-9; deg += step_deg) c.points.push_back({deg * kPi / 180, s.radius_m(deg * kPi / 180)});
  return c;
}

// Points every 5°: the periodic cubic spline's error is h⁴·max|ρ''''|/384 = (5°)⁴·16·w0/384 ≈ 2.4e-6·w0 in radius and
// of order h³ in slope; bounds 1e-5·w0 and 1e-3 of the largest tilt.
TEST(CamProfile, AListSampledFromPolarOrEllipseIsThatCam) {
  for (const CamProfile p : {CamProfile::Polar, CamProfile::Ellipse}) {
    const CamSurface exact(cam(p), kW0, kR), listed(listed_from(exact, 5.0), kW0, kR);
    const double tilt_max = 2 * kW0 / (kR - kW0);
    double worst_r = 0, worst_t = 0;
    for (double deg = -180; deg <= 180; deg += 0.7) {
      const double t = deg * kPi / 180;
      worst_r = std::max(worst_r, std::abs(listed.standoff_m(t) - exact.standoff_m(t)));
      worst_t = std::max(worst_t, std::abs(listed.tilt(t) - exact.tilt(t)));
    }
    EXPECT_LT(worst_r, 1e-5 * kW0);
    EXPECT_LT(worst_t, 1e-3 * tilt_max);
    EXPECT_NEAR(listed.standoff_m(0.0), kW0, 1e-15);  // at a knot: the listed radius
  }
}

// The tilt is ρ'/ρ: against a central difference of the radius, for each form.
TEST(CamProfile, TiltIsTheRadiusSlopeOverTheRadius) {
  const CamSurface polar(cam(CamProfile::Polar), kW0, kR), ellipse(cam(CamProfile::Ellipse), kW0, kR);
  const CamSurface listed(listed_from(ellipse, 10.0), kW0, kR);
  for (const CamSurface* s : {&polar, &ellipse, &listed})
    for (double deg = 3; deg < 360; deg += 17) {
      const double t = deg * kPi / 180, h = 1e-6;
      const double fd = (s->radius_m(t + h) - s->radius_m(t - h)) / (2 * h) / s->radius_m(t);
      EXPECT_NEAR(s->tilt(t), fd, 1e-7 * 2 * kW0 / kR) << deg;
    }
}

// Ellipse vs polar: equal at the axes, the ellipse inside by 1.5·w0²/r·sin²2θ to leading order (w0/r ≈ 1 %: the next
// order is a further 1 % of it).
TEST(CamProfile, EllipseLiesInsideThePolarFormBySecondOrder) {
  const CamSurface polar(cam(CamProfile::Polar), kW0, kR), ellipse(cam(CamProfile::Ellipse), kW0, kR);
  for (const double deg : {0.0, 90.0, 180.0}) EXPECT_NEAR(ellipse.radius_m(deg * kPi / 180), polar.radius_m(deg * kPi / 180), 1e-15);
  for (double deg = 5; deg < 90; deg += 5) {
    const double t = deg * kPi / 180, s2 = std::sin(2 * t);
    EXPECT_NEAR(polar.radius_m(t) - ellipse.radius_m(t), 1.5 * kW0 * kW0 / kR * s2 * s2, 0.03 * 1.5 * kW0 * kW0 / kR) << deg;
  }
}

}  // namespace
}  // namespace sw
