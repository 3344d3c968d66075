#pragma once
// The torque–twist curve of a drive and its readings in the catalog's terms: three straight segments (K1 up to T1, K2
// up to T2, K3 beyond), lost motion as catalogs measure it (twist between ±4 % of rated torque on the loop's middle
// line, so it holds the elastic twist and any play), and the middle line of a loop measured both ways.
#include <cstddef>
#include <utility>
#include <vector>

namespace sw {

/// A torque–twist curve: points in non-decreasing torque, negative and positive. Two or more points at one torque are
/// a vertical step of the twist (a dead band crossed at that torque): at T = 0 a drive with play has two, the twist
/// where the first flank closes one way and the other way. The middle line of a loop without friction is the curve
/// itself.
struct TorqueTwist {
  std::vector<double> torque_Nm, twist_rad;  ///< same length, at least 2, torque_Nm.front() < torque_Nm.back()
};

/// Twist (rad) on the curve at `torque_Nm`: linear along the first segment with a torque step whose range holds it; at
/// a vertical step strictly inside the curve, the step's middle. Within `end_tolerance_Nm` beyond either end the end
/// segment is extended; further out it throws InputError naming the torque and the curve's range (never silent
/// extrapolation).
double twist_at(const TorqueTwist& c, double torque_Nm, double end_tolerance_Nm = 0.0);

/// Twist just below and just above `torque_Nm` (front ≤ T ≤ back): they differ only at a vertical step, where they
/// are its first and last point; elsewhere both are twist_at's value.
std::pair<double, double> twist_limits(const TorqueTwist& c, double torque_Nm);

/// True when the points (ascending torque) span a torque range: 2 or more, the last torque above the first.
bool spans_torque(const TorqueTwist& branch);

/// The middle line of a loop: `loading` and `unloading` (both with ascending torque; an unloading branch that does not
/// span a torque range counts as absent, and the loading branch alone is the curve) averaged over the torque range
/// both cover, on the union of their torques: exact for piecewise-linear branches. A vertical step of the mean keeps
/// both its limits, but at the range's ends only the side inside it. Precondition: `loading` spans a torque range that
/// overlaps the unloading branch's, when it counts (as the two branches of one loop do: both hold its top).
TorqueTwist middle_line(const TorqueTwist& loading, const TorqueTwist& unloading);

/// Twist between −fraction·T_R and +fraction·T_R (catalogs: 4 %), rad.
double lost_motion_rad(const TorqueTwist& c, double rated_torque_Nm, double fraction = 0.04);

/// A load cycle's two branches, each as a TorqueTwist (ascending torque): `unloading` traversed from the cycle's top
/// down to its bottom, `loading` from the bottom back up. Without friction they coincide.
struct TorqueLoop {
  TorqueTwist loading, unloading;
};

/// Indices into a torque path (torques in the order applied) of its last full load cycle: the last top (the largest
/// torque before the bottom) before the bottom (the path's last smallest torque), and the path's end.
struct LoadCycle {
  std::size_t top = 0, bottom = 0, end = 0;
};
/// Throws std::invalid_argument unless the path falls monotonically from that top to the bottom and rises from there
/// to its end (2 points or more each way).
LoadCycle last_load_cycle(const std::vector<double>& torque_Nm);

/// The branches of `cycle` on the path (torque_Nm, twist_rad); torques within `zero_torque_Nm` of zero stand at T = 0
/// (the limits at zero: a vertical step through a dead band, its limit from below first).
TorqueLoop loop_branches(const std::vector<double>& torque_Nm, const std::vector<double>& twist_rad,
                         const LoadCycle& cycle, double zero_torque_Nm);

/// The loop's width in twist at a torque: unloading − loading (rad; at a vertical step each branch's middle, as
/// twist_at). Throws InputError when a branch does not reach the torque.
double loop_width_rad(const TorqueLoop& loop, double torque_Nm);

/// The loop's width at zero torque with each branch read in the middle of any dead band it crosses there: the part of
/// the gap that the flanks' friction holds (a parallelogram loop with play 2d and friction h gives h).
double hysteresis_loss_rad(const TorqueLoop& loop);

/// The catalog's hysteresis loss as a rig reads it: the output's position on returning to zero torque from +T_R (the
/// unloading branch's limit from above) less that on returning from −T_R (the loading branch's limit from below). A
/// rig's output, held by its own bearings, stays where it arrives, at the edge of the dead band it came from, so the
/// reading holds the dead bands the branches cross at zero torque as well as the friction's gap (the parallelogram:
/// 2d + h). Without play it is hysteresis_loss_rad.
double rig_hysteresis_loss_rad(const TorqueLoop& loop);

/// The loop's widest place: its width (loop_width_rad) and the torque where it is. The width is linear between the
/// branches' points, so the largest over the union of their torques (where both branches reach) is exact. Friction on
/// flanks that all unload at zero torque (teeth with play) draws a lens, closed at zero torque and at the corners and
/// widest between; a preloaded mesh's loop (Masing's) is widest at zero torque, the hysteresis loss. Of equal widths
/// (to 1e-9 of the largest: an odd loop's ±T) the one at the largest torque.
struct LoopWidth {
  double width_rad = 0, torque_Nm = 0;
};
LoopWidth widest_loop_width(const TorqueLoop& loop);

/// The loop's area ∮T dψ (J): ∫T dψ along the loading branch less along the unloading branch, trapezoids (exact on
/// the branches' polylines). The energy a cycle dissipates: positive, 0 without friction.
double loop_area_J(const TorqueLoop& loop);

/// The catalog's three-segment law of a curve: K1 = T1/φ(T1), K2 = (T2 − T1)/(φ(T2) − φ(T1)),
/// K3 = (T_R − T2)/(φ(T_R) − φ(T2)) on the odd part of the curve φ(T) = (twist(T) − twist(−T))/2 (secants).
struct SegmentLaw {
  double t1_Nm = 0, t2_Nm = 0, k1_Nm_per_rad = 0, k2_Nm_per_rad = 0, k3_Nm_per_rad = 0;
  bool breakpoints_fitted = false;  ///< T1, T2 chosen to fit the curve (no catalog size named)
  /// φ of the law at T, odd in T (the mirror image for negative torque, as catalogs draw it); NaN beyond T2 when K3 is
  /// 0 (a catalog row that lists none).
  double twist_rad(double torque_Nm) const;
};
/// The law's secants at T1, T2 and T_R (±T_R: the curve's ends, read with their rounding, kEndRounding).
SegmentLaw segment_law(const TorqueTwist& c, double t1_Nm, double t2_Nm, double rated_torque_Nm);

/// The segment law whose breakpoints 0 < T1 < T2 < T_R (on a grid of T_R/200) best fit the curve's odd part in the
/// least-squares sense over [0, T_R].
SegmentLaw fitted_segment_law(const TorqueTwist& c, double rated_torque_Nm);

}  // namespace sw
