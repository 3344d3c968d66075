// The circular spline's torsional compliance: the closed form against an independent integration of the shear flow.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/error.hpp"
#include "contact/circular_spline.hpp"
#include "gear/tooth_profile.hpp"

namespace sw {
namespace {

TEST(CircularSpline, ClosedFormEqualsTheIntegratedShearFlow) {
  // The torque T passes every circle r as the shear stress τ = T/(2π·r²·b); the shear strain γ = τ/G turns the
  // circle r against r + dr by dφ = γ·dr/r. Integrate from the root circle to the fixed rim by composite Simpson
  // (4000 intervals: error ~1e-13 relative for this smooth integrand): 1e-10.
  const CircularSplineParams c{30e-3, 7e-3};
  const double r1 = 22e-3, G = 80e9, T = 1.0;
  const int n = 4000;
  const double h = (c.outer_radius_m - r1) / n;
  auto dphi = [&](double r) { return T / (2 * std::numbers::pi * r * r * c.width_m) / G / r; };
  double sum = dphi(r1) + dphi(c.outer_radius_m);
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4 : 2) * dphi(r1 + i * h);
  const double integrated = sum * h / 3;
  EXPECT_NEAR(circular_spline_compliance_rad_per_Nm(c, r1, G) / integrated, 1.0, 1e-10);
}

TEST(CircularSpline, DefaultIsTheDesignRuleAndBadRingsAreRefused) {
  GearParams g;  // the seed's set: z_c = 192, m = 0.2 mm
  const CircularSplineParams c = default_circular_spline(g, 6e-3);
  EXPECT_NEAR(c.outer_radius_m, 0.7 * 192 * 0.2e-3, 1e-15);
  EXPECT_DOUBLE_EQ(c.width_m, 6e-3);
  const double root = gear_radii(g).root_c;
  EXPECT_GT(circular_spline_compliance_rad_per_Nm(c, root, 80e9), 0.0);
  try {
    validate_circular_spline({root * 0.99, 6e-3}, root, "x.toml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("x.toml: circular_spline.outer_radius_mm = "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("must be > the circular spline's root radius"), std::string::npos);
  }
  EXPECT_THROW(circular_spline_compliance_rad_per_Nm({30e-3, 0.0}, root, 80e9), InputError);
}

}  // namespace
}  // namespace sw
