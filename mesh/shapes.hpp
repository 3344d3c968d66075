#pragma once
// Verification shapes (annular tube, thick cylinder, short ring, rectangular bar), TET10, metres.
#include "mesh/flexspline_params.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Largest ratio of along-wall to through-wall edge length in a layered wall. TetGen does not insert layers by
/// itself (a wall meshed at edge t / layers everywhere came out one tet thick), so walls are split into layers by
/// internal surfaces and the along-wall edge may be longer; 2:1 keeps the quadratic tets well shaped.
inline constexpr double kMaxLayerAspect = 2.0;

/// Edge lengths for a wall of thickness t (m): `layers` = max(wall_layers, ceil(t / size)) layers each one tet
/// thick, `across` = t / layers, `along` = min(size, kMaxLayerAspect * across). Throws InputError for mesh.size_mm <= 0 or
/// mesh.wall_layers < 1.
struct WallSize {
  double across_m = 0.0;
  double along_m = 0.0;
  int layers = 1;
};
WallSize wall_size(double thickness_m, const MeshParams& mesh);

/// Annular tube about z, r_inner < r < r_outer, 0 <= z <= length (also the thick cylinder and the short ring).
/// Markers: kSurfaceClamped at z = 0, kSurfaceOpenEnd at z = length, kSurfaceInner, kSurfaceOuter. Region 0.
/// The wall is wall_layers layers thick (wall_size); curved-surface nodes lie on the true cylinders.
TetMesh mesh_tube(double r_inner_m, double r_outer_m, double length_m, const MeshParams& mesh);

/// Bar 0 <= x <= length, |y| <= width/2, |z| <= height/2 (cross-section centred on the x axis). Markers:
/// kSurfaceClamped at x = 0, kSurfaceBarEnd at x = length, kSurfaceOther elsewhere. Region 0. Surface edge
/// size wall_size(min(width, height)).across; TetGen fills the inside under that size.
TetMesh mesh_bar(double length_x_m, double width_y_m, double height_z_m, const MeshParams& mesh);

}  // namespace sw
