#pragma once
// The drive's torque–twist curve read back from the contact stage's contact.json (SPEC.md "Contact result"): the
// reader beside the writer, for `strainwave reconcile --baseline contact`.
#include <string>
#include <vector>

namespace sw {

/// The middle line of the contact stage's torque–twist loop (with no friction both branches coincide and it is the
/// curve itself). Torque is non-decreasing; two points at one torque are a vertical step of the twist (a dead band
/// crossed at that torque).
struct TorqueTwistCurve {
  std::vector<double> torque_Nm, twist_rad;  ///< same length, at least 2, torque_Nm.front() < torque_Nm.back()
  double rated_torque_Nm = 0.0;
  double catalog_t1_Nm = 0.0, catalog_t2_Nm = 0.0;  ///< `catalog.T1_Nm`, `catalog.T2_Nm` when given, else 0
  std::string path;                          ///< the file it was read from (for messages)
};

/// Reads `torque_twist` (a list of {torque_Nm, twist_rad, ...}), `rated_torque_Nm` and, when present, the breakpoints
/// of `catalog` of a contact.json. The list is
/// the loading branch (torque rising) followed, optionally, by the unloading branch (torque falling back); the result
/// is their middle line, exact for piecewise-linear branches, over the torque range both branches cover.
/// Throws InputError, one line naming the file, the key and the value: file missing or not JSON, key missing or not
/// a number, rated torque <= 0, torque that falls on the loading branch or rises on the unloading branch, fewer than
/// two points.
TorqueTwistCurve read_torque_twist(const std::string& contact_json_path);

/// Twist (rad) on the curve at `torque_Nm`, piecewise linear between its points (at a vertical step: its middle).
/// Within `end_tolerance_Nm` beyond either end the end segment is extended; further out it throws InputError naming
/// the torque and the curve's range (never silent extrapolation).
double twist_at(const TorqueTwistCurve& curve, double torque_Nm, double end_tolerance_Nm = 0.0);

}  // namespace sw
