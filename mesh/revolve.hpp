#pragma once
// Axisymmetric solids: a profile in the (r, z) half-plane, revolved about z into a polygonal PLC, meshed by TetGen,
// then snapped onto the true surfaces of revolution (cylinders, planes, cones, tori). Metres.
#include <vector>

#include <Eigen/Core>

#include "mesh/flexspline_params.hpp"
#include "mesh/tet_mesh.hpp"
#include "mesh/tetgen_mesh.hpp"

namespace sw {

/// The true surface a profile edge sweeps: the straight line through a and b (a plane z = const, a cylinder
/// r = const or a cone) or the circle (centre, radius) (a torus, e.g. a fillet), both in (r, z). `marker` is the
/// Surface marker its boundary faces get; edges between two regions use any marker (they are not boundary).
struct ProfileSurface {
  enum class Kind { Line, Circle, Fixed };  ///< Fixed: a non-revolved facet given exactly by its points (no projection)
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

/// A local size field on the profile, graded toward singular points (r, z) such as a clamp's corner: the target edge
/// length at p is size_m + growth · |p − point| (the smallest over the points), never more than an edge's own size.
/// Edges are split by it (graded sub-segments) and rings take their angular counts from max_aspect times it: the
/// fields at such a ring corner vary with (r, z) far faster than around the axis, so the angular spacing may exceed
/// the profile spacing there. Empty points: no local refinement.
struct ProfileSizeField {
  std::vector<Eigen::Vector2d> points;  ///< (r, z), metres
  double size_m = 0.0;                  ///< edge length at the points
  double growth = 0.5;                  ///< increase of the edge length per unit distance from them
  double max_aspect = 1.0;              ///< angular spacing / profile spacing allowed near the points (>= 1)
  /// Target length at p given the edge's own size (m).
  double at(const Eigen::Vector2d& p, double edge_size_m) const;
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
  ProfileSizeField refine;                ///< local refinement (none by default)
};

/// Closest point on the surface of revolution to p (x, y, z in metres): the profile point nearest to (r, z) at the
/// same polar angle. For p on the axis the angle is taken as 0.
Eigen::Vector3d project_to_surface(const ProfileSurface& s, const Eigen::Vector3d& p);

/// Moves boundary nodes onto their true surfaces: every corner of a boundary face is projected onto the surface of
/// that face (Steiner points TetGen put on a flat facet), all midside nodes are then reset to their edge midpoints,
/// and the midside nodes of boundary faces are projected. face_surface[i] indexes `surfaces` for mesh.faces[i].
/// Interior midside nodes stay at midpoints. Precondition: the moves are small against the local edge length.
void project_boundary(TetMesh& mesh, const std::vector<int>& face_surface, const std::vector<ProfileSurface>& surfaces);

/// A revolved profile turned into a PLC (steps 1-4 of mesh_revolved), with the rings of points it is made of, so that
/// a caller can attach non-axisymmetric facets to those rings (e.g. a toothed prism) before meshing it with
/// mesh_revolved_plc. Facet marker = surface index + 1; region volume bounds from the region sizes.
struct RevolvedPlc {
  Plc plc;
  std::vector<Eigen::Vector2d> vertex_rz;  ///< per profile vertex after splitting: (r, z), metres
  std::vector<int> first, count;           ///< per vertex: its ring's first PLC point and size (-1 / 0: unused)
  std::vector<int> ring_of_point, index_in_ring;  ///< per revolved PLC point: its vertex (-1 on the axis), its k
  /// PLC points of the ring through (r, z), point k at polar angle 2 pi k / n. Throws InputError when no ring
  /// passes there (a caller's geometry that does not meet the profile).
  std::vector<int> ring(double r_m, double z_m) const;
};

/// Steps 1-4 of mesh_revolved: split the edges, choose the angular counts and build the PLC.
RevolvedPlc revolve_profile(const RevolvedProfile& profile);

/// Meshes a revolved PLC, possibly extended by the caller (points appended after the revolved ones, facets with
/// markers = index + 1 into `surfaces`, which extends profile.surfaces; Kind::Fixed surfaces are not projected),
/// then projects the curved-surface nodes and the ring chords' midside nodes and sets the surface markers.
/// `max_added_points` is TetGen's node budget (TetgenOptions; 0 = none).
TetMesh mesh_revolved_plc(const RevolvedPlc& revolved, const std::vector<ProfileSurface>& surfaces,
                          const MeshParams& mesh, std::int64_t max_added_points = 0);

/// Meshes the revolved profile: each non-horizontal edge is split into sub-segments of at most its size and swept
/// as planar trapezoids over N angular steps (N per ring group, from the smallest size on it and its largest radius,
/// a multiple of 8 so the axes x, y are node planes); horizontal edges become planar annulus / disc facets. Each
/// region's tet volume is bounded by that of a regular tet of its size. Nodes on curved surfaces are then projected
/// (project_boundary) and the faces get the surface markers. Quality from `mesh`.
TetMesh mesh_revolved(const RevolvedProfile& profile, const MeshParams& mesh, std::int64_t max_added_points = 0);

}  // namespace sw
