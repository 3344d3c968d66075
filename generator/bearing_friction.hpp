#pragma once
// The friction moment of the wave generator's ball bearing from its own ball loads, by Palmgren's two-term model
// (A. Palmgren, Ball and Roller Bearing Engineering, 3rd ed., SKF Industries 1959, ch. "Friction"; as given in
// Harris & Kotzalas, Rolling Bearing Analysis, 5th ed. 2006, vol. 1, ch. "Kinematic speeds, friction torque and
// power loss", the empirical friction torque of Palmgren):
//   M = M0 + M1
//   M0 = 1e−7·f0·(ν·n)^(2/3)·d_m³        for ν·n ≥ 2000,     M0 = 160e−7·f0·d_m³ for ν·n < 2000      (N·mm)
//   M1 = f1·P1·d_m,   f1 = z·(P0/C0)^y                                                            (N·mm)
// with ν the lubricant's (a grease's base oil's) kinematic viscosity at the operating temperature (mm²/s), n the
// speed of the rings relative to each other (rpm), d_m the pitch diameter (mm), C0 the basic static load rating of
// ISO 76 (bearing_life.hpp). Coefficients for radial deep-groove ball bearings (Palmgren 1959, reproduced by Harris &
// Kotzalas in the same chapter's tables): f0 = 0.7–2 with grease (lower for light, higher for heavy series), 1 with
// oil mist, 2 in an oil bath, 4 with oil jet or a vertical shaft in a bath; z = 0.0004–0.0006 (light to heavy
// series), y = 0.55. Defaults below: f0 = 2, z = 0.0005, y = 0.55.
//
// The load the method prescribes is the bearing's equivalent load (P1 = F_r under pure radial load, and P0 = F_r, the
// static equivalent load): it is written for a bearing whose balls carry one Stribeck load zone under a radial force.
// The wave generator's balls carry two opposite lobes whose radial forces cancel, so the net radial force says nothing
// about the friction. Here P1 = P0 = F_eq, the radial load of the classic bearing (same Z, zero clearance, Stribeck's
// Q(ψ) = Q_max·cos^1.5 ψ over |ψ| < 90°, Harris & Kotzalas vol. 1 ch. "Distributions of internal loading in statically
// loaded bearings") whose balls give the same Σ Q_j^(1+y) as the given ones:
//   F_eq = Z·J_r·[Σ_j Q_j^(1+y) / (Z·J_(1+y))]^(1/(1+y)),
//   J_r = (1/2π)∫cos^2.5 ψ dψ = 0.2288,  J_p = (1/2π)∫cos^(1.5p) ψ dψ  (|ψ| < 90°).
// For the classic bearing this returns F_r (to the discreteness of Z), and since M1 = z·d_m·C0^(−y)·F_eq^(1+y) it
// makes M1 a sum over the balls of Q_j^(1+y): Palmgren's M1 ∝ F^(1+y) read ball by ball, so two lobes give the sum of
// the lobes' moments. That reading (friction additive over balls) is this module's assumption, not Palmgren's.
//
// Idealisations: Palmgren's empirical fit to measured running moments of whole bearings, with the cage, the seals
// (none here) and the grease's soap not modelled separately (an estimate, not a prediction to a few %); steady
// temperature; no clearance or preload beyond the given ball loads. The starting (breakaway) moment offered below is
// M1 alone: an idealisation that leaves out the grease's yield stress, seal drag and stiction, which make a real
// breakaway moment larger.
#include <string>
#include <vector>

#include "generator/generator_bearing.hpp"

namespace sw {

/// Palmgren's coefficients for a radial deep-groove ball bearing (see the header for their published ranges).
struct PalmgrenCoefficients {
  double f0 = 2.0;     ///< lubrication factor of the viscous term: oil bath / upper end of the grease range
  double z = 0.0005;   ///< load-term factor, middle of 0.0004–0.0006
  double y = 0.55;     ///< load-term exponent of deep-groove ball bearings
};

/// Checks the coefficients (0 < f0 ≤ 10, 0 < z ≤ 0.01, 0 < y ≤ 1: beyond any of Palmgren's tabulated bearings). Throws
/// InputError "<where>.<key> = value; expectation" (where "palmgren" when empty).
void validate_palmgren_coefficients(const PalmgrenCoefficients& c, const std::string& where);

/// The friction moment and its parts, N·m.
struct BearingFrictionMoment {
  double viscous_Nm = 0;         ///< M0, the no-load (viscous) term
  double load_Nm = 0;            ///< M1, the load term
  double total_Nm = 0;           ///< M0 + M1
  double equivalent_load_N = 0;  ///< F_eq = P1 = P0 (see the header)
  double static_rating_N = 0;    ///< C0 of ISO 76
};

/// Palmgren's equivalent radial load F_eq (N) of the ball loads (one per ball, b.balls of them, each ≥ 0) with the
/// load-term exponent y (see the header); 0 when no ball is loaded. InputError on a count other than b.balls, a
/// negative load or y outside (0, 1].
double palmgren_equivalent_load_N(const GeneratorBearing& b, const std::vector<double>& ball_loads_N, double y);

/// Palmgren's running friction moment of the bearing from its ball loads at the speed of the rings relative to each
/// other (rpm ≥ 0; its sign is ignored) with lubricant kinematic viscosity ν (mm²/s > 0, at the operating
/// temperature: kinematic_viscosity_mm2_s in common/lubricant.hpp). At n = 0 the viscous term is 0 (the bearing
/// stands; see palmgren_breakaway_moment_Nm). Validates b and c.
BearingFrictionMoment palmgren_friction_moment(const GeneratorBearing& b, const std::vector<double>& ball_loads_N,
                                               double relative_speed_rpm, double viscosity_mm2_s,
                                               const PalmgrenCoefficients& c = {});

/// The starting (breakaway) moment the model gives, N·m: M1 alone, no viscous term. An idealisation (see the header):
/// a real breakaway moment is larger by the grease's yield stress, seal drag and stiction.
double palmgren_breakaway_moment_Nm(const GeneratorBearing& b, const std::vector<double>& ball_loads_N,
                                    const PalmgrenCoefficients& c = {});

}  // namespace sw
