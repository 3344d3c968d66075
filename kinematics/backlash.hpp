#pragma once
// Backlash of a strain wave gear: involute flexspline teeth placed on the deformed neutral curve, rigid internal
// circular-spline teeth, the closest distance on both flanks of every tooth pair. Derivation in kinematics/README.md.
//
// Frames. Everything is computed in the wave generator's frame W (origin on the common axis, +x on the major axis).
// A flexspline tooth whose undeformed centre line is at material angle φ (from the major axis) is placed rigidly by
//     p = ρ·e(φ₁′) + R(γ)·(q − (r_m, 0)),   ρ = r_m + w(φ),  φ₁′ = φ + v(φ)/r_m + φ₀,  γ = φ₁′ + μ(φ)
// where q is a point of tooth 0 in the undeformed flexspline frame (tooth centred on +x), e(θ) = (cos θ, sin θ) and
// R(γ) the rotation by γ. The circular spline is concentric with W; the tooth space that tooth k meets is centred at
// σ = φ·z_f/z_c + j·2π/z_c, j the integer that puts σ nearest to φ₁′ (for z_c − z_f even, j = 0 at φ = 0).
//
// Flanks. "ccw" = the flexspline flank facing increasing polar angle (j_t1), "cw" = the other one (j_t2). A positive
// φ₀ (torsional wind-up of the flexspline under load, counter-clockwise) closes the ccw clearance and opens the cw one.
// Clearances are signed: negative = interference (penetration depth), never clipped.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "gear/tooth_profile.hpp"
#include "kinematics/neutral_curve.hpp"

namespace sw {

/// Geometry of one gear set on one deformed neutral curve (cheap to copy; no ownership).
struct BacklashModel {
  GearParams gear;
  GearRadii radii;
  Involute flank_f;  ///< ccw flank of flexspline tooth 0, flexspline frame
  Involute flank_c;  ///< ccw side of circular-spline space 0, circular-spline frame
  NeutralCurve curve;
};

/// Builds the model. Throws InputError for a gear set that cannot be cut (see gear_radii) or r_m outside the teeth.
BacklashModel make_backlash_model(const GearParams& gear, NeutralCurve curve);

/// The closest approach of one flexspline flank to the circular-spline flank it faces.
struct FlankClearance {
  double clearance_m = 0;        ///< signed closest distance (< 0: interference depth), metres
  Eigen::Vector2d point_f{0, 0};  ///< closest point on the flexspline flank (frame W), metres
  Eigen::Vector2d point_c{0, 0};  ///< closest point on the circular-spline flank (or its tip corner), frame W
  Eigen::Vector2d normal{0, 0};  ///< unit direction in which point_f must move to close the clearance
  double lever_arm_m = 0;        ///< (point_f × normal)_z: d(clearance)/dφ₀ = −lever_arm_m (metres per radian)
  double roll_f = 0;             ///< involute roll parameter of point_f on the flexspline flank
};

/// Both flanks of one tooth pair at one instant.
struct PairClearance {
  int pair = 0;              ///< flexspline tooth index k (0 for pair_clearance())
  double phi_rad = 0;        ///< material angle of the tooth from the major axis, (−π, π]
  double position_deg = 0;   ///< paper's tooth-pair position: 90° − angle to the nearest end of the major axis (0 minor, 90 major)
  bool engaged = false;      ///< the flexspline tip reaches beyond the circular spline's tip circle
  double depth_m = 0;        ///< radial overlap: |tip centre| − r_ac (> 0 when engaged), metres
  double tip_to_root_m = 0;  ///< r_rc − |tip centre|: radial tip clearance in the space (< 0: tip hits the root)
  int space = 0;             ///< circular-spline space index j relative to the pair's nominal one
  FlankClearance ccw;        ///< j_t1
  FlankClearance cw;         ///< j_t2
  /// Backlash of the pair as the paper tabulates it: the smaller flank clearance, metres.
  double backlash_m() const { return ccw.clearance_m < cw.clearance_m ? ccw.clearance_m : cw.clearance_m; }
};

/// Rigid placement of flexspline tooth 0's geometry in frame W: p = R(angle_rad)·q + offset_m.
struct ToothPlacement {
  double angle_rad = 0;
  Eigen::Vector2d offset_m{0, 0};
};

/// Clearances of one flexspline tooth, placed rigidly, against the circular-spline space centred at space_angle_rad
/// (circular spline concentric with W). Fills ccw, cw, depth_m, engaged, tip_to_root_m; phi_rad, position_deg, pair
/// and space are left 0. The distance engine used by pair_clearance(), exposed for rigid-gear checks.
PairClearance tooth_clearance(const BacklashModel& model, const ToothPlacement& tooth, double space_angle_rad);

/// Placement of the tooth at material angle φ (rad) on the deformed neutral curve with wind-up φ₀ (rad), see above.
ToothPlacement place_tooth(const NeutralCurve& curve, double phi_rad, double phi0_rad);

/// Clearances of a tooth at material angle φ (rad, from the major axis) with flexspline wind-up φ₀ (rad).
/// Solves each flank to |error| < 1e-12 m on the exact involutes.
PairClearance pair_clearance(const BacklashModel& model, double phi_rad, double phi0_rad);

/// Material angle of flexspline tooth k when the wave generator has turned by wg_angle_rad against the fixed circular
/// spline (tooth 0 centred on the major axis at 0): φ_k = 2πk/z_f − wg·z_c/z_f, wrapped to (−π, π].
double tooth_material_angle(const GearParams& gear, int k, double wg_angle_rad);

/// Every tooth pair at a wave-generator angle (rad); only the engaged ones if engaged_only. Sorted by tooth index.
std::vector<PairClearance> pair_clearances(const BacklashModel& model, double wg_angle_rad, double phi0_rad,
                                           bool engaged_only = true);

/// Smallest flank clearance over the engaged pairs at a wave-generator angle (rad), metres (negative: interference).
/// +infinity if no pair is engaged.
double min_backlash_m(const BacklashModel& model, double wg_angle_rad, double phi0_rad);

/// Result of a full wave-generator revolution.
struct RevolutionSweep {
  std::vector<double> wg_angle_rad;  ///< steps
  std::vector<double> min_backlash_m;  ///< per step, over engaged pairs
  double min_m = 0, max_m = 0;         ///< over the revolution (max of the per-step minimum)
  double min_at_rad = 0;               ///< wave-generator angle of the minimum
  int engaged_pairs_min = 0, engaged_pairs_max = 0;
  int distinct_positions = 0;          ///< generator positions actually solved (the rest repeat, period 2π/z_c)
};

/// min_backlash_m over one revolution at `steps` equal steps (steps ≥ 1). Exact use of the period 2π/z_c.
RevolutionSweep sweep_revolution(const BacklashModel& model, double phi0_rad, int steps);

/// One place where the flanks or the tip and root overlap.
struct Interference {
  double phi_rad = 0;        ///< material angle of the tooth
  std::string where;         ///< "ccw flank", "cw flank", "tip/root"
  double depth_m = 0;        ///< penetration (> 0)
  Eigen::Vector2d point{0, 0};  ///< frame W, metres
};

/// Interferences of one pair (empty if none).
std::vector<Interference> interferences(const PairClearance& p);

}  // namespace sw
