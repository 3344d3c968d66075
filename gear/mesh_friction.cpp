#include "gear/mesh_friction.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.hpp"

namespace sw {

namespace {

[[noreturn]] void bad(const std::string& field, double value, const std::string& expectation) {
  std::ostringstream s;
  s << "flank contact: " << field << " = " << value << "; " << expectation;
  throw InputError(s.str());
}

void validate(const FlankConditions& c, bool uses_lubricant_factor) {
  if (!(c.normal_load_N_per_m > 0)) bad("normal_load_N_per_m", c.normal_load_N_per_m, "must be > 0");
  if (!(c.rolling_speed_sum_m_per_s >= 0))
    bad("rolling_speed_sum_m_per_s", c.rolling_speed_sum_m_per_s, "must be >= 0");
  if (!(c.sliding_speed_m_per_s >= 0)) bad("sliding_speed_m_per_s", c.sliding_speed_m_per_s, "must be >= 0");
  if (!(c.relative_radius_m > 0)) bad("relative_radius_m", c.relative_radius_m, "must be > 0");
  if (!(c.dynamic_viscosity_mPa_s > 0)) bad("dynamic_viscosity_mPa_s", c.dynamic_viscosity_mPa_s, "must be > 0");
  if (!(c.roughness_Ra_um > 0)) bad("roughness_Ra_um", c.roughness_Ra_um, "must be > 0");
  if (uses_lubricant_factor && !(c.lubricant_factor > 0))
    bad("lubricant_factor", c.lubricant_factor, "must be > 0 (mineral oil 1.0)");
}

MeshFriction capped(MeshFriction r) {
  if (r.coefficient > kBoundaryFriction) {
    r.coefficient = kBoundaryFriction;
    r.boundary_cap = true;
  }
  return r;
}

}  // namespace

double lubricant_factor(LubricantBase base) {
  // ISO/TS 6336-20:2022 (ISO/TR 13989-1:2000), table of the lubricant factor X_L.
  switch (base) {
    case LubricantBase::MineralOil: return 1.0;
    case LubricantBase::Polyalphaolefin: return 0.8;
    case LubricantBase::PolyglycolNonWaterSoluble: return 0.7;
    case LubricantBase::PolyglycolWaterSoluble: return 0.6;
    case LubricantBase::TractionFluid: return 1.5;
    case LubricantBase::PhosphateEster: return 1.3;
  }
  return 1.0;
}

MeshFriction iso_mean_friction(const FlankConditions& c) {
  validate(c, true);
  MeshFriction r;
  if (c.rolling_speed_sum_m_per_s == 0) {  // no entrainment, no film: a locked drive starting (header comment)
    r.coefficient = kBoundaryFriction;
    r.boundary_cap = true;
    return r;
  }
  // ISO/TR 13989-1 clause 5 range rules: w_Bt·K_Bγ ≥ 150 N/mm, v_ΣC ≤ 50 m/s.
  constexpr double kMinLoad_N_per_mm = 150.0, kMaxSpeed_m_per_s = 50.0;
  double load_N_per_mm = c.normal_load_N_per_m * 1e-3;
  if (load_N_per_mm < kMinLoad_N_per_mm) {
    load_N_per_mm = kMinLoad_N_per_mm;
    r.load_raised = true;
  }
  double speed = c.rolling_speed_sum_m_per_s;
  if (speed > kMaxSpeed_m_per_s) {
    speed = kMaxSpeed_m_per_s;
    r.speed_lowered = true;
  }
  const double rho_mm = c.relative_radius_m * 1e3;
  // ISO/TS 6336-20 μ_mC and X_R = 2.2 (Ra/ρ_redC)^0.25 (Ra µm, ρ_redC mm).
  const double roughness_factor = 2.2 * std::pow(c.roughness_Ra_um / rho_mm, 0.25);
  r.coefficient = 0.045 * std::pow(load_N_per_mm / (speed * rho_mm), 0.2) *
                  std::pow(c.dynamic_viscosity_mPa_s, -0.05) * roughness_factor * c.lubricant_factor;
  return capped(r);
}

MeshFriction benedict_kelley_friction(const FlankConditions& c) {
  validate(c, false);
  // Conversions to Benedict & Kelley's US units (exact by definition of the inch; lbf = 4.4482216 N).
  constexpr double kMetresPerInch = 0.0254;
  constexpr double kNewtonPerMetre_per_LbfPerInch = 4.4482216152605 / kMetresPerInch;  // 175.1268
  constexpr double kMaxRoughness_uin = 50.0;  // C_R = 50/(50 − S) diverges at S = 50 µin
  const double roughness_uin = c.roughness_Ra_um / kMetresPerInch;  // 1 µin = 0.0254 µm
  if (!(roughness_uin < kMaxRoughness_uin))
    bad("roughness_Ra_um", c.roughness_Ra_um, "must be < 1.27 (50 µin) for Benedict & Kelley's roughness factor");
  MeshFriction r;
  if (c.rolling_speed_sum_m_per_s == 0 || c.sliding_speed_m_per_s == 0) {
    r.coefficient = kBoundaryFriction;
    r.boundary_cap = true;
    return r;
  }
  const double load_lbf_per_in = c.normal_load_N_per_m / kNewtonPerMetre_per_LbfPerInch;
  const double sliding_in_per_s = c.sliding_speed_m_per_s / kMetresPerInch;
  const double rolling_in_per_s = c.rolling_speed_sum_m_per_s / kMetresPerInch;
  const double viscosity_cP = c.dynamic_viscosity_mPa_s;  // 1 cP = 1 mPa·s
  // Benedict & Kelley (1961): f = 0.0127 C_R log10(3.17e8 W / (μ0 V_s V_t²)).
  const double argument = 3.17e8 * load_lbf_per_in / (viscosity_cP * sliding_in_per_s * rolling_in_per_s * rolling_in_per_s);
  if (!(argument > 1.0)) {
    std::ostringstream s;
    s << "flank contact: Benedict & Kelley's log argument 3.17e8·W/(μ0·Vs·Vt²) = " << argument
      << " <= 1 (load " << c.normal_load_N_per_m << " N/m too light for the speeds): outside the formula's range; use "
      << "iso_mean_friction";
    throw InputError(s.str());
  }
  const double roughness_factor = kMaxRoughness_uin / (kMaxRoughness_uin - roughness_uin);
  r.coefficient = 0.0127 * roughness_factor * std::log10(argument);
  return capped(r);
}

}  // namespace sw
