#pragma once
// The flexspline's meridian section (the (r, z) half-plane of a body of revolution) as quadratic triangles, for the
// semi-analytical harmonic solver (fem/fourier_solver.hpp). The profile is the one mesh/flexspline.hpp revolves:
// tube or cup, body wall, toothed rim as the equivalent ring ("ring"), plain ("none") or with the teeth as a layer of
// ribs along the face on it ("layer": region kToothLayerRegion, its solidity in SectionMesh::tooth_layer), diaphragm,
// fillet, boss.
//
// Structured blocks, each split into two 6-node triangles per cell: every wall has the same number of layers
// (max of wall_size(thickness).layers over the body wall and the diaphragm, so blocks meet conformingly), cells
// along a wall of at most wall_size().along. The fillet corner is two blocks of straight rays from the fillet's
// centre to the outer corner of the diaphragm/wall elbow, so the arc is exact at every node (midside nodes on it).
// Axial node lines at the wave generator's band edges z_wg ± band_width/2, so band loads and the cam's prescription
// cover exactly the band. Metres.
#include <array>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "fem/flexspline_model.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// The region of the tooth layer's triangles.
inline constexpr int kToothLayerRegion = 4;

/// A boundary edge of the section: end nodes 0, 1 and the midside node 2; `marker` is a mesh/tet_mesh.hpp Surface.
struct SectionEdge {
  std::array<int, 3> nodes{};
  int marker = kSurfaceOther;
};

/// The teeth as a homogenised layer on the rim (teeth = "layer"): its solidity φ(r), the fraction of the circle at
/// radius r that is tooth (gear/tooth_profile.hpp flexspline_solidity), tabulated from the rim's outer radius to the
/// tip and read by linear interpolation; and the ribs' factor on their shear along the face (fem/rib_cell.hpp).
struct ToothLayer {
  std::vector<double> radius_m, solidity;
  double shear_factor = 1.0;  ///< κ of G_θz = κ φ G: the rib's anti-plane shear on its rim against the rule of mixtures
  double at(double r_m) const;
};

/// 6-node triangles in (r, z): corners 0..2 counter-clockwise, then midsides of edges (0,1), (1,2), (2,0).
struct SectionMesh {
  Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> nodes;  ///< (r, z), metres
  std::vector<std::array<int, 6>> triangles;
  std::vector<int> region;          ///< per triangle: 0 body, 1 rim, 2 diaphragm, 3 boss (as mesh/flexspline.hpp),
                                    ///< kToothLayerRegion the tooth layer
  std::optional<ToothLayer> tooth_layer;  ///< teeth = "layer": the layer's solidity (its triangles' region)
  std::vector<SectionEdge> edges;   ///< boundary edges with markers (the axis r = 0 carries none)
  std::size_t n_nodes() const { return static_cast<std::size_t>(nodes.rows()); }
};

/// Meshes the section of the flexspline `f` (validated as mesh_flexspline does; teeth "explicit" is rejected: the
/// toothed rim is not a body of revolution). `band`: the generator's (z centre, width) to resolve, if any.
SectionMesh mesh_flexspline_section(const FlexsplineParams& f, const std::optional<GearParams>& gear,
                                    const MeshParams& mesh, std::optional<std::pair<double, double>> band = {});

/// A straight annular section r_inner..r_outer × 0..length (the thick cylinder): markers kSurfaceClamped at z = 0,
/// kSurfaceOpenEnd at z = length, kSurfaceInner, kSurfaceOuter; `layers` × `cells_along` cells.
SectionMesh mesh_annulus_section(double r_inner_m, double r_outer_m, double length_m, int layers, int cells_along);

/// The same with the caller's cell corners: r_m from the inner to the outer radius, z_m from 0 to the length (each
/// increasing, at least two values; metres).
SectionMesh mesh_annulus_section(const std::vector<double>& r_m, const std::vector<double>& z_m);

/// Element and natural coordinates (ξ, η) of a point (r, z); element −1 when outside the section.
std::pair<long, Eigen::Vector2d> locate_in_section(const SectionMesh& s, const Eigen::Vector2d& rz);

/// T6 shape functions at natural coordinates (ξ, η) (area coordinates L1 = 1 − ξ − η, L2 = ξ, L3 = η).
Eigen::Matrix<double, 6, 1> t6_shape(double xi, double eta);
/// Their derivatives: row 0 d/dξ, row 1 d/dη.
Eigen::Matrix<double, 2, 6> t6_shape_derivatives(double xi, double eta);

}  // namespace sw
