// Verification shapes: tube (also thick cylinder and short ring) and bar. Volumes and marked areas against the
// analytic values, each a conforming TET10 mesh with the tets its size asks for, nodes on the true surfaces, layers
// through the wall, refinement, errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <utility>

#include "common/error.hpp"
#include "mesh/revolve.hpp"
#include "mesh/shapes.hpp"
#include "mesh/tetgen_mesh.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;
// Curved TRI6/TET10 faces interpolate a circle quadratically between nodes on it: the relative area error is
// O(dθ^4), measured 1.5e-6 at 32 segments around (dθ = 0.196, the coarsest ring here), so 5e-6 relative.
constexpr double kCurvedGeometryTol = 5e-6;
// Nodes projected onto a cylinder: radius exact up to round-off of hypot and the rescaling.
constexpr double kOnSurfaceTol = 1e-12;

MeshParams params(double size_mm, int layers) {
  MeshParams p;
  p.size_m = size_mm * 1e-3;
  p.wall_layers = layers;
  return p;
}

double radius(const TetMesh& m, int node) { return std::hypot(m.nodes(node, 0), m.nodes(node, 1)); }

/// `m` is a conforming TET10 mesh: it has tets, a region per tet and boundary faces, and every node is a corner or the
/// one midside node of its edge (shared by every tet on that edge), so n_nodes = corners + edges. An empty mesh or one
/// with unused or duplicated nodes fails here.
void expect_tet10_mesh(const TetMesh& m) {
  ASSERT_FALSE(m.tets.empty());
  EXPECT_EQ(m.region.size(), m.tets.size());
  EXPECT_FALSE(m.faces.empty());
  std::set<int> corners;
  std::map<std::pair<int, int>, int> midside_of_edge;
  for (const auto& t : m.tets) {
    for (int k = 0; k < 4; ++k) corners.insert(t[k]);
    for (int e = 0; e < 6; ++e) {
      const int a = t[kTetEdges[e][0]], b = t[kTetEdges[e][1]];
      const auto [it, inserted] = midside_of_edge.try_emplace({std::min(a, b), std::max(a, b)}, t[4 + e]);
      ASSERT_EQ(it->second, t[4 + e]) << "edge " << a << "-" << b << " has two midside nodes";
    }
  }
  std::set<int> midsides;
  for (const auto& [edge, node] : midside_of_edge) midsides.insert(node);
  EXPECT_EQ(midsides.size(), midside_of_edge.size()) << "a midside node shared by two edges";
  EXPECT_EQ(m.n_nodes(), corners.size() + midside_of_edge.size()) << "nodes that no tet uses";
}

std::size_t faces_marked(const TetMesh& m, int marker) {
  return static_cast<std::size_t>(
      std::count_if(m.faces.begin(), m.faces.end(), [&](const BoundaryFace& f) { return f.marker == marker; }));
}

/// Fewest triangles that can cover `area_m2` when no triangle exceeds half a cell of a × b (m): 2·area / (a·b).
double fewest_triangles(double area_m2, double a_m, double b_m) { return 2.0 * area_m2 / (a_m * b_m); }

struct TubeDims { double ri, ro, length; };

class TubeShapes : public ::testing::TestWithParam<TubeDims> {};

TEST_P(TubeShapes, VolumeAndMarkedAreasMatchTheAnnulus) {
  const auto [ri, ro, L] = GetParam();
  const MeshParams mesh = params(2.0, 1);
  const TetMesh m = mesh_tube(ri, ro, L, mesh);
  expect_tet10_mesh(m);
  // The cylinders are swept quads no longer than `along` axially and no wider than `across` around (each ring gets
  // at least 2π r / across points), each split into two triangles.
  const WallSize w = wall_size(ro - ri, mesh);
  EXPECT_GE(faces_marked(m, kSurfaceInner), fewest_triangles(2 * kPi * ri * L, w.along_m, w.across_m));
  EXPECT_GE(faces_marked(m, kSurfaceOuter), fewest_triangles(2 * kPi * ro * L, w.along_m, w.across_m));
  EXPECT_NEAR(mesh_volume(m) / (kPi * (ro * ro - ri * ri) * L), 1.0, kCurvedGeometryTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceInner) / (2 * kPi * ri * L), 1.0, kCurvedGeometryTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceOuter) / (2 * kPi * ro * L), 1.0, kCurvedGeometryTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceClamped) / (kPi * (ro * ro - ri * ri)), 1.0, kCurvedGeometryTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceOpenEnd) / (kPi * (ro * ro - ri * ri)), 1.0, kCurvedGeometryTol);
  EXPECT_EQ(boundary_area(m, kSurfaceOther), 0.0);
  for (int r : m.region) ASSERT_EQ(r, 0);
  EXPECT_GT(m.quality.min_dihedral_deg, 5.0);
  EXPECT_GT(m.quality.max_radius_edge_ratio, 0.6);
}

INSTANTIATE_TEST_SUITE_P(TubeThickCylinderShortRing, TubeShapes,
                         ::testing::Values(TubeDims{18.5e-3, 19.5e-3, 30e-3},  // torsion tube
                                           TubeDims{10e-3, 20e-3, 10e-3},      // thick (Lamé) cylinder
                                           TubeDims{20e-3, 21e-3, 2e-3}));     // short thin ring

TEST(MeshTube, EveryBoundaryNodeOfACylinderLiesOnIt) {
  const double ri = 18.4e-3, ro = 19.0e-3;
  const TetMesh m = mesh_tube(ri, ro, 2e-3, params(0.6, 2));
  int checked_midsides = 0;
  for (const auto& f : m.faces) {
    if (f.marker != kSurfaceInner && f.marker != kSurfaceOuter) continue;
    const double r0 = f.marker == kSurfaceInner ? ri : ro;
    for (int k = 0; k < 6; ++k) ASSERT_NEAR(radius(m, f.nodes[k]) / r0, 1.0, kOnSurfaceTol) << "node slot " << k;
    checked_midsides += 3;
  }
  EXPECT_GT(checked_midsides, 1000);
  // Without the projection the midside of a chord spanning dθ = 2π/N sits at r cos(dθ/2): far outside the
  // tolerance, so the check above is meaningful (N <= 200 here gives 1.2e-4).
}

TEST(MeshTube, WallHasTheRequestedNumberOfLayers) {
  const double ri = 18.4e-3, ro = 19.0e-3, L = 1.5e-3;
  for (int layers : {1, 2, 3}) {
    const TetMesh m = mesh_tube(ri, ro, L, params(0.6, layers));
    const double across = (ro - ri) / layers;
    expect_tet10_mesh(m);
    EXPECT_NEAR(mesh_volume(m) / (kPi * (ro * ro - ri * ri) * L), 1.0, kCurvedGeometryTol);
    // Every layer cylinder r_i + k·across (k = 0..layers) carries corner nodes between the ends (the end annuli have
    // rings at these radii whether or not the layers exist): at least one ring, 8 points (revolve.cpp's fewest).
    for (int k = 0; k <= layers; ++k) {
      const double r = ri + k * across;
      std::set<int> on_cylinder;
      for (const auto& t : m.tets)
        for (int c = 0; c < 4; ++c)
          if (std::abs(radius(m, t[c]) / r - 1.0) < kOnSurfaceTol && m.nodes(t[c], 2) > 1e-9 &&
              m.nodes(t[c], 2) < L - 1e-9)
            on_cylinder.insert(t[c]);
      EXPECT_GE(on_cylinder.size(), 8u) << "layer cylinder " << k << " of " << layers;
    }
    // No tet reaches across more than one layer, so every radial line crosses at least `layers` tets.
    double widest = 0.0;
    for (const auto& t : m.tets) {
      double lo = 1, hi = 0;
      for (int k = 0; k < 4; ++k) {
        lo = std::min(lo, radius(m, t[k]));
        hi = std::max(hi, radius(m, t[k]));
      }
      widest = std::max(widest, hi - lo);
    }
    // A tet in one layer spans at most the layer plus the chord sag of its ring segment.
    EXPECT_LT(widest, across * 1.05) << layers << " layers";
  }
}

TEST(MeshTube, RefinementGivesMoreNodes) {
  const TetMesh coarse = mesh_tube(10e-3, 11e-3, 5e-3, params(1.0, 1));
  const TetMesh fine = mesh_tube(10e-3, 11e-3, 5e-3, params(0.5, 2));
  ASSERT_GT(coarse.n_nodes(), 0u);
  EXPECT_GT(fine.n_nodes(), 3 * coarse.n_nodes());
}

TEST(MeshTube, RejectsInvertedRadiiAndZeroLayers) {
  try {
    mesh_tube(19e-3, 18e-3, 5e-3, params(1.0, 2));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "tube outer radius = 18 mm; must be > inner radius = 19 mm");
  }
  try {
    mesh_tube(18e-3, 19e-3, 5e-3, params(1.0, 0));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "mesh.wall_layers = 0; must be >= 1");
  }
}

TEST(MeshBar, VolumeAndEndAreasAreExactAndMarked) {
  const double L = 20e-3, w = 2e-3, h = 3e-3;
  const MeshParams mesh = params(1.0, 2);
  const TetMesh m = mesh_bar(L, w, h, mesh);
  expect_tet10_mesh(m);
  // Every face is pre-split into a grid of spacing at most the edge size, each square two triangles.
  const double edge = wall_size(std::min(w, h), mesh).across_m;
  EXPECT_GE(m.faces.size(), fewest_triangles(2 * (L * w + L * h + w * h), edge, edge));
  // Straight-sided: exact up to round-off.
  EXPECT_NEAR(mesh_volume(m) / (L * w * h), 1.0, 1e-12);
  EXPECT_NEAR(boundary_area(m, kSurfaceClamped) / (w * h), 1.0, 1e-12);
  EXPECT_NEAR(boundary_area(m, kSurfaceBarEnd) / (w * h), 1.0, 1e-12);
  EXPECT_NEAR(boundary_area(m, kSurfaceOther) / (2 * L * (w + h)), 1.0, 1e-12);
  for (const auto& f : m.faces)
    if (f.marker == kSurfaceClamped)
      for (int k = 0; k < 6; ++k) ASSERT_EQ(m.nodes(f.nodes[k], 0), 0.0);
  double ymin = 1, ymax = -1;
  for (int i = 0; i < static_cast<int>(m.n_nodes()); ++i) {
    ymin = std::min(ymin, m.nodes(i, 1));
    ymax = std::max(ymax, m.nodes(i, 1));
  }
  EXPECT_DOUBLE_EQ(ymin, -w / 2);
  EXPECT_DOUBLE_EQ(ymax, w / 2);
}

TEST(ProjectToSurface, PutsPointsOnCylinderConeAndTorus) {
  ProfileSurface cyl;  // r = 5
  cyl.a = {5, 0};
  cyl.b = {5, 1};
  const Eigen::Vector3d p(3, 4.5, 2);
  const Eigen::Vector3d q = project_to_surface(cyl, p);
  EXPECT_NEAR(std::hypot(q.x(), q.y()), 5.0, 1e-14);
  EXPECT_NEAR(std::atan2(q.y(), q.x()), std::atan2(p.y(), p.x()), 1e-14);
  EXPECT_EQ(q.z(), 2.0);
  ProfileSurface torus;
  torus.kind = ProfileSurface::Kind::Circle;
  torus.centre = {10, 3};
  torus.radius = 2;
  const Eigen::Vector3d t = project_to_surface(torus, Eigen::Vector3d(0, 11, 4));
  EXPECT_NEAR(std::hypot(std::hypot(t.x(), t.y()) - 10, t.z() - 3), 2.0, 1e-14);
  EXPECT_NEAR(t.x(), 0.0, 1e-15);
  ProfileSurface cone;  // r = z
  cone.a = {0, 0};
  cone.b = {1, 1};
  const Eigen::Vector3d c = project_to_surface(cone, Eigen::Vector3d(2, 0, 0));
  EXPECT_NEAR(c.x(), 1.0, 1e-15);
  EXPECT_NEAR(c.z(), 1.0, 1e-15);
}

}  // namespace
}  // namespace sw
