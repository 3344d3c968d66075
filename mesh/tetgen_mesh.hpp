#pragma once
// TetGen 1.5 wrapper: a piecewise-linear complex (PLC) in, a quadratic (TET10) TetMesh out. Metres throughout.
// The PLC's facet markers are copied to the boundary faces unchanged; callers map them to Surface markers.
#include <vector>

#include <Eigen/Core>

#include "mesh/tet_mesh.hpp"

namespace sw {

/// A planar facet: one or more closed polygons (indices into Plc::points, in order around each polygon), hole
/// points lying strictly inside holes of the facet, and a marker passed through to the boundary faces.
struct PlcFacet {
  std::vector<std::vector<int>> polygons;
  std::vector<Eigen::Vector3d> holes;
  int marker = 0;
};

/// A region seed: a point strictly inside a closed sub-domain, the region id given to its tets, and an upper bound on
/// tet volume there (m^3; 0 = no bound).
struct PlcRegion {
  Eigen::Vector3d seed = Eigen::Vector3d::Zero();
  int id = 0;
  double max_volume_m3 = 0.0;
};

/// The boundary description TetGen meshes. Facets must close the domain; facets between regions are allowed.
struct Plc {
  std::vector<Eigen::Vector3d> points;   ///< metres
  std::vector<PlcFacet> facets;
  std::vector<Eigen::Vector3d> holes;    ///< seeds of volume holes
  std::vector<PlcRegion> regions;
};

/// TetGen switches that matter here (always used: -p, -o2, -A, -Q; never -V).
struct TetgenOptions {
  double max_radius_edge_ratio = 2.0;  ///< -q bound (> ~1.1 to terminate); 0 disables quality refinement
  double min_dihedral_deg = 0.0;       ///< -q/<angle> (0 = TetGen default)
  double max_volume_m3 = 0.0;          ///< global tet volume bound (-a<v>), 0 = none; region bounds apply in addition
  bool preserve_boundary = false;      ///< -Y: no Steiner points on boundary facets
  /// Wall-clock budget of the TetGen run (s). TetGen 1.5 has no limit of its own and stalls on some inputs; the run
  /// is stopped and reported in one line when it is exceeded.
  double time_limit_s = 600.0;
  /// Node budget: the points TetGen may add to the PLC's (-S), 0 = none. A run that reaches it is refused in one line
  /// (TetGen would stop refining there and return a mesh short of its quality and size bounds).
  std::int64_t max_added_points = 0;
};

/// Meshes the PLC into a TET10 TetMesh: nodes n x 3 (m), tets in VTK quadratic-tetra order with positive corner
/// volume, midside nodes at edge midpoints, region ids from the PLC regions (0 when none), all boundary triangles as
/// TRI6 (corners ordered with the outward normal, then midsides (0,1),(1,2),(2,0)) with the marker of the facet they
/// lie on, and the quality of the linear tets. Throws InputError saying what TetGen was asked to do when it fails.
TetMesh tetrahedralize_plc(const Plc& plc, const TetgenOptions& options);

/// Dihedral angles and radius-edge ratio over the corner (linear) tets of the mesh.
MeshQuality mesh_quality(const TetMesh& mesh);

/// Volume of the quadratic mesh (m^3), exact for straight or curved TET10 (the Jacobian is integrated exactly).
double mesh_volume(const TetMesh& mesh);

/// Area (m^2) of the boundary faces carrying `marker`, integrated over the curved TRI6 geometry (6x6 Gauss
/// points per face, accurate to round-off for the gently curved faces meshes here have).
double boundary_area(const TetMesh& mesh, int marker);

/// Midside nodes of each VTK edge (0,1),(1,2),(0,2),(0,3),(1,3),(2,3): the local corner pairs.
inline constexpr int kTetEdges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};

}  // namespace sw
