// Flexspline meshes: volume and marked areas against the analytic revolved profile, regions, and every rejected
// inconsistent combination with its message.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "common/error.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/estimate.hpp"
#include "mesh/flexspline.hpp"
#include "mesh/shapes.hpp"
#include "mesh/tetgen_mesh.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;
// Quadratic faces on cylinders (>= 100 segments around) are exact to ~1e-8; the fillet torus is followed by
// quadratic faces over arc pieces of up to 45 degrees, whose interpolation error is O(dφ^4) ~ 1e-3 of the fillet's
// small share of the volume: 1e-4 relative overall, the accuracy the FEM needs from the geometry.
constexpr double kVolumeTol = 1e-4;
constexpr double kAreaTol = 1e-4;
// At the coarse test size (1 mm edges on a 1 mm fillet: 1.5 edges per quarter arc) some fillet elements would be
// inverted by projecting their midside nodes onto the torus; the mesher straightens those (revolve.cpp), which moves
// the fillet's volume and area by up to ~0.4 % of the body. Finer meshes project them.
constexpr double kCoarseFilletTol = 5e-3;
// Interfaces between regions are not projected except along their ring edges (only boundary faces are), so how
// the volume splits between boss and diaphragm across the interface cylinder r = boss_radius carries the chordal
// error of that polygonal surface, O(dθ^2 / 24) ~ 5e-4 at the coarse ring (56 points); the total is unaffected.
constexpr double kRegionSplitTol = 2e-3;

// A cup whose rim matches the default gear's root circle (19.0425 mm) within 0.25 module.
FlexsplineParams seed_cup() {
  FlexsplineParams f;
  f.rim_thickness_m = 0.65e-3;
  return f;
}

MeshParams coarse() {
  MeshParams m;
  m.size_m = 1.0e-3;
  m.wall_layers = 1;
  return m;
}

double region_volume(const TetMesh& m, int region) {
  TetMesh sub;
  sub.nodes = m.nodes;
  for (std::size_t t = 0; t < m.tets.size(); ++t)
    if (m.region[t] == region) sub.tets.push_back(m.tets[t]);
  return mesh_volume(sub);
}

TEST(MeshFlexspline, CupVolumeRegionsAndMarkedAreasMatchTheProfile) {
  const FlexsplineParams f = seed_cup();
  const GearParams g;
  const TetMesh m = mesh_flexspline(f, g, coarse());
  const double ri = f.inner_radius_m, ro = ri + f.wall_thickness_m, L = f.length_m, w = f.rim_width_m;
  const double td = f.diaphragm_thickness_m, rb = f.boss_radius_m, rf = f.fillet_radius_m, hb = 2 * td;
  const double rr = rim_outer_radius(f, g);
  EXPECT_GT(rr, ri + f.rim_thickness_m);
  // Fillet web: the corner square minus the quarter disc, revolved (Pappus).
  const double web = 2 * kPi * (rf * rf * (ri - rf / 2) - kPi * rf * rf / 4 * (ri - rf + 4 * rf / (3 * kPi)));
  const double boss = kPi * rb * rb * hb;
  const double diaphragm = kPi * (ro * ro - rb * rb) * td;
  const double body = kPi * (ro * ro - ri * ri) * (L - w - td) + web;
  const double rim = kPi * (rr * rr - ri * ri) * w;
  EXPECT_NEAR(region_volume(m, 3) / boss, 1.0, kRegionSplitTol);
  EXPECT_NEAR(region_volume(m, 2) / diaphragm, 1.0, kRegionSplitTol);
  EXPECT_NEAR(region_volume(m, 0) / body, 1.0, kCoarseFilletTol);
  EXPECT_NEAR(region_volume(m, 1) / rim, 1.0, kVolumeTol);
  EXPECT_NEAR(mesh_volume(m) / (boss + diaphragm + body + rim), 1.0, kCoarseFilletTol);

  const double fillet_area = 2 * kPi * rf * ((ri - rf) * kPi / 2 + rf);
  EXPECT_NEAR(boundary_area(m, kSurfaceInner) / (2 * kPi * ri * (L - td - rf)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceOuter) / (2 * kPi * ro * (L - w)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceRimOuter) / (2 * kPi * rr * w), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceOpenEnd) / (kPi * (rr * rr - ri * ri)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceRimStep) / (kPi * (rr * rr - ro * ro)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceClamped) / (2 * kPi * rb * rb + 2 * kPi * rb * (hb - td)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceDiaphragm) /
                  (kPi * (ro * ro - rb * rb) + kPi * ((ri - rf) * (ri - rf) - rb * rb) + fillet_area),
              1.0, kCoarseFilletTol);
  EXPECT_EQ(boundary_area(m, kSurfaceOther), 0.0);
  EXPECT_GT(m.quality.min_dihedral_deg, 3.0);
}

TEST(MeshFlexspline, ToothedTubeHasBodyAndRimAndPlainTubeIsTheAnnulus) {
  FlexsplineParams f = seed_cup();
  f.shape = FlexsplineShape::Tube;
  const GearParams g;
  const TetMesh m = mesh_flexspline(f, g, coarse());
  const double ri = f.inner_radius_m, ro = ri + f.wall_thickness_m, L = f.length_m, w = f.rim_width_m;
  const double rr = rim_outer_radius(f, g);
  EXPECT_NEAR(region_volume(m, 0) / (kPi * (ro * ro - ri * ri) * (L - w)), 1.0, kVolumeTol);
  EXPECT_NEAR(region_volume(m, 1) / (kPi * (rr * rr - ri * ri) * w), 1.0, kVolumeTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceClamped) / (kPi * (ro * ro - ri * ri)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceInner) / (2 * kPi * ri * L), 1.0, kAreaTol);

  f.teeth = TeethModel::None;
  const TetMesh plain = mesh_flexspline(f, std::nullopt, coarse());
  EXPECT_NEAR(mesh_volume(plain) / (kPi * (ro * ro - ri * ri) * L), 1.0, kVolumeTol);
  EXPECT_EQ(boundary_area(plain, kSurfaceRimOuter), 0.0);
}

// One rejected combination per rule, with the exact message.
struct Bad {
  const char* name;
  void (*edit)(FlexsplineParams&, MeshParams&);
  const char* message;
};

class MeshFlexsplineRejects : public ::testing::TestWithParam<Bad> {};

TEST_P(MeshFlexsplineRejects, InconsistentKeysWithAMessageNamingThem) {
  FlexsplineParams f = seed_cup();
  MeshParams m = coarse();
  GetParam().edit(f, m);
  try {
    validate_flexspline(f, m);
    check_teeth_on_rim(f, GearParams{});
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), GetParam().message);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Rules, MeshFlexsplineRejects,
    ::testing::Values(
        Bad{"FilletTooLarge", [](FlexsplineParams& f, MeshParams&) { f.fillet_radius_m = 11e-3; },
            "flexspline.fillet_radius_mm = 11; must be < inner_radius_mm - boss_radius_mm = 10.4"},
        Bad{"BossLargerThanInnerRadius", [](FlexsplineParams& f, MeshParams&) { f.boss_radius_m = 19e-3; },
            "flexspline.boss_radius_mm = 19; must be < inner_radius_mm = 18.4"},
        Bad{"NegativeRim", [](FlexsplineParams& f, MeshParams&) { f.rim_thickness_m = -0.1e-3; },
            "flexspline.rim_thickness_mm = -0.1; must be > 0"},
        Bad{"RimThinnerThanWall", [](FlexsplineParams& f, MeshParams&) { f.rim_thickness_m = 0.5e-3; },
            "flexspline.rim_thickness_mm = 0.5; must be >= wall_thickness_mm = 0.6 (the rim is the thick end of the "
            "wall)"},
        Bad{"RimWiderThanBody", [](FlexsplineParams& f, MeshParams&) { f.rim_width_m = 18.5e-3; },
            "flexspline.rim_width_mm = 18.5; must be < length_mm - diaphragm_thickness_mm - fillet_radius_mm = 18"},
        Bad{"NegativeWall", [](FlexsplineParams& f, MeshParams&) { f.wall_thickness_m = -0.4e-3; },
            "flexspline.wall_thickness_mm = -0.4; must be > 0"},
        Bad{"RootCircleMismatch", [](FlexsplineParams& f, MeshParams&) { f.rim_thickness_m = 0.7e-3; },
            "flexspline.rim_thickness_mm = 0.7; inner_radius_mm + rim_thickness_mm = 19.1 must match the teeth's root "
            "circle 19.0425 mm (from [gear]) within 0.25 module = 0.05 mm"},
        Bad{"ZeroLayers", [](FlexsplineParams&, MeshParams& m) { m.wall_layers = 0; },
            "mesh.wall_layers = 0; must be >= 1"},
        Bad{"DiaphragmAsLongAsTheCup", [](FlexsplineParams& f, MeshParams&) { f.diaphragm_thickness_m = 20e-3; },
            "flexspline.diaphragm_thickness_mm = 20; must be < length_mm = 20"}),
    [](const ::testing::TestParamInfo<Bad>& info) { return std::string(info.param.name); });

TEST(MeshFlexspline, RingTeethNeedTheGearTable) {
  EXPECT_THROW(mesh_flexspline(seed_cup(), std::nullopt, coarse()), InputError);
}

// ---- Explicit teeth ----------------------------------------------------------------------------------------------

// Area (m^2) and perimeter (m) of a closed polygon.
double polygon_area(const std::vector<Eigen::Vector2d>& p) {
  double a = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& u = p[i];
    const auto& v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - v.x() * u.y();
  }
  return 0.5 * a;
}
double polygon_perimeter(const std::vector<Eigen::Vector2d>& p) {
  double l = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) l += (p[(i + 1) % p.size()] - p[i]).norm();
  return l;
}

// A coarse gear (module 0.5, 72 teeth) on a small cup whose rim base reaches 0.4 mm beyond the body wall, so the
// explicit teeth mesh in about a second; the seed gear is exercised by the budget test below.
GearParams coarse_gear() {
  GearParams g;
  g.module_m = 0.5e-3;
  g.teeth_flexspline = 72;
  g.teeth_circular = 74;
  g.profile_shift_flexspline = 1.0;
  g.profile_shift_circular = 1.05;
  g.cutter_teeth = 30;
  return g;
}
FlexsplineParams coarse_toothed_cup(const GearParams& g) {
  FlexsplineParams f;
  f.rim_thickness_m = 1.2e-3;
  f.inner_radius_m = gear_radii(g).root_f - f.rim_thickness_m;
  f.wall_thickness_m = 0.8e-3;
  f.length_m = 12e-3;
  f.rim_width_m = 4e-3;
  f.boss_radius_m = 6e-3;
  f.teeth = TeethModel::Explicit;
  return f;
}

// The mesh's outline is a polyline of ~4 points per involute flank, with points closer than 0.4 of the tooth edge
// merged (the root fillet becomes a chord): the flank chords' sagitta loses ~2e-5 mm^2 per segment and the merged
// fillet adds up to ~4e-3 mm^2 per pitch against ~1.4 mm^2 of rim cross-section per pitch (measured +0.2 %), and the
// flanks' polyline is shorter than the curve, the merged fillet chord most (measured -1.2 %, -1.0 % at the seed gear).
constexpr double kRimOutlineTol = 5e-3;
constexpr double kFlankAreaTol = 2e-2;
// The revolved parts (body, diaphragm, boss) are those of the ring variant up to the angular counts of shared rings.
// The two meshes differ where the mesher straightens elements that projection would distort (coarse fillet, see
// kCoarseFilletTol), which differs by up to ~2e-4 of a region between them.
constexpr double kSameRevolvedTol = 1e-3;
constexpr double kMidsideMoveTol = 0.02e-3;

TEST(MeshFlexsplineExplicitTeeth, VolumeAndToothSurfacesMatchTheOutlineExtrudedOverTheRim) {
  const GearParams g = coarse_gear();
  const FlexsplineParams f = coarse_toothed_cup(g);
  const TetMesh m = mesh_flexspline(f, g, coarse());
  const double ri = f.inner_radius_m, ro = ri + f.wall_thickness_m, L = f.length_m, w = f.rim_width_m;
  const double td = f.diaphragm_thickness_m, rb = f.boss_radius_m, rf = f.fillet_radius_m, hb = 2 * td;
  const auto outline = flexspline_outline(g, 60);  // the exact profile, to ~1e-7 of its area
  const double area = polygon_area(outline), perimeter = polygon_perimeter(outline);
  EXPECT_NEAR(region_volume(m, 1) / ((area - kPi * ri * ri) * w), 1.0, kRimOutlineTol);
  FlexsplineParams ring = f;
  ring.teeth = TeethModel::Ring;
  const TetMesh r = mesh_flexspline(ring, g, coarse());
  for (const int region : {0, 2, 3}) EXPECT_NEAR(region_volume(m, region) / region_volume(r, region), 1.0, kSameRevolvedTol);

  EXPECT_NEAR(boundary_area(m, kSurfaceRimOuter) / (perimeter * w), 1.0, kFlankAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceOpenEnd) / (area - kPi * ri * ri), 1.0, kRimOutlineTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceRimStep) / (area - kPi * ro * ro), 1.0, kRimOutlineTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceInner) / (2 * kPi * ri * (L - td - rf)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceOuter) / (2 * kPi * ro * (L - w)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceClamped) / (2 * kPi * rb * rb + 2 * kPi * rb * (hb - td)), 1.0, kAreaTol);
  EXPECT_GT(boundary_area(m, kSurfaceDiaphragm), 0.0);
  EXPECT_EQ(boundary_area(m, kSurfaceOther), 0.0);
  EXPECT_GT(m.quality.min_dihedral_deg, 3.0);
}

TEST(MeshFlexsplineExplicitTeeth, TetsArePositiveAndMidsideNodesSitAtTheirEdgeMidpoints) {
  const GearParams g = coarse_gear();
  const TetMesh m = mesh_flexspline(coarse_toothed_cup(g), g, coarse());
  double worst_move = 0.0;  // over the rim (the boss's 8-point rings near the axis have large sagittas)
  for (std::size_t i = 0; i < m.tets.size(); ++i) {
    const auto& t = m.tets[i];
    const Eigen::Vector3d a = m.nodes.row(t[0]), b = m.nodes.row(t[1]), c = m.nodes.row(t[2]), d = m.nodes.row(t[3]);
    ASSERT_GT((b - a).cross(c - a).dot(d - a), 0.0);
    for (int e = 0; e < 6 && m.region[i] == 1; ++e) {
      const Eigen::Vector3d mid = 0.5 * (m.nodes.row(t[kTetEdges[e][0]]) + m.nodes.row(t[kTetEdges[e][1]]));
      worst_move = std::max(worst_move, (Eigen::Vector3d(m.nodes.row(t[4 + e])) - mid).norm());
    }
  }
  EXPECT_LT(worst_move, kMidsideMoveTol);
  // Tooth flanks are planar quads of the outline's polyline: their midside nodes are exact midpoints.
  int flank_faces = 0;
  for (const auto& face : m.faces) {
    if (face.marker != kSurfaceRimOuter) continue;
    ++flank_faces;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d mid = 0.5 * (m.nodes.row(face.nodes[k]) + m.nodes.row(face.nodes[(k + 1) % 3]));
      EXPECT_LT((Eigen::Vector3d(m.nodes.row(face.nodes[3 + k])) - mid).norm(), 1e-12);
    }
  }
  EXPECT_GT(flank_faces, 0);
  EXPECT_GT(mesh_volume(m), 0.0);
}

TEST(MeshFlexsplineExplicitTeeth, RootCircleInsideTheBodyWallIsRejected) {
  FlexsplineParams f = seed_cup();  // root circle 19.0425 mm
  f.teeth = TeethModel::Explicit;
  f.wall_thickness_m = 0.65e-3;     // outer wall 19.05 mm: the teeth would undercut the body
  try {
    mesh_flexspline(f, GearParams{}, coarse());
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "flexspline.teeth = \"explicit\": the teeth's root circle 19.0425 mm (from [gear]) must lie outside "
                 "the body wall, inner_radius_mm + wall_thickness_mm = 19.05 mm; reduce wall_thickness_mm or "
                 "inner_radius_mm");
  }
  f = seed_cup();
  f.teeth = TeethModel::Explicit;
  f.rim_thickness_m = 0.8e-3;  // root circle 0.1575 mm inside the rim's outer radius: the teeth do not fit
  EXPECT_THROW(mesh_flexspline(f, GearParams{}, coarse()), InputError);
  EXPECT_THROW(mesh_flexspline(f, std::nullopt, coarse()), InputError);
}

// The size field toward the clamp corners: the edge length at the corners is the diaphragm's layer / 2^levels (an
// edge of the graded profile is at most that long where it starts at the corner; 1.5x allows for the split rounding
// up to whole sub-segments), the geometry is the uniform mesh's (the refinement only moves where nodes are), the node
// count is the estimate's (calibrated at 0.6 mm / 2 layers; 15 % here at 1 mm / 1 layer) and the tets stay usable.
TEST(MeshFlexsplineCornerRefinement, GradesTowardTheClampCornersWithinTheEstimate) {
  const FlexsplineParams f = seed_cup();
  const GearParams g;
  MeshParams mp = coarse();
  mp.corner_levels = 0;
  const TetMesh uniform = mesh_flexspline(f, g, mp);
  mp.corner_levels = 3;
  const double corner_edge = std::ldexp(wall_size(f.diaphragm_thickness_m, mp).across_m, -3);
  const ProfileSizeField field = corner_size_field(f, mp);
  ASSERT_EQ(field.points.size(), 2u);
  EXPECT_DOUBLE_EQ(field.size_m, corner_edge);
  EXPECT_DOUBLE_EQ(field.at(field.points[1], 1e-3), corner_edge);
  EXPECT_NEAR(field.at(field.points[1] + Eigen::Vector2d(0.1e-3, 0), 1e-3), corner_edge + kCornerGrowth * 0.1e-3, 1e-15);
  EXPECT_DOUBLE_EQ(field.at(field.points[1] + Eigen::Vector2d(5e-3, 0), 1e-3), 1e-3);  // never above the edge's size

  const TetMesh m = mesh_flexspline(f, g, mp);
  EXPECT_NEAR(mesh_volume(m) / mesh_volume(uniform), 1.0, 1e-4);
  // Shortest edge at each corner ring (nodes within a tenth of the corner edge of it, in (r, z)).
  for (const Eigen::Vector2d& corner : field.points) {
    auto rz = [&](int v) { return Eigen::Vector2d(std::hypot(m.nodes(v, 0), m.nodes(v, 1)), m.nodes(v, 2)); };
    double shortest = 1.0;
    for (const auto& t : m.tets)
      for (const auto& e : kTetEdges) {
        const int a = t[e[0]], b = t[e[1]];
        if ((rz(a) - corner).norm() < 0.1 * corner_edge || (rz(b) - corner).norm() < 0.1 * corner_edge)
          shortest = std::min(shortest, (m.nodes.row(a) - m.nodes.row(b)).norm());
      }
    EXPECT_LT(shortest, 1.5 * corner_edge);
    EXPECT_GT(shortest, 0.25 * corner_edge);
  }
  const double estimate = estimate_model_size(f, g, mp).nodes;
  std::printf("seed cup 1 mm / 1 layer: %zu nodes uniform, %zu at corner_levels 3 (estimate %.0f), min dihedral %.2f\n",
              uniform.n_nodes(), m.n_nodes(), estimate, m.quality.min_dihedral_deg);
  EXPECT_GT(m.n_nodes(), uniform.n_nodes());
  EXPECT_NEAR(static_cast<double>(m.n_nodes()) / estimate, 1.0, 0.15);
  EXPECT_GT(m.quality.min_dihedral_deg, 1.0);
}

TEST(MeshFlexsplineCornerRefinement, TooManyLevelsAreRejectedWithTheKey) {
  MeshParams mp = coarse();
  mp.corner_levels = kMaxCornerLevels + 1;
  try {
    mesh_flexspline(seed_cup(), GearParams{}, mp);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh.corner_levels = 9; must be in [-1, 8]"), std::string::npos) << e.what();
  }
}

// The seed case (module 0.2, 190 teeth, 0.6 mm wall) with explicit teeth at its default mesh: within the node budget
// the FEM's 60 s / 6 GB bench allows (~600k nodes), every tooth in the mesh, and the markers the FEM loads by.
TEST(MeshFlexsplineExplicitTeeth, SeedCupMeshesWithinTheNodeBudget) {
  FlexsplineParams f = seed_cup();
  f.teeth = TeethModel::Explicit;
  const GearParams g;
  const MeshParams mp;  // size 0.6 mm, 2 wall layers
  const TetMesh m = mesh_flexspline(f, g, mp);
  const double estimate = estimate_model_size(f, g, mp).nodes;
  std::printf("seed cup, explicit teeth: %zu nodes (estimate %.0f), %zu tets, min dihedral %.2f deg\n", m.n_nodes(),
              estimate, m.tets.size(), m.quality.min_dihedral_deg);
  EXPECT_LT(m.n_nodes(), 600000u);
  // The model-size estimate that refuses work before meshing counts the teeth at their own edge lengths.
  EXPECT_NEAR(static_cast<double>(m.n_nodes()) / estimate, 1.0, 0.25);
  EXPECT_GT(m.quality.min_dihedral_deg, 1.0);
  const double tooth_area = polygon_perimeter(flexspline_outline(g, 60)) * f.rim_width_m;
  EXPECT_NEAR(boundary_area(m, kSurfaceRimOuter) / tooth_area, 1.0, kFlankAreaTol);
  // Every tooth tip carries mesh nodes.
  const double tip = gear_radii(g).tip_f;
  std::vector<bool> tooth_seen(g.teeth_flexspline, false);
  for (Eigen::Index i = 0; i < m.nodes.rows(); ++i)
    if (std::hypot(m.nodes(i, 0), m.nodes(i, 1)) > tip - 1e-9) {
      const double th = std::atan2(m.nodes(i, 1), m.nodes(i, 0));
      tooth_seen[static_cast<int>(std::lround(th / (2 * kPi / g.teeth_flexspline)) + g.teeth_flexspline) %
                 g.teeth_flexspline] = true;
    }
  EXPECT_EQ(std::count(tooth_seen.begin(), tooth_seen.end(), true), g.teeth_flexspline);
}

}  // namespace
}  // namespace sw
