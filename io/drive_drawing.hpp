#pragma once
// drive.svg: a drawing of the drive's three parts from a case, to scale: the circular spline (the rigid ring with
// internal teeth), the flexspline (the thin toothed rim, here its section at the teeth, deformed by the generator) and
// the wave generator inside it (its cam, and the ball bearing's rings and balls when the case has one), with the major
// and minor axes; beside it the mesh at the major axis (teeth engaged) and at the minor axis (teeth apart) enlarged.
// The teeth are the backlash model's outlines (the flexspline's placed on the deformed neutral curve, as every
// kinematic figure of the tool places them); the rings' other radii are the case's. A picture, not a result: no figure
// is read off it.
#include <optional>
#include <string>

#include "generator/generator_bearing.hpp"
#include "kinematics/backlash.hpp"

namespace sw {

/// The radii the drawing takes from the case besides the teeth (metres).
struct DriveOutline {
  double bore_radius_m = 0;                   ///< the flexspline's inner radius under the teeth, at rest
  double circular_spline_outer_radius_m = 0;
  std::optional<GeneratorBearing> bearing;    ///< drawn when present: outer ring, balls, inner ring on the cam
  std::string generator;                      ///< the generator model's name, for its label
};

/// The drawing as an SVG document; `title` heads it (the case's path). The circular spline is the path with id
/// "circular-spline" (its outside, then its toothed inside), the flexspline "flexspline" (its toothed outside, then
/// its bore), in whole micrometres with y down (SVG's; each sub-path's first point absolute, then relative steps),
/// before the views place them.
std::string drive_svg(const BacklashModel& model, const DriveOutline& outline, const std::string& title);

}  // namespace sw
