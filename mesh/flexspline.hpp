#pragma once
// The flexspline as a TET10 mesh: a tube or a cup, modelled as an axisymmetric profile revolved about z (the
// clamped end / boss at z = 0, the open end at z = length). Regions: 0 body wall, 1 toothed rim, 2 diaphragm,
// 3 boss. Metres.
//
// Cup profile (r, z): boss r <= boss_radius, 0 <= z <= 2 diaphragm_thickness (the hub's height is not in the case
// file; every boss face is clamped, so it only fixes the diaphragm at r = boss_radius); diaphragm
// boss_radius <= r <= r_o, 0 <= z <= diaphragm_thickness; body inner_radius <= r <= r_o up to length - rim_width,
// with a fillet of fillet_radius in the inner corner between the diaphragm's top face and the body's inner wall;
// rim inner_radius <= r <= r_rim over the last rim_width (r_o = inner_radius + wall_thickness).
// Tube: body from z = 0 (clamped) and, when teeth != none, the rim zone at the open end.
//
// Teeth "ring": the rim's outer radius is r_root + (r_tip - r_root) / 2 with r_root = inner_radius + rim_thickness
// and the tooth height from gear/tooth_profile.hpp. Rule: the tooth layer is smeared into a uniform ring with the
// tooth layer's solidity (teeth about as thick as the spaces: half the layer is steel), so the ring carries the
// teeth's area, mass and axial stiffness. What it gets wrong: the real teeth are separated by spaces and carry
// almost no hoop stress, so the ring over-states the rim's hoop bending stiffness (the ovalisation the wave
// generator imposes) by about ((t_rim + h/2) / t_rim)^3 and its torsional stiffness less so; it also smooths the
// stress concentration at the tooth roots. Teeth "none": the rim is rim_thickness thick with no ring.
// Teeth "explicit" is not meshed yet (InputError).
#include <optional>

#include "common/params.hpp"
#include "gear/gear.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Outer radius (m) of the rim for the teeth model: inner_radius + rim_thickness for "none", plus half the tooth
/// height (tip - root radius of `gear`) for "ring". Throws InputError when "ring" has no gear.
double rim_outer_radius(const FlexsplineParams& f, const std::optional<GearParams>& gear);

/// Checks every dimension and combination of the flexspline keys (and the teeth against the gear: root circle
/// within 0.25 module of inner_radius + rim_thickness). Throws InputError naming the keys in mm, e.g.
/// "flexspline.fillet_radius_mm = 3; must be < inner_radius_mm - boss_radius_mm = 2.4".
void validate_flexspline(const FlexsplineParams& f, const std::optional<GearParams>& gear, const MeshParams& mesh);

/// Meshes the flexspline (see the file comment for the geometry): markers kSurfaceClamped (tube end z = 0, all
/// boss faces), kSurfaceInner, kSurfaceOuter (body, and the diaphragm's edge r = r_o), kSurfaceRimOuter,
/// kSurfaceRimStep, kSurfaceOpenEnd, kSurfaceDiaphragm (diaphragm faces and fillet). Each wall (body, rim,
/// diaphragm) has at least mesh.wall_layers layers; curved-surface nodes lie on the true cylinders and torus.
TetMesh mesh_flexspline(const FlexsplineParams& f, const std::optional<GearParams>& gear, const MeshParams& mesh);

}  // namespace sw
