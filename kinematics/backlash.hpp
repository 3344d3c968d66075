#pragma once
// Backlash of a strain wave gear: involute flexspline teeth placed on the deformed neutral curve, rigid internal
// circular-spline teeth, the closest distance on both flanks of every tooth pair. Derivation in kinematics/README.md.
//
// Frames. Everything is computed in the wave generator's frame W (origin on the common axis, +x on the major axis).
// A flexspline tooth whose undeformed centre line is at material angle φ (from the major axis) is placed rigidly on
// the deformed neutral curve (Cartesian placement, exact for the given displacement field):
//     P = R(φ₀)·[(r_m + w)·e(φ) + v·e'(φ)],   γ = φ + φ₀ + atan2(v − w', r_m + w + v'),   p = P + R(γ)·(q − (r_m, 0))
// where q is a point of tooth 0 in the undeformed flexspline frame (tooth centred on +x), e(θ) = (cos θ, sin θ),
// e' its derivative, ' = d/dφ, and γ the direction of the deformed curve's normal (plane sections stay normal).
// The circular spline is concentric with W; the tooth space that tooth k meets is centred at σ = φ·z_f/z_c + j·2π/z_c,
// j the integer that puts σ nearest to the tooth's polar angle (for z_c − z_f even, j = 0 at φ = 0).
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
  TipRounding round_f;  ///< the flexspline tooth's ccw tip corner (sharp when its radius is 0)
  TipRounding round_c;  ///< the tip corner of the circular-spline tooth beyond space 0's ccw side
  NeutralCurve curve;
};

/// Builds the model. Throws InputError for a gear set that cannot be cut (see gear_radii) or r_m outside the teeth.
BacklashModel make_backlash_model(const GearParams& gear, NeutralCurve curve);

/// The part of a tooth outline where the closest points lie.
enum class ToothPart { Flank, TipCorner, TipLand };

/// "flank", "tip corner", "tip land".
const char* part_name(ToothPart part);

/// The closest approach of one side of a flexspline tooth (flank, tip corner, tip land) to the circular-spline tooth
/// it faces (flank, tip corner, tip land): the true distance between the two outlines, signed.
struct FlankClearance {
  double clearance_m = 0;        ///< signed closest distance (< 0: overlap, the depth to separate them), metres
  Eigen::Vector2d point_f{0, 0};  ///< closest point on the flexspline outline (frame W), metres
  Eigen::Vector2d point_c{0, 0};  ///< closest point on the circular-spline outline, frame W
  Eigen::Vector2d normal{0, 0};  ///< unit direction in which point_f must move to close the clearance
  double lever_arm_m = 0;        ///< (point_f × normal)_z: d(clearance)/dφ₀ = −lever_arm_m (metres per radian)
  double roll_f = 0;             ///< involute roll parameter of point_f when it lies on the flank
  ToothPart part_f = ToothPart::Flank;  ///< where point_f lies on the flexspline tooth
  ToothPart part_c = ToothPart::Flank;  ///< where point_c lies on the circular-spline tooth
};

/// Both flanks of one tooth pair at one instant.
struct PairClearance {
  int pair = 0;              ///< flexspline tooth index k (0 for pair_clearance())
  double phi_rad = 0;        ///< material angle of the tooth from the major axis, (−π, π]
  double position_deg = 0;   ///< paper's tooth-pair position: 90° − angle to the nearest end of the major axis (0 minor, 90 major)
  bool engaged = false;      ///< in the mesh zone: the flexspline tip reaches beyond the circular spline's tip circle
  double depth_m = 0;        ///< radial overlap: |tip centre| − r_ac (> 0 when engaged), metres
  double tip_to_root_m = 0;  ///< r_rc − |tip centre|: radial tip clearance in the space (< 0: tip hits the root)
  int space = 0;             ///< circular-spline space index j relative to the pair's nominal one
  FlankClearance ccw;        ///< j_t1 (closed by a positive turn of the flexspline, φ₀ > 0)
  FlankClearance cw;         ///< j_t2
  /// Backlash of the pair as the paper tabulates it: the smaller flank clearance, metres. Meaningful in the mesh zone
  /// only (engaged); out of it the teeth face tip to tip and there is no backlash.
  double backlash_m() const { return ccw.clearance_m < cw.clearance_m ? ccw.clearance_m : cw.clearance_m; }
  /// Total play of the pair j_t1 + j_t2, metres: what a rigid turn of the rim cannot change, only move between flanks.
  double total_play_m() const { return ccw.clearance_m + cw.clearance_m; }
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

/// Which side of the teeth: ccw (j_t1, closed by turning the flexspline by +δ) or cw (j_t2, closed by −δ).
enum class Flank { Ccw, Cw };

/// The rigid turn of the flexspline rim about the axis (beyond φ₀) that brings one flank of the pair at material angle
/// φ into contact: the root δ ≥ 0 of j(φ₀ ± δ) = 0, solved on the exact geometry to 1e-13 rad (first-order start
/// j/lever). A pair already overlapping gives the first-order estimate j/lever < 0. +infinity if no rigid turn below
/// 0.1 rad closes it.
double closing_angle_rad(const BacklashModel& model, double phi_rad, double phi0_rad, Flank flank);

/// The flank where a rigid turn closes it, its tooth first drawn in along its centre line by `drawn_in_m` (the rim's
/// inward and the circular spline's outward give under load, which a turn does not make; 0: as placed): the turn (as
/// closing_angle_rad, +infinity when none below 0.1 rad closes it) and the clearance drawn in, before the turn: its
/// points, normal and lever are the contact's where the turn closes it, to first order in the turn (at the closed
/// position itself the nearest points of two near-conjugate flanks are ill-determined, and at zero distance the
/// normal is not defined). As the teeth part radially the contact climbs toward the tips: its normal turns (along the
/// involutes, round a tip corner) and its lever and radial share change with it.
struct ClosedFlank {
  double turn_rad = 0;
  FlankClearance contact;
};
ClosedFlank closed_flank(const BacklashModel& model, double phi_rad, double phi0_rad, Flank flank,
                         double drawn_in_m = 0);

/// Counts of pairs near contact, per flank: within 1, 5 and 10 µm.
inline constexpr double kNearContact_m[3] = {1e-6, 5e-6, 10e-6};

/// The mesh at one wave-generator position.
struct MeshState {
  double wg_angle_rad = 0;
  int engaged_pairs = 0;
  double min_backlash_m = 0;          ///< min over engaged pairs of min(j_t1, j_t2); +inf if none
  double closing_ccw_rad = 0;         ///< smallest closing angle of the ccw flanks over the engaged pairs
  double closing_cw_rad = 0;          ///< same for the cw flanks
  int pair_ccw = -1, pair_cw = -1;    ///< the pairs that close first
  double angular_play_rad() const { return closing_ccw_rad + closing_cw_rad; }  ///< free turn of the output, rad
  int near_ccw[3] = {0, 0, 0};        ///< engaged pairs with j_t1 < 1, 5, 10 µm
  int near_cw[3] = {0, 0, 0};         ///< engaged pairs with j_t2 < 1, 5, 10 µm
};

/// The mesh state at a wave-generator angle (rad) with wind-up φ₀ (rad). The angular play is geometric: the free
/// rotation of the flexspline (the output, circular spline fixed, generator locked) from first contact one way to
/// first contact the other way, teeth and rim rigid. It is not the catalog's lost motion, which includes the elastic
/// twist at ±4 % of rated torque.
MeshState mesh_state(const BacklashModel& model, double wg_angle_rad, double phi0_rad);

/// Result of a full wave-generator revolution.
struct RevolutionSweep {
  std::vector<double> wg_angle_rad;  ///< steps
  std::vector<double> min_backlash_m;  ///< per step, over engaged pairs
  double min_m = 0, max_m = 0;         ///< over the revolution (max of the per-step minimum)
  double min_at_rad = 0;               ///< wave-generator angle of the minimum
  int engaged_pairs_min = 0, engaged_pairs_max = 0;
  int distinct_positions = 0;          ///< generator positions actually solved (the rest repeat, period 2π/z_c)
  double angular_play_min_rad = 0, angular_play_max_rad = 0;  ///< over the revolution
  std::vector<MeshState> period;       ///< the distinct positions in one period 2π/z_c, in generator-angle order
};

/// min_backlash_m over one revolution at `steps` equal steps (steps ≥ 1). Exact use of the period 2π/z_c.
RevolutionSweep sweep_revolution(const BacklashModel& model, double phi0_rad, int steps);

/// The tightest place of the mesh at rest (no wind-up): the smallest clearance over the engaged pairs at every material
/// angle (0.25° grid, refined by Brent around the worst), both flanks and the tip to the root, with the pair where it
/// is. Metres, < 0: the depth of an interference; +infinity if no pair is engaged.
struct TightestPair {
  double clearance_m = 0;
  PairClearance pair;
};
TightestPair tightest_pair_at_rest(const BacklashModel& model);

/// The geometry a designer checks before any sweep (basic model, no load).
struct GeometryCheck {
  GearRadii radii;
  double w_major_m = 0, w_minor_m = 0;  ///< radial displacement of the neutral curve at the major / minor axis
  /// Radial overlap of the tip circles at the major axis: r_af + w(0) − r_ac. Against 2·w0: the teeth leave the mesh
  /// at the minor axis only if the tips clear there.
  double working_depth_m = 0;
  double two_w0_m = 0;
  double minor_axis_tip_clearance_m = 0;  ///< r_ac − (r_af + w_minor): > 0 when the tips pass at the minor axis
  double major_axis_tip_root_m = 0;       ///< r_rc − (r_af + w(0)): flexspline tip to circular-spline root
  double major_axis_root_tip_m = 0;       ///< (r_rf + w(0)) − r_ac: circular-spline tip to flexspline root (radial)
  PairClearance major_axis;               ///< the pair on the major axis (φ = 0)
  double major_axis_play_rad = 0;         ///< its closing angles summed: the dead band the proportions leave there
  bool interference = false;              ///< any engaged pair (or tip/root) overlapping at rest
  double worst_clearance_m = 0;           ///< smallest clearance over engaged pairs and positions (< 0: depth)
  PairClearance worst;                    ///< the pair where it is
  /// When interfering: the largest common factor s ≤ 1 on both addenda (h_a,f*·s, h_a,c*·s) free of interference,
  /// and the w0 range (scale factors of the curve) free of interference; 0 when none was found.
  double addendum_scale_free = 0;
  double addendum_free_flexspline = 0, addendum_free_circular = 0;  ///< the coefficients that scale gives
  double w0_scale_free_lo = 0, w0_scale_free_hi = 0;
};

/// Scans every tooth-pair position (material angle φ over a full turn, 0.25° steps refined around the worst) of the
/// basic model. Cheap (well under a second without interference; a few seconds with, for the remedies).
GeometryCheck check_geometry(const GearParams& gear, const NeutralCurve& curve);

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
