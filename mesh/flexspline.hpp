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
// Teeth "explicit": the rim's outer surface is the tooth outline of gear/tooth_profile.hpp (flexspline_outline, tooth 0
// on +x) extruded from z = length - rim_width to length. The rim's inner part stays revolved: the inner wall and the
// body's layer cylinders continue to the open end (plus cylinders between r_o and the root circle when the rim base
// reaches half a layer beyond r_o); the outermost of them, r_p, is the inner face of a prism r_p .. outline whose
// facets are built directly: the outline at every axial level, planar flank quads (kSurfaceRimOuter, corners and
// midside nodes on the outline's polyline, not projected), the open end z = length (kSurfaceOpenEnd) and the shoulder
// z = length - rim_width from max(r_o, r_p) to the outline (kSurfaceRimStep), sharing the revolved part's rings.
// Region 1, like the ring. Edges across a tooth are half its mid-height thickness, 2.5 times that axially; outline
// points closer than 0.4 of that edge are merged, which replaces a root fillet much smaller than the tooth (0.013 mm
// deep at the seed case) by a chord (see simplify_outline in flexspline.cpp). Needs root circle > r_o.
#include <optional>

#include "gear/gear.hpp"
#include "mesh/flexspline_params.hpp"
#include "mesh/flexspline_sizes.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Meshes the flexspline (see the file comment for the geometry): markers kSurfaceClamped (tube end z = 0, all
/// boss faces), kSurfaceInner, kSurfaceOuter (body, and the diaphragm's edge r = r_o), kSurfaceRimOuter,
/// kSurfaceRimStep, kSurfaceOpenEnd, kSurfaceDiaphragm (diaphragm faces and fillet). Each wall (body, rim,
/// diaphragm) has at least mesh.wall_layers layers; curved-surface nodes lie on the true cylinders and torus.
TetMesh mesh_flexspline(const FlexsplineParams& f, const std::optional<GearParams>& gear, const MeshParams& mesh);

}  // namespace sw
