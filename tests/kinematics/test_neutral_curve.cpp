// Deformed neutral curve: cam closed forms, the thin-ring solution against Roark's diametral-load values, the fit of
// sampled (FEM) curves.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <vector>

#include "common/error.hpp"
#include "kinematics/neutral_curve.hpp"

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kRm = 18.75e-3, kW0 = 0.2e-3;

TEST(CamCurve, HasTheInextensibleClosedForms) {
  const sw::NeutralCurve c = sw::cam_neutral_curve(kRm, kW0);
  for (double phi = -3.0; phi < 3.2; phi += 0.37) {
    const auto p = c.at(phi);
    EXPECT_NEAR(p.w_m, kW0 * std::cos(2 * phi), 1e-18);
    EXPECT_NEAR(p.v_m, -0.5 * kW0 * std::sin(2 * phi), 1e-18);
    EXPECT_NEAR(p.mu_rad, 2 * kW0 / kRm * std::sin(2 * phi), 1e-15);
  }
}

TEST(RingCurve, TwoForceRatioMatchesRoarkDiametralLoad) {
  // Roark, thin ring under two diametral point loads (inextensible): change of the loaded diameter 0.1488·PR³/EI,
  // of the perpendicular one −0.1366·PR³/EI. Tolerance 2e-3 on the ratio: Roark prints four digits.
  sw::WaveGeneratorParams wg;
  wg.model = sw::TwoForce{};
  const sw::NeutralCurve c = sw::generator_neutral_curve(kRm, kW0, wg);
  EXPECT_NEAR(c.at(0).w_m, kW0, 1e-15);
  EXPECT_NEAR(c.at(kPi / 2).w_m / c.at(0).w_m, -0.1366 / 0.1488, 2e-3);
}

TEST(RingCurve, FourForceIsInextensibleAndSymmetric) {
  const sw::NeutralCurve c = sw::generator_neutral_curve(kRm, kW0, sw::WaveGeneratorParams{});
  double mean_w = 0;
  const int n = 3600;
  for (int i = 0; i < n; ++i) mean_w += c.at(2 * kPi * i / n).w_m / n;
  EXPECT_NEAR(mean_w, 0.0, 1e-15);  // no n = 0 mode: the neutral line keeps its length
  for (double phi : {0.1, 0.5, 1.0, 1.4}) {
    EXPECT_NEAR(c.at(phi).w_m, c.at(-phi).w_m, 1e-15);
    EXPECT_NEAR(c.at(phi).w_m, c.at(phi + kPi).w_m, 1e-15);
    EXPECT_NEAR(c.at(phi).v_m, -c.at(-phi).v_m, 1e-15);
    // v' = −w (inextensible), by central differences (h² error ~ 1e-13 m).
    const double h = 1e-4;
    EXPECT_NEAR((c.at(phi + h).v_m - c.at(phi - h).v_m) / (2 * h), -c.at(phi).w_m, 1e-11);
  }
}

TEST(FemCurve, FitsAWellSampledCurveExactly) {
  std::vector<double> phi, w, v, mu;
  for (int i = 0; i < 720; ++i) {
    const double p = -kPi + 2 * kPi * i / 720;
    phi.push_back(p);
    w.push_back(kW0 * std::cos(2 * p) + 1e-6 * std::cos(p));
    v.push_back(-0.5 * kW0 * std::sin(2 * p) + 2e-6);
    mu.push_back(2 * kW0 / kRm * std::sin(2 * p));
  }
  const auto c = sw::fit_neutral_curve(kRm, phi, w, v, mu, "samples");
  for (double x : {0.0, 0.3, 1.1, 2.9}) {
    EXPECT_NEAR(c.at(x).w_m, kW0 * std::cos(2 * x) + 1e-6 * std::cos(x), 1e-15);
    EXPECT_NEAR(c.at(x).v_m, -0.5 * kW0 * std::sin(2 * x) + 2e-6, 1e-15);
  }
}

TEST(FemCurve, RefusesAPartialCircleNamingTheSource) {
  std::vector<double> phi(400), zero(400, 0.0);
  for (size_t i = 0; i < phi.size(); ++i) phi[i] = 0.5 * kPi * i / phi.size();
  try {
    sw::fit_neutral_curve(kRm, phi, zero, zero, zero, "curve.csv");
    FAIL() << "no throw";
  } catch (const sw::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("curve.csv: phi spans"), std::string::npos) << e.what();
  }
}

}  // namespace
