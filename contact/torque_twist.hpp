#pragma once
// The torque–twist curve of a drive in the catalog's terms: three straight segments (K1 up to T1, K2 up to T2, K3
// beyond), lost motion as catalogs measure it (twist between ±4 % of rated torque on the loop's middle line, so it
// holds the elastic twist and any play), read off a computed curve.
#include <vector>

namespace sw {

/// A torque–twist curve sampled in increasing torque, negative and positive; at T = 0 a drive with play has two
/// points (the twist where the first flank closes one way and the other way). The middle line of a loop without
/// friction is the curve itself.
struct TorqueTwist {
  std::vector<double> torque_Nm, twist_rad;
};

/// Twist at torque T by linear interpolation (T = 0: the mean of the two limits). Throws std::out_of_range outside
/// the sampled torque range.
double twist_at(const TorqueTwist& c, double torque_Nm);

/// Twist between −fraction·T_R and +fraction·T_R (catalogs: 4 %), rad.
double lost_motion_rad(const TorqueTwist& c, double rated_torque_Nm, double fraction = 0.04);

/// The catalog's three-segment law of a curve: K1 = T1/φ(T1), K2 = (T2 − T1)/(φ(T2) − φ(T1)),
/// K3 = (T_R − T2)/(φ(T_R) − φ(T2)) on the odd part of the curve φ(T) = (twist(T) − twist(−T))/2 (secants).
struct SegmentLaw {
  double t1_Nm = 0, t2_Nm = 0, k1_Nm_per_rad = 0, k2_Nm_per_rad = 0, k3_Nm_per_rad = 0;
  bool breakpoints_fitted = false;  ///< T1, T2 chosen to fit the curve (no catalog size named)
  /// φ of the law at T, odd in T (the mirror image for negative torque, as catalogs draw it).
  double twist_rad(double torque_Nm) const;
};
SegmentLaw segment_law(const TorqueTwist& c, double t1_Nm, double t2_Nm, double rated_torque_Nm);

/// The segment law whose breakpoints 0 < T1 < T2 < T_R (on a grid of T_R/200) best fit the curve's odd part in the
/// least-squares sense over [0, T_R].
SegmentLaw fitted_segment_law(const TorqueTwist& c, double rated_torque_Nm);

}  // namespace sw
