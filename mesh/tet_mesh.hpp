#pragma once
// The quadratic tetrahedral mesh every later stage works on. Metres. Axis of the flexspline = z, clamped end at z = 0
// (the tube's clamped end, the cup's boss), open end at z = length. Angles θ are measured from +x, which is the
// wave generator's major axis.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace sw {

/// Boundary-face markers. Every boundary triangle carries one; the FEM picks its loads and supports by marker.
enum Surface : int {
  kSurfaceOther = 0,
  kSurfaceClamped = 1,     ///< fixed: tube end at z = 0, cup boss (hub) faces
  kSurfaceInner = 2,       ///< inner cylindrical wall (body and rim): wave generator acts here
  kSurfaceOuter = 3,       ///< outer cylindrical wall of the body (below the rim)
  kSurfaceRimOuter = 4,    ///< outer surface of the toothed rim (equivalent ring or tooth flanks/tips/roots)
  kSurfaceOpenEnd = 5,     ///< annular face at z = length
  kSurfaceDiaphragm = 6,   ///< cup: diaphragm faces, fillet, step faces
  kSurfaceBarEnd = 7,      ///< bar: the loaded end x = length (fixed end is kSurfaceClamped)
  kSurfaceRimStep = 8,     ///< annular shoulder z = length - rim_width between the body's outer wall and the rim's outer surface
};

/// A boundary triangle, quadratic: corners 0..2 then midsides of edges (0,1), (1,2), (2,0).
struct BoundaryFace {
  std::array<int, 6> nodes{};
  int marker = kSurfaceOther;
};

struct MeshQuality {
  double min_dihedral_deg = 0.0;
  double max_dihedral_deg = 0.0;
  double max_radius_edge_ratio = 0.0;
};

/// TET10 mesh. Connectivity in VTK_QUADRATIC_TETRA order: corners 0..3, then midsides of edges
/// (0,1), (1,2), (0,2), (0,3), (1,3), (2,3). Corner order gives positive volume.
struct TetMesh {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> nodes;  ///< n_nodes x 3, metres
  std::vector<std::array<int, 10>> tets;
  std::vector<int> region;               ///< per tet: region id (0 = body, 1 = rim, 2 = diaphragm, 3 = boss, ...)
  std::vector<BoundaryFace> faces;       ///< all boundary triangles, with markers
  MeshQuality quality;
  std::size_t n_nodes() const { return static_cast<std::size_t>(nodes.rows()); }
};

}  // namespace sw
