#pragma once
// Mean coefficient of friction of lubricated steel gear flanks from the contact's conditions (load, speeds, curvature,
// viscosity, roughness, lubricant), by two published mesh-friction models.
//
// Primary — ISO/TS 6336-20:2022 (formerly ISO/TR 13989-1:2000), the mean coefficient of friction of the integral-
// temperature scuffing method, an empirical fit of FZG test-rig gear measurements:
//   μ_mC = 0.045 · (w_Bt·K_Bγ / (v_ΣC · ρ_redC))^0.2 · η_oil^(−0.05) · X_R · X_L,     X_R = 2.2 · (Ra / ρ_redC)^0.25,
// in the standard's units: w_Bt·K_Bγ the normal (transverse base-circle) load per unit face width in N/mm (spur:
// K_Bγ = 1), v_ΣC the sum of the two flanks' tangential (rolling) speeds in m/s, ρ_redC the relative radius of
// curvature in mm, η_oil the dynamic viscosity at the oil (flank) temperature in mPa·s, Ra = (Ra1 + Ra2)/2 in µm.
// Lubricant factor X_L (the standard's table): mineral oil 1.0, polyalphaolefin 0.8, non-water-soluble polyglycol 0.7,
// water-soluble polyglycol 0.6, traction fluid 1.5, phosphate ester 1.3. The standard gives no X_L for grease.
// Why it is the primary: it is the current ISO model for cylindrical gears, fitted on gears (not discs alone), and it
// carries roughness and lubricant type as factors; its mild power laws stay finite and positive over the whole
// operating range, where Benedict & Kelley's logarithm turns negative at high speed and light load.
// Range rules (ISO/TR 13989-1 clause 5; from the text as recalled, the standard itself was not at hand for this
// implementation): a load below 150 N/mm is raised to 150 N/mm, a sum speed above 50 m/s is lowered to 50 m/s.
//
// Secondary — Benedict & Kelley (1961, ASLE Trans. 4:59, "Instantaneous coefficients of gear tooth friction"; the
// formula ISO/TR 14179-2:2001 uses), in its original US units:
//   f = 0.0127 · C_R · log10( 3.17e8 · W / (μ_0 · V_s · V_t²) ),     C_R = 50 / (50 − S),
// W load per unit face width in lbf/in, μ_0 the dynamic viscosity in cP (= mPa·s), V_s the sliding speed and V_t the
// sum of the rolling speeds in in/s, S the flanks' mean roughness in µin (Ra here; 1961 US practice read the
// arithmetic-average "AA" figure). The conversions used: 1 lbf/in = 175.1268 N/m, 1 in/s = 0.0254 m/s,
// 1 µin = 0.0254 µm. It needs sliding (V_s > 0: at the pitch point the logarithm diverges) and S < 50 µin (1.27 µm).
//
// Both formulas grow without bound as the speeds go to zero (ISO as v^−0.2, Benedict & Kelley as −log v), where the
// film collapses and the contact is boundary-lubricated. Rule used here (ours, not either source's): the result is
// capped at the boundary-lubrication coefficient kBoundaryFriction = 0.1, and at zero rolling speed — a locked drive's
// starting friction — the result IS kBoundaryFriction. The value 0.1 is the boundary coefficient μ_bl that
// Fernandes' GEARpie (github.com/cfernandesFEUP/GEARpie, CLASSES/LUBRICANT_LIBRARY.py: mubl = 0.1 for mineral, PAO,
// ester and glycol oils) uses in Matsumoto's mixed-film friction model μ = ξ μ_bl + (1 − ξ) μ_EHL; boundary-lubricated
// steel on steel lies at 0.05–0.15 (Bowden & Tabor), so 0.1 is a middle value, not a measurement of any grease.
//
// Idealisations: one mean coefficient for the whole path of contact (both models were fitted to mean values at the
// pitch point conditions); the viscosity is the caller's at the flank temperature (no thermal model here); a strain
// wave gear's slow, conformal, grease-lubricated flanks lie below both fits' speed ranges, so in practice the cap rules.
#include <string>

namespace sw {

/// Boundary-lubrication coefficient of steel flanks: the cap of both formulas and the starting friction at zero
/// rolling speed (GEARpie's μ_bl, see the header comment).
inline constexpr double kBoundaryFriction = 0.1;

/// The lubricant factor X_L of ISO/TS 6336-20 (ISO/TR 13989-1) by base oil.
enum class LubricantBase { MineralOil, Polyalphaolefin, PolyglycolNonWaterSoluble, PolyglycolWaterSoluble, TractionFluid,
                           PhosphateEster };

/// X_L of ISO/TS 6336-20's table: 1.0, 0.8, 0.7, 0.6, 1.5, 1.3 in the enum's order.
double lubricant_factor(LubricantBase base);

/// The conditions of one lubricated flank contact (a mean over the path of contact, usually taken at the pitch point).
struct FlankConditions {
  double normal_load_N_per_m = 0;      ///< normal load per unit face width (spur: F_bt/b = F_t/(b cos α_wt)), > 0
  double rolling_speed_sum_m_per_s = 0;  ///< v_Σ = v_1 + v_2, the flanks' tangential speeds relative to the contact, ≥ 0
  double sliding_speed_m_per_s = 0;    ///< v_g = |v_1 − v_2| (Benedict & Kelley only), ≥ 0
  double relative_radius_m = 0;        ///< ρ_red: 1/ρ_red = 1/ρ_1 ± 1/ρ_2 (minus for an internal pair), > 0
  double dynamic_viscosity_mPa_s = 0;  ///< η at the flank temperature, > 0
  double roughness_Ra_um = 0;          ///< arithmetic mean roughness Ra, mean of both flanks, > 0
  double lubricant_factor = 1.0;       ///< X_L (lubricant_factor()); mineral oil 1.0
};

/// A friction coefficient and which of the range rules made it.
struct MeshFriction {
  double coefficient = 0;
  bool load_raised = false;     ///< the load was below the fit's minimum and was raised to it (ISO: 150 N/mm)
  bool speed_lowered = false;   ///< the sum speed was above the fit's maximum and was lowered to it (ISO: 50 m/s)
  bool boundary_cap = false;    ///< the formula exceeded kBoundaryFriction (slow or starting contact): capped
};

/// ISO/TS 6336-20 (ISO/TR 13989-1) mean coefficient of friction μ_mC (header comment), with its load and speed rules,
/// capped at kBoundaryFriction; zero rolling speed gives kBoundaryFriction. Throws InputError naming the field when
/// load, radius, viscosity, roughness or X_L is not positive, or a speed is negative.
MeshFriction iso_mean_friction(const FlankConditions& c);

/// Benedict & Kelley (1961) coefficient of friction (header comment), capped at kBoundaryFriction; zero rolling or
/// sliding speed gives kBoundaryFriction (the logarithm diverges there). X_L is not used (the formula has no lubricant
/// factor). Throws InputError as iso_mean_friction, when Ra ≥ 1.27 µm (50 µin: C_R diverges), and when the log
/// argument is ≤ 1 (light load at high speed: the formula turns negative there).
MeshFriction benedict_kelley_friction(const FlankConditions& c);

}  // namespace sw
