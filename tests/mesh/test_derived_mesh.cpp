// The mesh a case gets for the [mesh] keys it leaves out (derive_mesh, the rule documented at MeshParams): the rule's
// values and what each was derived from on a tube, a cup with ring teeth, a cup with explicit teeth and cups where
// the wall or the rim sets the size; every one within the memory a 24 GB machine gives (the estimate under 16 GB).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <string>

#include "common/error.hpp"
#include "mesh/estimate.hpp"
#include "mesh/flexspline.hpp"
#include "mesh/shapes.hpp"

namespace sw {
namespace {

// The estimate's bound for a derived mesh: a 24 GB machine less the system's share and the estimate's own margin
// (it errs on the safe side: 7.95 GB estimated for the seed cup's 298k-node mesh).
constexpr double kDerivedMeshBudgetBytes = 16e9;

// The seed cup (r_i 18.4, wall 0.6, rim 6 mm wide, diaphragm 1 mm) with its rim on the default gear's root circle.
FlexsplineParams ring_cup() {
  FlexsplineParams f;
  f.rim_thickness_m = 0.65e-3;
  return f;
}

struct Part {
  const char* name;
  FlexsplineParams f;
  double size_mm;            ///< the rule's size_mm
  const char* size_from;     ///< what it was derived from
  int corner_levels;         ///< the rule's corner_levels
};

Part tube() {
  Part p{"Tube", FlexsplineParams{}, 1.0, "flexspline.wall_thickness_mm = 1 (one layer through the body wall)", 0};
  p.f.shape = FlexsplineShape::Tube;
  p.f.teeth = TeethModel::None;
  p.f.inner_radius_m = 18.5e-3;
  p.f.wall_thickness_m = 1.0e-3;
  p.f.length_m = 30e-3;
  return p;  // 2π·18.5/160 = 0.73 mm around is finer than the wall: one layer keeps the wall's tets
}

Part cup(const char* name, TeethModel teeth) {
  Part p{name, ring_cup(), 2 * std::numbers::pi * 18.4 / kDerivedEdgesAround,
         "2 pi x flexspline.inner_radius_mm = 18.4 over 160 edges around", 0};
  p.f.teeth = teeth;
  p.corner_levels = kDerivedCornerLevels + 1;  // the 1 mm diaphragm in ceil(1 / 0.7226) = 2 layers
  return p;
}

Part thin_wall_cup() {
  // 2 x 0.3 mm along the wall is finer than 160 edges around ask for; the diaphragm in ceil(1 / 0.6) = 2 layers.
  Part p{"ThinWallCup", ring_cup(), 0.6, "2 x flexspline.wall_thickness_mm = 0.3", kDerivedCornerLevels + 1};
  p.f.wall_thickness_m = 0.3e-3;
  return p;
}

Part narrow_rim_cup() {
  Part p = thin_wall_cup();
  p.name = "NarrowRimCup";
  p.f.rim_width_m = 2e-3;  // 4 edges over 2 mm: 0.5 mm, within [0.3, 0.6]
  p.size_mm = 0.5;
  p.size_from = "flexspline.rim_width_mm = 2 over 4 edges";
  return p;
}

class DerivedMesh : public ::testing::TestWithParam<Part> {};

TEST_P(DerivedMesh, FollowsTheRuleSaysWhereFromAndFitsTheMachine) {
  const Part& p = GetParam();
  const std::optional<GearParams> gear =
      p.f.teeth == TeethModel::None ? std::nullopt : std::optional<GearParams>(GearParams{});
  const MeshParams m = derive_mesh(p.f, {});
  EXPECT_NEAR(m.size_m * 1e3, p.size_mm, 1e-9);
  EXPECT_EQ(m.size_from, p.size_from);
  EXPECT_EQ(m.wall_layers, 1);
  EXPECT_EQ(m.wall_layers_from, "the rule of one quadratic tet through each wall");
  EXPECT_EQ(m.corner_levels, p.corner_levels);
  EXPECT_EQ(corner_levels(p.f, m), p.corner_levels);  // both solvers read it here
  EXPECT_FALSE(m.corner_levels_from.empty());
  EXPECT_NO_THROW(validate_flexspline(p.f, m));
  EXPECT_NO_THROW(check_teeth_on_rim(p.f, gear));
  // One layer through the body wall, no longer along it than that layer allows.
  const WallSize w = wall_size(p.f.wall_thickness_m, m);
  EXPECT_EQ(w.layers, 1);
  EXPECT_NEAR(w.along_m, m.size_m, 1e-15);
  if (p.f.teeth == TeethModel::Explicit) EXPECT_LE(tooth_mesh_size(*gear, m).axial_m, m.size_m);
  const ModelSizeEstimate e = estimate_model_size(p.f, gear, m);
  std::printf("%s: size %.4f mm, %d layer, corner levels %d: %.3g nodes, %.3g GB estimated\n", p.name, m.size_m * 1e3,
              m.wall_layers, m.corner_levels, e.nodes, e.peak_bytes / 1e9);
  EXPECT_LT(e.peak_bytes, kDerivedMeshBudgetBytes);
  EXPECT_NO_THROW(refuse_if_too_large(e, kDerivedMeshBudgetBytes, p.name));
}

INSTANTIATE_TEST_SUITE_P(Parts, DerivedMesh,
                         ::testing::Values(tube(), cup("RingCup", TeethModel::Ring),
                                           cup("ExplicitCup", TeethModel::Explicit), thin_wall_cup(), narrow_rim_cup()),
                         [](const ::testing::TestParamInfo<Part>& i) { return std::string(i.param.name); });

// A key the case gives stays as given (nothing to say where it came from); the corner grading follows the given
// size and layers; -1 asks for the rule's grading.
TEST(DerivedMesh, KeysTheCaseGivesAreKeptAndTheGradingFollowsThem) {
  const FlexsplineParams f = ring_cup();
  MeshKeysGiven given;
  given.size_m = 0.25e-3;  // the 1 mm diaphragm in 4 layers: 3 + log2 4
  const MeshParams m = derive_mesh(f, given);
  EXPECT_DOUBLE_EQ(m.size_m, 0.25e-3);
  EXPECT_TRUE(m.size_from.empty());
  EXPECT_EQ(m.wall_layers, 1);
  EXPECT_EQ(m.corner_levels, kDerivedCornerLevels + 2);
  EXPECT_EQ(m.corner_levels_from, "3 + log2 of the diaphragm's 4 layers, rounded down");
  given.wall_layers = 3;
  given.corner_levels = 0;
  const MeshParams n = derive_mesh(f, given);
  EXPECT_EQ(n.wall_layers, 3);
  EXPECT_EQ(n.corner_levels, 0);
  EXPECT_TRUE(n.wall_layers_from.empty() && n.corner_levels_from.empty());
  given.corner_levels = -1;
  EXPECT_EQ(derive_mesh(f, given).corner_levels, kDerivedCornerLevels + 2);
}

// A derived value out of range comes from a flexspline key out of range: the flexspline's check reports that key
// first; the mesh's own check says what the value was derived from and which key sets it.
TEST(DerivedMesh, ADerivedValueOutOfRangeIsReportedAsTheKeyItCameFrom) {
  FlexsplineParams f = ring_cup();
  f.wall_thickness_m = -0.4e-3;
  const MeshParams m = derive_mesh(f, {});
  try {
    validate_flexspline(f, m);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "flexspline.wall_thickness_mm = -0.4; must be > 0");
  }
  try {
    validate_mesh(m);
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "mesh.size_mm = -0.8 (not in the file: derived from 2 x flexspline.wall_thickness_mm = "
                           "-0.4); must be > 0; write mesh.size_mm to set it");
  }
}

}  // namespace
}  // namespace sw
