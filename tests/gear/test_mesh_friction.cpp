// Mean flank friction (gear/mesh_friction.hpp): ISO/TS 6336-20's μ_mC and Benedict & Kelley's formula against hand
// computations written out here (no worked example with stated inputs was found for either), their trends, the range
// rules and the refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "common/error.hpp"
#include "gear/mesh_friction.hpp"
#include "tests/input_error.hpp"

namespace {

using namespace sw;

/// The hand values below carry 5–6 significant digits.
constexpr double kHandTol = 1e-4;

/// A pitch-point contact of an industrial spur pair: 300 N/mm, v_Σ = 10 m/s, v_g = 2 m/s, ρ_red = 8 mm, 20 mPa·s,
/// Ra = 0.5 µm, mineral oil.
FlankConditions industrial() {
  FlankConditions c;
  c.normal_load_N_per_m = 300e3;
  c.rolling_speed_sum_m_per_s = 10.0;
  c.sliding_speed_m_per_s = 2.0;
  c.relative_radius_m = 8e-3;
  c.dynamic_viscosity_mPa_s = 20.0;
  c.roughness_Ra_um = 0.5;
  return c;
}

// μ_mC = 0.045 (300/(10·8))^0.2 · 20^−0.05 · 2.2 (0.5/8)^0.25 · 1.0
//      = 0.045 · 1.302559 · 0.860892 · 1.1 = 0.0555086.
TEST(IsoMeanFriction, MatchesTheHandComputedFormula) {
  const MeshFriction r = iso_mean_friction(industrial());
  EXPECT_NEAR(r.coefficient / 0.0555086, 1.0, kHandTol);
  EXPECT_FALSE(r.load_raised || r.speed_lowered || r.boundary_cap);
}

TEST(IsoMeanFriction, FallsWithSpeedAndViscosityRisesWithRoughnessAndLoad) {
  const double mu = iso_mean_friction(industrial()).coefficient;
  FlankConditions c = industrial();
  c.rolling_speed_sum_m_per_s = 20.0;
  EXPECT_LT(iso_mean_friction(c).coefficient, mu);
  c = industrial();
  c.dynamic_viscosity_mPa_s = 80.0;
  EXPECT_LT(iso_mean_friction(c).coefficient, mu);
  c = industrial();
  c.roughness_Ra_um = 1.0;
  EXPECT_NEAR(iso_mean_friction(c).coefficient / mu, std::pow(2.0, 0.25), 1e-12);  // X_R ∝ Ra^0.25
  c = industrial();
  c.normal_load_N_per_m = 600e3;
  EXPECT_NEAR(iso_mean_friction(c).coefficient / mu, std::pow(2.0, 0.2), 1e-12);  // ∝ w^0.2
}

TEST(IsoMeanFriction, ScalesWithTheLubricantFactor) {
  FlankConditions c = industrial();
  c.lubricant_factor = lubricant_factor(LubricantBase::Polyalphaolefin);
  EXPECT_NEAR(iso_mean_friction(c).coefficient / iso_mean_friction(industrial()).coefficient, 0.8, 1e-12);
  EXPECT_EQ(lubricant_factor(LubricantBase::MineralOil), 1.0);
}

// Range rules: the load is raised to 150 N/mm, the sum speed lowered to 50 m/s; a slow contact is capped at the
// boundary value and a locked one (v_Σ = 0) starts at it.
TEST(IsoMeanFriction, AppliesItsRangeRulesAndTheBoundaryCap) {
  FlankConditions light = industrial(), at_min = industrial();
  light.normal_load_N_per_m = 100e3;
  at_min.normal_load_N_per_m = 150e3;
  const MeshFriction r = iso_mean_friction(light);
  EXPECT_TRUE(r.load_raised);
  EXPECT_DOUBLE_EQ(r.coefficient, iso_mean_friction(at_min).coefficient);
  FlankConditions fast = industrial(), at_max = industrial();
  fast.rolling_speed_sum_m_per_s = 80.0;
  at_max.rolling_speed_sum_m_per_s = 50.0;
  EXPECT_TRUE(iso_mean_friction(fast).speed_lowered);
  EXPECT_DOUBLE_EQ(iso_mean_friction(fast).coefficient, iso_mean_friction(at_max).coefficient);
  FlankConditions slow = industrial();
  slow.rolling_speed_sum_m_per_s = 1e-4;  // the formula gives 0.0555·(1e5)^0.2 = 0.55
  EXPECT_TRUE(iso_mean_friction(slow).boundary_cap);
  EXPECT_EQ(iso_mean_friction(slow).coefficient, kBoundaryFriction);
  FlankConditions locked = industrial();
  locked.rolling_speed_sum_m_per_s = 0.0;
  EXPECT_EQ(iso_mean_friction(locked).coefficient, kBoundaryFriction);
}

// f = 0.0127 · 50/(50 − 10) · log10(3.17e8 · 1000 / (10 · 100 · 1000²)) = 0.0127 · 1.25 · log10(317)
//   = 0.0127 · 1.25 · 2.501059 = 0.0397043, for W = 1000 lbf/in, μ0 = 10 cP, V_s = 100 in/s, V_t = 1000 in/s,
// S = 10 µin, given here in SI.
TEST(BenedictKelleyFriction, MatchesTheHandComputedFormulaInItsOwnUnits) {
  FlankConditions c;
  c.normal_load_N_per_m = 1000.0 * 175.1268352;  // 1000 lbf/in
  c.sliding_speed_m_per_s = 100.0 * 0.0254;
  c.rolling_speed_sum_m_per_s = 1000.0 * 0.0254;
  c.dynamic_viscosity_mPa_s = 10.0;
  c.roughness_Ra_um = 10.0 * 0.0254;
  c.relative_radius_m = 5e-3;  // not used by the formula
  EXPECT_NEAR(benedict_kelley_friction(c).coefficient / 0.0397043, 1.0, kHandTol);
}

TEST(BenedictKelleyFriction, FallsWithSpeedAndViscosityRisesWithRoughnessAndLoad) {
  const double mu = benedict_kelley_friction(industrial()).coefficient;
  EXPECT_GT(mu, 0.0);
  FlankConditions c = industrial();
  c.rolling_speed_sum_m_per_s = 20.0;
  EXPECT_LT(benedict_kelley_friction(c).coefficient, mu);
  c = industrial();
  c.sliding_speed_m_per_s = 4.0;
  EXPECT_LT(benedict_kelley_friction(c).coefficient, mu);
  c = industrial();
  c.dynamic_viscosity_mPa_s = 80.0;
  EXPECT_LT(benedict_kelley_friction(c).coefficient, mu);
  c = industrial();
  c.roughness_Ra_um = 1.0;
  EXPECT_GT(benedict_kelley_friction(c).coefficient, mu);
  c = industrial();
  c.normal_load_N_per_m = 600e3;
  EXPECT_GT(benedict_kelley_friction(c).coefficient, mu);
  c = industrial();
  c.sliding_speed_m_per_s = 0.0;  // pitch point: the logarithm diverges, boundary value
  EXPECT_EQ(benedict_kelley_friction(c).coefficient, kBoundaryFriction);
}

using sw::testing::message_of;

TEST(MeshFriction, RefusesNonPhysicalInputNamingTheField) {
  FlankConditions c = industrial();
  c.dynamic_viscosity_mPa_s = -1.0;
  EXPECT_NE(message_of([&] { iso_mean_friction(c); }).find("dynamic_viscosity_mPa_s = -1"), std::string::npos);
  c = industrial();
  c.rolling_speed_sum_m_per_s = -2.0;
  EXPECT_NE(message_of([&] { iso_mean_friction(c); }).find("rolling_speed_sum_m_per_s = -2"), std::string::npos);
  c = industrial();
  c.lubricant_factor = 0.0;
  EXPECT_THROW(iso_mean_friction(c), InputError);
  c = industrial();
  c.roughness_Ra_um = 1.5;  // 59 µin: Benedict & Kelley's C_R = 50/(50 − S) is undefined
  EXPECT_NE(message_of([&] { benedict_kelley_friction(c); }).find("roughness_Ra_um = 1.5"), std::string::npos);
  c = industrial();
  c.normal_load_N_per_m = 1.0;  // 1 N/m at 10 m/s: log argument below 1
  EXPECT_NE(message_of([&] { benedict_kelley_friction(c); }).find("log argument"), std::string::npos);
}

}  // namespace
