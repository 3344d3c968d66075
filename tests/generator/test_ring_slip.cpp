// The generator's outer ring slipping on the bore (generator/ring_slip.hpp): against closed forms.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "generator/ring_slip.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;

// A load spread evenly over ±α about both ends of the major axis on a bore whose curvature changes by K·cos2θ: the
// median of cos2θ over θ uniform in [−α, α] is cos α (θ = ±α/2), and
//   (1/2α)·∫ |cos2θ − cos α| dθ over [−α, α] = (2·sin α − sin 2α)/(2α),
// so M = μ·R·d·K·F·(2·sin α − sin 2α)/(2α), F the load of both ends. 4000 stations (the midpoint rule
// of a kinked integrand: error of order 1/N²·(kink) ≈ 1e-7); asserted to 1e-5.
TEST(RingSlip, EvenLoadOnACosineCurvatureGivesTheClosedForm) {
  const double alpha = kPi / 6, K = 1.6, R = 0.02, d = 0.7e-3, mu = 0.1, F = 600;
  const int per_end = 2000;
  std::vector<double> force, kappa;
  for (const double end : {0.0, kPi})
    for (int i = 0; i < per_end; ++i) {
      const double t = end - alpha + (i + 0.5) * 2 * alpha / per_end;
      force.push_back(F / (2 * per_end));
      kappa.push_back(K * std::cos(2 * t));
    }
  const RingSlip s = ring_slip(force, kappa, R, d, mu);
  const double expected = mu * R * d * K * F * (2 * std::sin(alpha) - std::sin(2 * alpha)) /
                          (2 * alpha);
  EXPECT_NEAR(s.moment_Nm / expected, 1.0, 1e-5);
  EXPECT_NEAR(s.creep_curvature_per_m, K * std::cos(alpha), 1e-3 * K);
}

// One station carrying more than half the load sticks (κ_c is its curvature) and the others slip against it: by hand.
TEST(RingSlip, AStationCarryingMostOfTheLoadSticksAndTheOthersSlip) {
  const RingSlip s = ring_slip({10, 30, 5}, {1.0, 2.0, 0.5}, 0.02, 1e-3, 0.1);
  EXPECT_DOUBLE_EQ(s.creep_curvature_per_m, 2.0);
  EXPECT_NEAR(s.moment_Nm, 0.1 * 0.02 * 1e-3 * (10 * 1.0 + 5 * 1.5), 1e-15);
  // Nothing slips without friction or without load, and a uniform curvature (a round bore) slips nowhere.
  EXPECT_EQ(ring_slip({10, 30, 5}, {1.0, 2.0, 0.5}, 0.02, 1e-3, 0.0).moment_Nm, 0.0);
  EXPECT_EQ(ring_slip({0, 0}, {1.0, 2.0}, 0.02, 1e-3, 0.1).moment_Nm, 0.0);
  EXPECT_EQ(ring_slip({10, 30}, {1.5, 1.5}, 0.02, 1e-3, 0.1).moment_Nm, 0.0);
}

// The bore's curvature on an elliptical generator of semi-axes r ± w0: a/b² at the major axis and b/a² at the minor
// (the ellipse's own curvature), to 1e-6 of the change.
TEST(RingSlip, BoreCurvatureOnAnEllipseIsTheEllipses) {
  const double r = 0.02, w0 = 0.3e-3, a = r + w0, b = r - w0;
  const CamSurface cam(Cam{.profile = CamProfile::Ellipse}, w0, r);
  const std::vector<double> k = bore_curvature_change_per_m(cam, r, {0.0, kPi / 2, kPi});
  EXPECT_NEAR(k[0], a / (b * b) - 1 / r, 1e-6 * std::abs(a / (b * b) - 1 / r));
  EXPECT_NEAR(k[1], b / (a * a) - 1 / r, 1e-6 * std::abs(b / (a * a) - 1 / r));
  EXPECT_NEAR(k[2], k[0], 1e-9);
  // The polar cam to first order in w0: 3·w0·cos2θ/r².
  const CamSurface polar(Cam{}, w0, r);
  EXPECT_NEAR(bore_curvature_change_per_m(polar, r, {0.0})[0] / (3 * w0 / (r * r)), 1.0, 0.05);
}

TEST(RingSlip, BadInputIsOneClearLine) {
  const auto message = [](auto&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message([] { ring_slip({1, 2}, {1}, 0.02, 1e-3, 0.1); }).rfind("ring slip: stations' curvatures 1;", 0),
            0u);
  EXPECT_EQ(message([] { ring_slip({1, -2}, {1, 1}, 0.02, 1e-3, 0.1); }),
            "ring slip: station force -2; must be finite and >= 0 N");
  EXPECT_EQ(message([] { ring_slip({1}, {1}, 0.02, 1e-3, 1.5); }),
            "ring slip: friction coefficient 1.5; must be in [0, 1]");
  EXPECT_EQ(message([] { ring_slip({1}, {1}, 0.0, 1e-3, 0.1); }), "ring slip: bore radius 0; must be > 0 m");
}

}  // namespace
}  // namespace sw
