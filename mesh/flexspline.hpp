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

#include "mesh/flexspline_params.hpp"
#include "gear/gear.hpp"
#include "mesh/revolve.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Outer radius (m) of the rim for the teeth model: inner_radius + rim_thickness for "none", plus half the tooth
/// height (tip - root radius of `gear`) for "ring", the tip radius for "explicit". Throws InputError when "ring" or
/// "explicit" has no gear.
double rim_outer_radius(const FlexsplineParams& f, const std::optional<GearParams>& gear);


/// Boss edge length over mesh.size: every boss face is clamped, so its tets carry no strain worth resolving; only the
/// interface with the diaphragm (r = boss_radius) keeps the diaphragm's size. The harmonic section and the model-size
/// estimate mesh and count the boss with it too.
inline constexpr double kBossSizeFactor = 4.0;

/// Growth of the edge length with the distance from a clamp corner (the size field's slope): 0.5 keeps neighbouring
/// tets within TetGen's radius-edge bound without a cascade of Steiner points.
inline constexpr double kCornerGrowth = 0.5;
/// Angular over meridian spacing allowed near the corners. The corner fields vary with (r, z) much faster than around
/// the axis, so the angular spacing may be longer, at a price measured on the seed cup (torque alone, 0.6 mm / 2
/// layers, φ₀ against the extrapolated harmonic solution): corner edge 0.05 mm, aspect 4: −0.55 % (241k nodes), 8:
/// −0.76 % (212k); 0.025 mm, 8: −0.54 % (252k), 16: −1.0 % (219k, slivers). 4 is as cheap as 8 for the same error
/// and keeps better tets.
inline constexpr double kCornerAspect = 4.0;

/// Halvings of the diaphragm's layer toward the cup's clamp corners: mesh.corner_levels, the rule's value
/// (derived_corner_levels) for -1; 0 for a tube. Both solvers take it from here (the TET10 size field, the harmonic
/// section's grading). Measured on the seed cup at 0.6 mm / 2 layers (3 diaphragm layers), cam in place, against the
/// extrapolated harmonic solution: φ₀ −2.1 % uniform, −0.60 / −0.45 / −0.34 % at levels 3 / 4 / 5 for 228k / 298k /
/// 483k nodes (183k uniform; each level about doubles what the field adds); size-17 cup at 0.8 mm / 1 layer: −2.4 %
/// uniform, −0.78 / −0.56 / −0.41 / −0.29 % at levels 2 / 3 / 4 / 5 for 123k / 142k / 181k / 286k nodes (114k).
/// Throws InputError above kMaxCornerLevels.
int corner_levels(const FlexsplineParams& f, const MeshParams& mesh);

/// The TET10 size field of a cup: graded toward the two corners where the clamped boss meets the free diaphragm,
/// (boss_radius, 0) (clamped face → free face, 180°) and (boss_radius, diaphragm_thickness) (clamped side → free top,
/// a 270° re-entrant corner). Displacements are singular there (φ₀ converges as h^0.7 on uniform meshes); the edge
/// length is the diaphragm's layer thickness / 2^levels at the corners and grows by kCornerGrowth per unit distance.
/// Empty for a tube or corner_levels = 0.
ProfileSizeField corner_size_field(const FlexsplineParams& f, const MeshParams& mesh);

/// Edge lengths of the explicit teeth's mesh: across a tooth half its thickness at mid height (two quadratic tets
/// across), along the axis 2.5 times that (the teeth are prisms whose fields vary slowly along it); neither above
/// mesh.size_m. The model-size estimate counts the teeth with them.
struct ToothMeshSize {
  double across_m = 0, axial_m = 0;
};
ToothMeshSize tooth_mesh_size(const GearParams& g, const MeshParams& mesh);

/// Meshes the flexspline (see the file comment for the geometry): markers kSurfaceClamped (tube end z = 0, all
/// boss faces), kSurfaceInner, kSurfaceOuter (body, and the diaphragm's edge r = r_o), kSurfaceRimOuter,
/// kSurfaceRimStep, kSurfaceOpenEnd, kSurfaceDiaphragm (diaphragm faces and fillet). Each wall (body, rim,
/// diaphragm) has at least mesh.wall_layers layers; curved-surface nodes lie on the true cylinders and torus.
TetMesh mesh_flexspline(const FlexsplineParams& f, const std::optional<GearParams>& gear, const MeshParams& mesh);

}  // namespace sw
