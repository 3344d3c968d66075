#pragma once
// The tooth pairs of a case as the backlash module sees them: the bridge from kinematics/ to the multibody model,
// shared by `strainwave dynamics`, reconcile's dynamics baseline and bench_dynamics.
#include <vector>

#include "fem/flexspline_model.hpp"
#include "dynamics/model.hpp"

namespace sw {

/// w0 of the model (m): wave_generator.radial_deformation_mm, else the standard m·(z_c − z_f)/2 at which the
/// flexspline's pitch circle meets the circular spline's. Needs [gear].
double radial_deformation_m(const FlexsplineModel& model);

/// Every engaged pair of the model (its gear on the generator's thin-ring curve) at wave-generator angle 0 and φ₀ = 0,
/// from the backlash module. The ccw flank closes with a positive (ccw) wind-up of the rim, which is the model's drive flank; its arm is d(clearance)/dφ₀ with the sign
/// turned; a flank whose clearance does not close with the matching rotation never touches (infinite clearance).
std::vector<ToothPair> pairs_from_kinematics(const FlexsplineModel& model);

}  // namespace sw
