#pragma once
// The limits of the datasheet that stand on the loaded contact: the teeth's root strength (ISO 6336-3 on the contact's
// flank forces, each over its band of the face). Each returns the figure with the one line that says how it was
// computed.
#include <string>

#include "contact/loaded_contact.hpp"
#include "datasheet/datasheet.hpp"
#include "gear/gear.hpp"
#include "generator/generator_bearing.hpp"

namespace sw {

/// The allowable root stress of teeth loaded once per mesh entry, always the same way (a pulsating cycle 0..σ):
/// Goodman's line with σ_a = σ_m = σ/2, σ = 2/(1/S_e + 1/S_u) (the material's fatigue limit and ultimate strength;
/// a polished specimen's, no notch or size factor beyond ISO 6336-3's Y_S).
double pulsating_allowable_stress_Pa(double fatigue_limit_Pa, double ultimate_strength_Pa);

/// The flexspline teeth's root limit: at +rated torque, every loaded flank contact of the loaded contact, its
/// tangential part F_t = F_n·cos α at its contact radius, the root stress by ISO 6336-3 method B (gear/tooth_root.hpp:
/// Y_F, Y_S at that load radius, Y_B of the rim under the teeth) over the band of the face it stands for (the whole face
/// for one section); the largest of them, and the torque at which it reaches the pulsating allowable, the flank force
/// taken proportional to the torque beyond rated. Contacts loaded below the root's critical section (the method's arm
/// h_Fe ≤ 0) are left out and counted. Infinite when none is left. Throws InputError without the material's fatigue
/// data, or for teeth the method does not cover.
/// Why ISO 6336-3 method B does not cover the flexspline's teeth, or "" when it does: its rim factor Y_B is defined for
/// a rim under the teeth thicker than kRimBackupRatioMin of their depth (clause 8), and a designed rim at a low ratio
/// (tall teeth of a large module on a rim set by the diameter) can be thinner. Then the datasheet says so in place of
/// the figure, and keeps every other.
std::string tooth_root_not_covered(const GearParams& gear, const FlexsplineParams& flexspline);

ToothRootFigure tooth_root_limit(const GearParams& gear, const FlexsplineParams& flexspline, const Material& material,
                                 const ContactAnalysis& contact);

/// The ball loads (N, one per ball at angles 2πb/Z from the major axis) of the generator's stations' forces at one
/// torque step: each station pair's force (at each of its two stations) spread by its hat, so the load per unit angle
/// is the stations' force over their spacing, linear between stations (the hats sum to one); each ball carries the
/// load of its own arc ±π/Z (the flexible outer ring passes what presses on it to the nearest ball; its bending between
/// balls is left out). Their sum is the stations' (both halves) exactly.
std::vector<double> ball_loads_N(const BodyStations& stations, const std::vector<double>& station_force_N, int balls);

/// The index of the contact's step whose torque is nearest `torque_Nm`; of two as near, the later (at zero torque the
/// curve's limit from the positive side).
std::size_t step_nearest(const ContactAnalysis& contact, double torque_Nm);

/// L10 of the generator bearing (generator/bearing_life.hpp: Lundberg–Palmgren raceway ratings, the load zone turning
/// with the cam) from the ball loads of the loaded contact at +rated torque, in hours at `input_speed_rpm` for a cup
/// drive with the circular spline fixed (the output turns against the input); the life exponent against torque from
/// the step nearest half rated. Throws InputError when the generator's stations are not in the contact (the force
/// idealisation holds the band instead) or the contact has no station forces.
BearingLifeFigure generator_bearing_life(const GeneratorBearing& bearing, const BodyStations& stations,
                                         const ContactAnalysis& contact, double ratio, double input_speed_rpm);

}  // namespace sw
