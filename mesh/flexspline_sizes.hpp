#pragma once
// The sizes of the flexspline's TET10 mesh, which the mesher (mesh/flexspline.hpp), the model-size estimate
// (mesh/estimate.hpp) and the harmonic solver's section all follow: the rim's outer radius for the teeth model, the
// boss's edge, the grading toward the cup's clamp corners and the explicit teeth's edges. Metres.
#include <optional>

#include "gear/gear.hpp"
#include "mesh/flexspline_params.hpp"
#include "mesh/revolve.hpp"

namespace sw {

/// Outer radius (m) of the rim for the teeth model: inner_radius + rim_thickness for "none" and "layer" (whose teeth
/// are a layer outside it, fem/fourier_section.hpp ToothLayer), plus half the tooth height (tip - root radius of
/// `gear`) for "ring", the tip radius for "explicit". Throws InputError when "ring" or "explicit" has no gear.
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

}  // namespace sw
