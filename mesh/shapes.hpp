#pragma once
// Verification shapes (annular tube, thick cylinder, short ring, rectangular bar), TET10, metres.
#include "mesh/flexspline_params.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Annular tube about z, r_inner < r < r_outer, 0 <= z <= length (also the thick cylinder and the short ring).
/// Markers: kSurfaceClamped at z = 0, kSurfaceOpenEnd at z = length, kSurfaceInner, kSurfaceOuter. Region 0.
/// The wall is wall_layers layers thick (wall_size, mesh/flexspline_params.hpp); curved-surface nodes lie on the true
/// cylinders.
TetMesh mesh_tube(double r_inner_m, double r_outer_m, double length_m, const MeshParams& mesh);

/// Bar 0 <= x <= length, |y| <= width/2, |z| <= height/2 (cross-section centred on the x axis). Markers:
/// kSurfaceClamped at x = 0, kSurfaceBarEnd at x = length, kSurfaceOther elsewhere. Region 0. Surface edge
/// size wall_size(min(width, height)).across; TetGen fills the inside under that size.
TetMesh mesh_bar(double length_x_m, double width_y_m, double height_z_m, const MeshParams& mesh);

}  // namespace sw
