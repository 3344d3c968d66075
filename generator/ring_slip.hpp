#pragma once
// The generator's outer ring slipping on the flexspline's bore: a loss of a running drive that the bearing's own
// friction and the flanks' sliding do not hold. SI units.
//
// Physics. Where the bore lies on the generator, the flexspline's rim and the bearing's outer ring bend together to
// the same curvature change Δκ(θ) (1/m; > 0 where the curvature grows, at the major axis). A fibre at distance y
// outside a ring's neutral axis stretches by y·Δκ (thin rings, neutral axes inextensible), so the bore (y = −h_f/2 of
// the rim) shortens while the ring's outside (y = +h_r/2 of the ring) lengthens: the two surfaces in contact differ in
// circumferential strain by d·Δκ, d = (h_f + h_r)/2 the distance of the two neutral axes. The wave runs through both
// bodies at Ω = ω_in·(1 + 1/ratio) relative to their material, so a material point of the bore moves against the ring
// at v = Ω·R·d·(Δκ(θ) − κ_c), R the bore's radius, κ_c the rings' common creep (a rigid turn of the ring against the
// flexspline). Friction μ·F on each station's normal force F then dissipates P = μ·Ω·R·d·Σ F_i·|Δκ_i − κ_c|. The ring
// is free to turn: its moment balance Σ μ·F_i·sign(v_i) = 0 (the balls' rolling resistance on it is a thousandth of
// μ·ΣF and left out) makes κ_c the stations' force-weighted median of Δκ — where the ring sticks. This is Goodman and
// Klumpp's slip damping of two beams bent together under pressure (Goodman & Klumpp, Analysis of slip damping with
// reference to turbine-blade vibration, J. Appl. Mech. 23, 1956) with the bending carried by a travelling wave, and
// the creep of Reynolds' rolling bodies whose surfaces strain differently (Johnson, Contact Mechanics, 1985, §8.1).
//
// The bore's curvature where it lies on the generator is the generator's surface's: ρ(θ) as a polar curve,
// κ = (ρ² + 2ρ'² − ρρ'')/(ρ² + ρ'²)^(3/2).
//
// Idealisations: gross slip wherever a station carries, the rings rigid along the bore. The friction's traction
// stretches the two rings' sections by about μ·ΣF/(2·E·A) each, on the designed size 17 about a tenth of the spread
// of d·Δκ over the loaded arc: a partial-slip analysis would lower the loss by up to that, so the figure is an upper
// bound on this count; the curvature the generator's surface's (the balls' Hertz approach, microns, ripples it
// between balls and is left out); the neutral axes at the rim's and the ring's mid-thickness (teeth and the ring's
// shoulders would move them apart a little: d is a lower bound); Coulomb friction μ constant, the boundary value for
// a contact that slides without rolling.
#include <vector>

#include "generator/cam_profile.hpp"
#include "generator/generator_bearing.hpp"

namespace sw {

/// The change of the bore's curvature (1/m) where it lies on `cam`'s surface, at each angle θ (from the major axis):
/// the curvature of ρ(θ) as a polar curve less 1/bore_radius_m.
std::vector<double> bore_curvature_change_per_m(const CamSurface& cam, double bore_radius_m,
                                                const std::vector<double>& angle_rad);

/// The distance of the flexspline rim's neutral axis from the outer ring's: half the rim under the generator plus half
/// the ring's wall from its groove to the bore (kOuterRingWallPerBallDiameter·D), metres.
double ring_slip_lever_m(double rim_thickness_m, const GeneratorBearing& b);

/// The slip of the ring on the bore at one state of the generator's stations.
struct RingSlip {
  double creep_curvature_per_m = 0;  ///< κ_c: the force-weighted median of Δκ (where the ring sticks)
  /// The friction's moment between the generator and the flexspline, against the wave's turn relative to their
  /// material: μ·R·d·Σ F_i·|Δκ_i − κ_c| (the loss P = moment·Ω, Ω = ω_in·(1 + 1/ratio)). Rate-independent: the same
  /// at any speed, breakaway included. No load: zero.
  double moment_Nm = 0;
};

/// The ring's slip with normal forces `force_N` (stations around the bore, ≥ 0) at curvature changes
/// `curvature_change_per_m` (one per station), bore radius R, lever d (ring_slip_lever_m) and friction μ in [0, 1].
/// Throws InputError for sizes that differ, a negative or non-finite force, R or d ≤ 0 or μ outside [0, 1].
RingSlip ring_slip(const std::vector<double>& force_N, const std::vector<double>& curvature_change_per_m,
                   double bore_radius_m, double lever_m, double friction);

/// The ring on the bore of one drive: the bore's curvature change at each of the generator's stations (their half
/// turn; the partners half a turn on are alike), the bore's radius, the lever d (ring_slip_lever_m) and the interface's
/// μ. No curvatures: a generator without a ring on the bore (the given forces, rollers).
struct RingOnBore {
  std::vector<double> curvature_change_per_m;
  double bore_radius_m = 0, lever_m = 0, friction = 0;
};

/// The ring's slip moment under the stations' forces `station_force_N` (their half turn, as RingOnBore's curvatures):
/// twice ring_slip's over the listed stations, the partners carrying the same forces at the same curvature. 0 for a
/// RingOnBore without curvatures; ring_slip's InputError otherwise.
double ring_on_bore_moment_Nm(const RingOnBore& ring, const std::vector<double>& station_force_N);

}  // namespace sw
