#pragma once
// A thin plane slab of an external gear's teeth on their body, for the explicit-tooth check of the tooth-pair
// stiffness: the 2-D section (2K+1 teeth of flexspline_outline centred on +x, the body down to the bore radius)
// extruded by a short depth in z. Plane strain is imposed by the caller (u_z = 0). Metres.
#include <vector>

#include "gear/gear.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

struct ToothSlabOptions {
  int teeth_each_side = 2;          ///< K: neighbours on each side of the loaded tooth
  double bore_radius_m = 0;         ///< r_int, the inner edge of the body (< root radius)
  int points_per_flank = 48;        ///< outline samples on each flank of the loaded tooth (neighbours get a quarter)
  double depth_over_spacing = 3.0;  ///< slab depth in z as a multiple of the loaded flank's point spacing
  double max_edge_over_spacing = 6.0;  ///< tet size bound everywhere (regular tet of this edge), 0 = none
  /// Planes z = cut·depth (fractions in (0, 1), ascending) the tets do not cross: a load over a band of the depth
  /// then falls on whole faces (the loaded contact's face sections, contact/tooth_fem.hpp face_coupling).
  std::vector<double> depth_cuts;
};

/// Markers of the slab's boundary faces (TetMesh::faces): the loaded tooth's outline (flanks, tip, fillets and the root
/// halves next to it) kSurfaceRimOuter, the bore arc kSurfaceClamped, the sector's radial sides kSurfaceRimStep,
/// everything else (neighbour teeth, the z faces) kSurfaceOther.
struct ToothSlab {
  TetMesh mesh;
  double depth_m = 0;  ///< slab thickness in z (faces at z = 0 and z = depth_m)
};

/// Meshes the slab of the flexspline teeth of `g` (TET10 through TetGen). Throws InputError when the bore is not
/// inside the root circle or K < 0.
ToothSlab mesh_tooth_slab(const GearParams& g, const ToothSlabOptions& options);

/// The same slab without teeth, the body out to `outer_radius_m` (the 3-D model's rim_outer_radius: the ring of
/// flexspline.teeth = "ring", or the bare rim of "none"): the same sector, bore, depth and tet size; the outer arc
/// kSurfaceRimOuter. What the 3-D model holds of a tooth's load, to be taken off the explicit slab's. Throws
/// InputError when the bore is not inside the outer radius.
ToothSlab mesh_ring_slab(const GearParams& g, const ToothSlabOptions& options, double outer_radius_m);

}  // namespace sw
