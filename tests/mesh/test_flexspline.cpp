// Flexspline meshes: volume and marked areas against the analytic revolved profile, regions, and every rejected
// inconsistent combination with its message.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "common/error.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/flexspline.hpp"
#include "mesh/tetgen_mesh.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;
// Quadratic faces on cylinders (>= 100 segments around) are exact to ~1e-8; the fillet torus is followed by
// quadratic faces over arc pieces of up to 45 degrees, whose interpolation error is O(dφ^4) ~ 1e-3 of the fillet's
// small share of the volume: 1e-4 relative overall, the accuracy the FEM needs from the geometry.
constexpr double kVolumeTol = 1e-4;
constexpr double kAreaTol = 1e-4;
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
  EXPECT_NEAR(region_volume(m, 0) / body, 1.0, kVolumeTol);
  EXPECT_NEAR(region_volume(m, 1) / rim, 1.0, kVolumeTol);
  EXPECT_NEAR(mesh_volume(m) / (boss + diaphragm + body + rim), 1.0, kVolumeTol);

  const double fillet_area = 2 * kPi * rf * ((ri - rf) * kPi / 2 + rf);
  EXPECT_NEAR(boundary_area(m, kSurfaceInner) / (2 * kPi * ri * (L - td - rf)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceOuter) / (2 * kPi * ro * (L - w)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceRimOuter) / (2 * kPi * rr * w), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceOpenEnd) / (kPi * (rr * rr - ri * ri)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceRimStep) / (kPi * (rr * rr - ro * ro)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceClamped) / (2 * kPi * rb * rb + 2 * kPi * rb * (hb - td)), 1.0, kAreaTol);
  EXPECT_NEAR(boundary_area(m, kSurfaceDiaphragm) /
                  (kPi * (ro * ro - rb * rb) + kPi * ((ri - rf) * (ri - rf) - rb * rb) + fillet_area),
              1.0, kAreaTol);
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
    validate_flexspline(f, GearParams{}, m);
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

}  // namespace
}  // namespace sw
