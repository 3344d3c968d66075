// The lubricant's viscosity at temperature by ASTM D341's Walther line: the two given points come back, a third
// published point of real oils is predicted, the line falls with temperature, and bad input is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "common/error.hpp"
#include "common/lubricant.hpp"

namespace sw {
namespace {

Lubricant iso_vg_68() {  // a VG 68 mineral oil, VI ≈ 100 (68 and 8.6 mm²/s are typical catalogue values of the grade)
  Lubricant l;
  l.kind = "oil";
  l.viscosity_40C_mm2_s = 68.0;
  l.viscosity_100C_mm2_s = 8.6;
  return l;
}

TEST(Lubricant, WaltherLineReturnsItsTwoGivenPoints) {
  // Two points define A and B; evaluating at them must give them back up to floating-point rounding of the double
  // logarithms (1e-10 relative: far below any viscosity measurement, far above 1e-16 round-off of pow/log10).
  constexpr double kRoundTrip = 1e-10;
  const Lubricant l = iso_vg_68();
  EXPECT_NEAR(kinematic_viscosity_mm2_s(l, 40.0) / 68.0, 1.0, kRoundTrip);
  EXPECT_NEAR(kinematic_viscosity_mm2_s(l, 100.0) / 8.6, 1.0, kRoundTrip);
  EXPECT_NEAR(walther_kinematic_viscosity_mm2_s(30.0, 175.0, 100.0, 11.0, 30.0) / 175.0, 1.0, kRoundTrip);
}

TEST(Lubricant, ViscosityFallsAsTheOilWarms) {
  const Lubricant l = iso_vg_68();
  double previous = kinematic_viscosity_mm2_s(l, -20.0);
  for (double T = -10.0; T <= 120.0; T += 10.0) {
    const double nu = kinematic_viscosity_mm2_s(l, T);
    EXPECT_LT(nu, previous) << "at " << T << " C";
    previous = nu;
  }
}

TEST(Lubricant, PredictsTheMiddleTemperatureOfPublishedMineralOils) {
  // Stachowiak & Batchelor, Engineering Tribology, ch. 2 "Physical properties of lubricants", Table 2.3 "Dynamic
  // viscosity and pressure-viscosity coefficients of some commonly used lubricants" (measured at atmospheric
  // pressure; adapted there from their ref. [12]): dynamic viscosities (mPa·s) at 30, 60, 100 °C of thirteen mineral
  // oils, in the table's order (water and the polyglycol of the table left out: D341 is for petroleum oils).
  // D341 is for kinematic viscosity, so each is divided by a density. Assumption (not from the table): ρ(T) = 880·(1 −
  // 6.4e-4·(T − 15)) kg/m³, a typical mineral oil (ρ15 ≈ 0.85–0.90 g/cm³, volumetric expansion ≈ 6–7e-4 /K). It
  // nearly cancels, the 30/100 °C fit and the 60 °C point being divided alike: with ρ15 = 850 or 900 the median is
  // 1.85 or 1.65 %, with no expansion at all 2.1 %.
  // The line through 30 and 100 °C predicts 60 °C; the brief's 2 % is held by the MEDIAN over the thirteen oils
  // (measured 1.56 %), not by every oil: the first light machine oil misses by 12 % and one heavy oil by 5.5 %, which
  // is what ASTM D341's own warning about non-straight oils and 1950s data allows; no oil is dropped.
  constexpr double kMedianTolerance = 0.02;
  struct Oil { double eta30, eta60, eta100; };
  const std::vector<Oil> oils = {{38, 12.1, 5.3},  {153, 34, 9.1},    {250, 50.5, 12.6}, {810, 135, 26.8},
                                 {18.6, 6.3, 2.4}, {45, 12, 3.9},     {107, 23.3, 6.4},  {122, 26.3, 7.3},
                                 {171, 31, 7.5},   {30.7, 8.6, 3.1},  {165, 30.0, 6.8},  {310, 44.2, 9.4},
                                 {2000, 180, 24}};
  auto density = [](double T_C) { return 880.0 * (1.0 - 6.4e-4 * (T_C - 15.0)); };  // kg/m³, the assumption above
  auto kinematic = [&](double eta_mPas, double T_C) { return eta_mPas * 1e3 / density(T_C); };  // mm²/s
  std::vector<double> errors;
  for (const Oil& o : oils) {
    const double predicted =
        walther_kinematic_viscosity_mm2_s(30.0, kinematic(o.eta30, 30.0), 100.0, kinematic(o.eta100, 100.0), 60.0);
    errors.push_back(std::abs(predicted / kinematic(o.eta60, 60.0) - 1.0));
  }
  std::sort(errors.begin(), errors.end());
  const double median = errors[errors.size() / 2];
  std::printf("Walther at 60 C over %zu oils: median error %.2f %%, largest %.1f %%\n", errors.size(), 100 * median,
              100 * errors.back());
  EXPECT_LT(median, kMedianTolerance);
}

TEST(Lubricant, RefusesAViscosityOrderThatCannotBeAnOil) {
  Lubricant l = iso_vg_68();
  l.viscosity_40C_mm2_s = 8.0;  // below ν100 = 8.6
  try {
    validate_lubricant(l, "wave_generator.lubricant");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("wave_generator.lubricant.viscosity_40C_mm2_s = 8"), std::string::npos) << m;
    EXPECT_NE(m.find("must be > viscosity_100C_mm2_s"), std::string::npos) << m;
  }
}

TEST(Lubricant, RefusesAnUnknownKindAndViscositiesOutsideD341) {
  Lubricant l = iso_vg_68();
  l.kind = "paste";
  EXPECT_THROW(validate_lubricant(l, ""), InputError);
  l = iso_vg_68();
  l.viscosity_100C_mm2_s = 1.5;  // below D341's 2.0 mm²/s
  try {
    kinematic_viscosity_mm2_s(l, 60.0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lubricant.viscosity_100C_mm2_s = 1.5"), std::string::npos) << e.what();
  }
  // A thin oil far above its 100 °C point leaves D341's range: refused, not extrapolated.
  Lubricant thin;
  thin.kind = "oil";
  thin.viscosity_40C_mm2_s = 10.0;
  thin.viscosity_100C_mm2_s = 2.6;
  EXPECT_THROW(kinematic_viscosity_mm2_s(thin, 200.0), InputError);
  EXPECT_THROW(walther_kinematic_viscosity_mm2_s(40.0, 68.0, 40.0, 8.6, 60.0), InputError);   // one temperature
  EXPECT_THROW(walther_kinematic_viscosity_mm2_s(40.0, 68.0, 100.0, 8.6, -300.0), InputError);  // below 0 K
}

}  // namespace
}  // namespace sw
