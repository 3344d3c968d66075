#include "dynamics/kinematic_pairs.hpp"

#include <cmath>
#include <limits>

#include "kinematics/backlash.hpp"
#include "kinematics/neutral_curve.hpp"

namespace sw {

double radial_deformation_m(const FlexsplineModel& c) {
  if (c.wave_generator && c.wave_generator->radial_deformation_m) return *c.wave_generator->radial_deformation_m;
  return c.gear->module_m * (c.gear->teeth_circular - c.gear->teeth_flexspline) / 2.0;
}

std::vector<ToothPair> pairs_from_kinematics(const FlexsplineModel& c) {
  const double rm = rim_mean_radius(c.flexspline);
  const double w0 = radial_deformation_m(c);
  const NeutralCurve curve =
      c.wave_generator ? generator_neutral_curve(rm, w0, *c.wave_generator) : cam_neutral_curve(rm, w0);
  const BacklashModel model = make_backlash_model(*c.gear, curve);
  std::vector<ToothPair> pairs;
  constexpr double kNever = std::numeric_limits<double>::infinity();
  for (const PairClearance& pc : pair_clearances(model, 0.0, 0.0, true)) {
    ToothPair t;
    t.angle_rad = pc.phi_rad;
    t.normal_projection = 1.0;  // the kinematic lever arm is already the moment of the flank normal
    t.lever_arm_m = std::abs(pc.ccw.lever_arm_m);
    t.clearance_drive_m = pc.ccw.lever_arm_m > 0 ? pc.ccw.clearance_m : kNever;
    t.coast_arm_m = std::abs(pc.cw.lever_arm_m);
    t.clearance_coast_m = pc.cw.lever_arm_m < 0 ? pc.cw.clearance_m : kNever;
    if (t.lever_arm_m > 0 && t.coast_arm_m > 0) pairs.push_back(t);
  }
  return pairs;
}

}  // namespace sw
