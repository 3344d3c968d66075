// TetGen wrapper: TET10 numbering, orientation, boundary faces, markers, regions, size control and errors, on a
// box split by an interior facet into two regions (everything here has an exact answer).
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include <Eigen/Geometry>

#include "common/error.hpp"
#include "mesh/tetgen_mesh.hpp"

namespace sw {
namespace {

// Box [0,a]x[0,b]x[0,c] with an interior facet at x = a/2 separating region 0 (x < a/2) from region 1.
// Facet markers: 1 at x=0, 2 at x=a, 3..6 for the y/z sides of both halves (3,4 left half, 5,6 right half
// are split per half), 9 on the interior facet.
constexpr double kA = 2e-3, kB = 1e-3, kC = 1.5e-3;
Plc split_box(double max_volume_left, double max_volume_right) {
  Plc plc;
  const double xs[3] = {0, kA / 2, kA};
  for (double x : xs)
    for (double y : {0.0, kB})
      for (double z : {0.0, kC}) plc.points.emplace_back(x, y, z);
  auto id = [](int i, int j, int k) { return 4 * i + 2 * j + k; };  // i: x-level 0..2
  plc.facets.push_back({{{id(0, 0, 0), id(0, 1, 0), id(0, 1, 1), id(0, 0, 1)}}, {}, 1});
  plc.facets.push_back({{{id(2, 0, 0), id(2, 1, 0), id(2, 1, 1), id(2, 0, 1)}}, {}, 2});
  plc.facets.push_back({{{id(1, 0, 0), id(1, 1, 0), id(1, 1, 1), id(1, 0, 1)}}, {}, 9});
  for (int h = 0; h < 2; ++h) {  // the four sides of each half
    plc.facets.push_back({{{id(h, 0, 0), id(h + 1, 0, 0), id(h + 1, 0, 1), id(h, 0, 1)}}, {}, 3});  // y = 0
    plc.facets.push_back({{{id(h, 1, 0), id(h + 1, 1, 0), id(h + 1, 1, 1), id(h, 1, 1)}}, {}, 4});  // y = b
    plc.facets.push_back({{{id(h, 0, 0), id(h + 1, 0, 0), id(h + 1, 1, 0), id(h, 1, 0)}}, {}, 5});  // z = 0
    plc.facets.push_back({{{id(h, 0, 1), id(h + 1, 0, 1), id(h + 1, 1, 1), id(h, 1, 1)}}, {}, 6});  // z = c
  }
  plc.regions.push_back({Eigen::Vector3d(kA / 4, kB / 2, kC / 2), 0, max_volume_left});
  plc.regions.push_back({Eigen::Vector3d(3 * kA / 4, kB / 2, kC / 2), 1, max_volume_right});
  return plc;
}

// Round-off scale for coordinates of a few mm: 1e-15 relative to the box size.
constexpr double kRoundOff = 1e-15 * kA;

TEST(TetgenMesh, EveryMidsideNodeIsTheMidpointOfItsVtkEdge) {
  const TetMesh m = tetrahedralize_plc(split_box(1e-10, 1e-10), {});
  ASSERT_GT(m.tets.size(), 100u);
  for (const auto& t : m.tets)
    for (int e = 0; e < 6; ++e) {
      const Eigen::Vector3d mid = 0.5 * (m.nodes.row(t[kTetEdges[e][0]]) + m.nodes.row(t[kTetEdges[e][1]]));
      ASSERT_LT((m.nodes.row(t[4 + e]).transpose() - mid).norm(), kRoundOff) << "edge " << e;
    }
}

TEST(TetgenMesh, CornerOrderGivesPositiveVolumeAndTheVolumeIsExact) {
  const TetMesh m = tetrahedralize_plc(split_box(1e-10, 1e-10), {});
  for (const auto& t : m.tets) {
    const Eigen::Vector3d a = m.nodes.row(t[0]), b = m.nodes.row(t[1]), c = m.nodes.row(t[2]),
                          d = m.nodes.row(t[3]);
    ASSERT_GT((b - a).cross(c - a).dot(d - a), 0.0);
  }
  // Straight-sided TET10 of a box: the volume is exact up to summation round-off.
  EXPECT_NEAR(mesh_volume(m), kA * kB * kC, 1e-12 * kA * kB * kC);
}

TEST(TetgenMesh, BoundaryFacesCarryTheirFacetMarkersAndAreaAndPointOutward) {
  const TetMesh m = tetrahedralize_plc(split_box(1e-10, 1e-10), {});
  const double tol = 1e-12 * kA * kB;  // straight TRI6: area exact up to round-off
  EXPECT_NEAR(boundary_area(m, 1), kB * kC, tol);
  EXPECT_NEAR(boundary_area(m, 2), kB * kC, tol);
  EXPECT_NEAR(boundary_area(m, 3), kA * kC, tol);
  EXPECT_NEAR(boundary_area(m, 4), kA * kC, tol);
  EXPECT_NEAR(boundary_area(m, 5), kA * kB, tol);
  EXPECT_NEAR(boundary_area(m, 6), kA * kB, tol);
  EXPECT_EQ(boundary_area(m, 9), 0.0) << "the interior facet is not a boundary";
  EXPECT_EQ(boundary_area(m, kSurfaceOther), 0.0) << "every boundary face has a facet marker";
  // Divergence theorem with F = x/3: sum over faces of (x . n) area / 3 = volume, only with outward normals.
  double flux = 0.0;
  for (const auto& f : m.faces) {
    const Eigen::Vector3d a = m.nodes.row(f.nodes[0]), b = m.nodes.row(f.nodes[1]), c = m.nodes.row(f.nodes[2]);
    flux += (a + b + c).dot((b - a).cross(c - a)) / 18.0;
    // Face midsides: (0,1), (1,2), (2,0).
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector3d mid = 0.5 * (m.nodes.row(f.nodes[e]) + m.nodes.row(f.nodes[(e + 1) % 3]));
      ASSERT_LT((m.nodes.row(f.nodes[3 + e]).transpose() - mid).norm(), kRoundOff);
    }
  }
  EXPECT_NEAR(flux, kA * kB * kC, 1e-12 * kA * kB * kC);
}

TEST(TetgenMesh, RegionsGetTheirIdsAndTheirVolumeBound) {
  const double vmax_left = 2e-11, vmax_right = 2e-12;
  const TetMesh m = tetrahedralize_plc(split_box(vmax_left, vmax_right), {});
  ASSERT_EQ(m.region.size(), m.tets.size());
  std::size_t n_left = 0, n_right = 0;
  for (std::size_t t = 0; t < m.tets.size(); ++t) {
    const auto& tt = m.tets[t];
    const Eigen::Vector3d a = m.nodes.row(tt[0]), b = m.nodes.row(tt[1]), c = m.nodes.row(tt[2]),
                          d = m.nodes.row(tt[3]);
    const double v = (b - a).cross(c - a).dot(d - a) / 6.0;
    const double xc = (a + b + c + d).x() / 4.0;
    ASSERT_EQ(m.region[t], xc < kA / 2 ? 0 : 1);
    ASSERT_LE(v, (m.region[t] == 0 ? vmax_left : vmax_right) * (1 + 1e-9));
    (m.region[t] == 0 ? n_left : n_right)++;
  }
  // A 10x smaller volume bound must give clearly more tets (equal halves otherwise).
  EXPECT_GT(n_right, 4 * n_left);
}

TEST(TetgenMesh, QualityIsReportedAndHonoursTheRadiusEdgeBound) {
  TetgenOptions o;
  o.max_radius_edge_ratio = 1.5;
  const TetMesh m = tetrahedralize_plc(split_box(1e-10, 1e-10), o);
  EXPECT_GT(m.quality.min_dihedral_deg, 5.0);
  EXPECT_LT(m.quality.max_dihedral_deg, 175.0);
  EXPECT_GT(m.quality.max_radius_edge_ratio, 0.6);  // >= sqrt(6)/4 = 0.61 for the best possible tet
  // TetGen's -q bound holds for tets away from the boundary; boundary-constrained tets may exceed it somewhat.
  EXPECT_LT(m.quality.max_radius_edge_ratio, 3.0);
  const MeshQuality again = mesh_quality(m);
  EXPECT_EQ(again.min_dihedral_deg, m.quality.min_dihedral_deg);
}

TEST(TetgenMesh, SmallerVolumeBoundGivesMoreNodes) {
  const TetMesh coarse = tetrahedralize_plc(split_box(1e-10, 1e-10), {});
  const TetMesh fine = tetrahedralize_plc(split_box(1e-11, 1e-11), {});
  EXPECT_GT(fine.n_nodes(), 3 * coarse.n_nodes());
}

TEST(TetgenMesh, TetgenFailureBecomesInputErrorSayingWhatWasAsked) {
  Plc plc = split_box(0, 0);
  // A facet that cuts through the box's y = 0 side: self-intersecting boundary.
  const int base = static_cast<int>(plc.points.size());
  plc.points.emplace_back(kA / 4, -kB, kC / 2);
  plc.points.emplace_back(kA / 4, kB / 2, kC / 2);
  plc.points.emplace_back(kA / 4 + 1e-4, kB / 2, kC / 4);
  plc.facets.push_back({{{base, base + 1, base + 2}}, {}, 7});
  try {
    tetrahedralize_plc(plc, {});
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("TetGen -p"), std::string::npos) << msg;
    EXPECT_NE(msg.find("12 facets"), std::string::npos) << msg;
    EXPECT_NE(msg.find("intersect"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line";
  }
}

// A run past its wall-clock budget is stopped and reported in one line (TetGen itself has no limit).
TEST(TetgenMesh, ARunPastItsBudgetStopsWithOneLine) {
  TetgenOptions o;
  o.max_volume_m3 = kA * kB * kC / 2e6;  // about 10^7 tetrahedra: far beyond 50 ms
  o.time_limit_s = 0.05;
  try {
    tetrahedralize_plc(split_box(0, 0), o);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("did not finish within its budget of 0.05"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line";
  }
}

// A run that reaches its node budget (points TetGen may add) is refused in one line instead of returning a mesh
// short of its bounds; below the budget the same run meshes.
TEST(TetgenMesh, ARunReachingItsNodeBudgetStopsWithOneLine) {
  TetgenOptions o;
  o.max_volume_m3 = kA * kB * kC / 2e4;  // about 10^5 tetrahedra, some 2·10^4 added points
  o.max_added_points = 500;
  try {
    tetrahedralize_plc(split_box(0, 0), o);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("reached its node budget of 500 added points"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line";
  }
  o.max_added_points = 1000000;
  EXPECT_GT(tetrahedralize_plc(split_box(0, 0), o).tets.size(), 10000u);
}

}  // namespace
}  // namespace sw
