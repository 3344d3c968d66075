#pragma once
// The ratcheting torque: the output torque at which the teeth ride over the circular spline's teeth with the wave
// generator locked (the catalog's ratcheting torque). Under load the flanks' forces push the flexspline's rim in
// (through the rim, the generator's balls and its plug) and the circular spline's ring out, by their radial
// components; a tooth whose tip is drawn back inside the circular spline's tip circle can no longer carry, and its
// load passes to the teeth that still overlap, which are pushed further apart. The teeth let go from the zones' edges
// (a few µm deep at rest) inward, until those left cannot carry the torque: the output turns through a tooth.
//
// The contacts climb as the teeth part: at every torque of the ramp each flank meets its partner where a rigid turn
// closes it with its tooth drawn in by the radial parting the load has made (kinematics/backlash.hpp closed_flank),
// so its normal turns along the involutes and round the tip corners, its force pushes harder radially and its lever
// shortens; the loads' parting is iterated to its fixed point (a parting that keeps growing is a tooth riding over).
//
// Idealisations, said wherever the figure is printed:
//  - a flank's load on the body keeps its point of application at rest (its direction turns with the contact's
//    normal, its gap and lever are the climbed contact's): the point moves up the flank by a fraction of the tooth's
//    height, which changes its moment about the tooth's foot, not its radial push;
//  - a tooth releases when its radial overlap (tip beyond the circular spline's tip circle) is gone, read at its tip on
//    the rim and on the ring, in each section of the face on its own (the sections' bands coupled through the rim and
//    the ring only); its own bending moves the tip along the pitch circle, not radially, and is left out;
//  - the tooth pair's own compliance stays the one at rest's contact radii;
//  - a tooth that has let go does not come back in during the ramp (loading is monotonic).
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sw {

/// A tooth that can carry in the ramp, in one section of the face (straight teeth on a coned rim: each section's
/// overlap its own): its flanks' unknowns there in the contact problem and its overlap at rest there.
struct RatchetTooth {
  int tooth = 0;
  double phi_rad = 0;            ///< material angle from the major axis
  double overlap_at_rest_m = 0;  ///< |tip| − r_a,c with the generator alone (> 0: engaged)
  int slice = 0;                 ///< the face's section (contact/contact_body.hpp face_slice); 0 with one
};

/// The drive loaded with only the teeth `can_carry` (per RatchetTooth) taking part: each tooth's radial overlap under
/// the load and whether its flanks carry force. Empty when those teeth cannot carry the torque.
struct RatchetState {
  Eigen::VectorXd overlap_m;
  /// What moved each tooth's tip from its overlap at rest: the rim in, the circular spline's ring out (m; their sum
  /// is overlap at rest − overlap). Empty when the solve does not split it.
  Eigen::VectorXd rim_in_m, ring_out_m;
  std::vector<bool> loaded;
  double twist_rad = 0;
  /// Per tooth, its most loaded flank's contact: how far its normal has turned from rest (rad, the climb) and where
  /// the teeth touch (e.g. "flank on flank", "tip corner on flank"). Empty when the solve does not climb.
  std::vector<double> normal_turn_rad;
  std::vector<std::string> contact;
};
using RatchetSolve = std::function<std::optional<RatchetState>(double torque_Nm, const std::vector<bool>& can_carry)>;

struct Ratcheting {
  double torque_Nm = std::numeric_limits<double>::infinity();  ///< infinity: not reached below the ceiling
  double ceiling_Nm = 0;                                       ///< where the search stopped looking
  double tolerance_rel = 0;                                    ///< of the torque, from the bisection
  /// The first tooth loaded at rated torque or above that lets go, and the torque it does so at.
  double first_release_Nm = std::numeric_limits<double>::infinity();
  int first_tooth = -1, first_slice = 0;
  double first_phi_rad = 0;
  /// Just below the ratcheting torque: the teeth still carrying, the one of them with least overlap left and that
  /// overlap, and the twist.
  int teeth_holding = 0;
  int last_tooth = -1, last_slice = 0;
  double last_phi_rad = 0, last_overlap_m = 0, twist_below_rad = 0;
  double last_rim_in_m = 0, last_ring_out_m = 0;  ///< that tooth's tip parted by the rim and by the ring
  double last_normal_turn_rad = 0;  ///< how far that tooth's contact normal has turned from rest as it climbed
  std::string last_contact;         ///< where its teeth touch then (empty: not climbed)
};

/// The teeth that can carry T: all those engaged at rest, then, round by round, those whose overlap under load is
/// gone released together (releasing a tooth loads the others more and parts them further, so a tooth out of overlap
/// stays out: the rounds reach the same set as releasing them one by one). Empty when none left can carry T.
std::optional<std::pair<std::vector<bool>, RatchetState>> teeth_holding(const std::vector<RatchetTooth>& teeth,
                                                                         const RatchetSolve& solve, double torque_Nm);

/// The least torque above `from_Nm` (which must hold) at which the teeth cannot hold: a geometric ramp (steps of
/// 10 %) up to `ceiling_Nm`, then bisection to `tolerance_rel`. Throws std::invalid_argument for from_Nm ≤ 0, a
/// ceiling below it or a tolerance ≤ 0, and InputError when nothing holds at from_Nm.
Ratcheting ratcheting_torque(const std::vector<RatchetTooth>& teeth, const RatchetSolve& solve, double from_Nm,
                             double ceiling_Nm, double tolerance_rel = 1e-3);

}  // namespace sw
