#pragma once
// Axisymmetric solids: a profile in the (r, z) half-plane, revolved about z into a polygonal PLC, meshed by TetGen,
// then snapped onto the true surfaces of revolution (cylinders, planes, cones, tori). Metres.
#include <vector>

#include <Eigen/Core>

#include "common/params.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// The true surface a profile edge sweeps: the straight line through a and b (a plane z = const, a cylinder
/// r = const or a cone) or the circle (centre, radius) (a torus, e.g. a fillet), both in (r, z). `marker` is the
/// Surface marker its boundary faces get; edges between two regions use any marker (they are not boundary).
struct ProfileSurface {
  enum class Kind { Line, Circle };
  Kind kind = Kind::Line;
  Eigen::Vector2d a = Eigen::Vector2d::Zero(), b = Eigen::Vector2d::Zero();  ///< Line: two distinct points (r, z)
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();                           ///< Circle
  double radius = 0.0;                                                        ///< Circle
  int marker = kSurfaceOther;
};

/// A straight profile edge between two profile vertices, lying on surface `surface` (index into
/// RevolvedProfile::surfaces). Arcs are given as several edges on one Circle surface.
struct ProfileEdge {
  int v0 = 0, v1 = 0;
  int surface = 0;
};

/// A region of the profile: a seed strictly inside it (r, z), its region id and its target edge length (m).
struct ProfileRegion {
  Eigen::Vector2d seed = Eigen::Vector2d::Zero();
  int id = 0;
  double size_m = 1e-3;
};

/// Closed profile (edges may separate regions). Vertices with r = 0 lie on the axis; edges along the axis are
/// allowed (they sweep nothing). Each edge's target length is the smallest size of the regions it touches,
/// given per edge here.
struct RevolvedProfile {
  std::vector<Eigen::Vector2d> vertices;  ///< (r, z), metres, r >= 0
  std::vector<ProfileEdge> edges;
  std::vector<double> edge_size_m;        ///< per edge: target sub-segment length
  std::vector<ProfileSurface> surfaces;
  std::vector<ProfileRegion> regions;
};

/// Closest point on the surface of revolution to p (x, y, z in metres): the profile point nearest to (r, z) at the
/// same polar angle. For p on the axis the angle is taken as 0.
Eigen::Vector3d project_to_surface(const ProfileSurface& s, const Eigen::Vector3d& p);

/// Moves boundary nodes onto their true surfaces: every corner of a boundary face is projected onto the surface of
/// that face (Steiner points TetGen put on a flat facet), all midside nodes are then reset to their edge midpoints,
/// and the midside nodes of boundary faces are projected. face_surface[i] indexes `surfaces` for mesh.faces[i].
/// Interior midside nodes stay at midpoints. Precondition: the moves are small against the local edge length.
void project_boundary(TetMesh& mesh, const std::vector<int>& face_surface, const std::vector<ProfileSurface>& surfaces);

/// Meshes the revolved profile: each non-horizontal edge is split into sub-segments of at most its size and swept
/// as planar trapezoids over N angular steps (N per ring group, from the smallest size on it and its largest radius,
/// a multiple of 8 so the axes x, y are node planes); horizontal edges become planar annulus / disc facets. Each
/// region's tet volume is bounded by that of a regular tet of its size. Nodes on curved surfaces are then projected
/// (project_boundary) and the faces get the surface markers. Quality from `mesh`.
TetMesh mesh_revolved(const RevolvedProfile& profile, const MeshParams& mesh);

}  // namespace sw
