// Catalog sizes and `strainwave design`'s proportions: the table is the reference's, and every written case loads,
// validates and has no interference at rest on the cam curve, for sizes 14..32 at ratios 50..160, from one rule set.
#include <algorithm>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "design/catalog.hpp"
#include "design/proportions.hpp"
#include "io/case.hpp"
#include "kinematics/backlash.hpp"
#include "kinematics/neutral_curve.hpp"
#include "mesh/estimate.hpp"
#include "mesh/flexspline.hpp"
#include "tests/input_error.hpp"

namespace sw {
namespace {

TEST(Catalog, HoldsTheReferenceRowsWithPitchDiameters) {
  ASSERT_EQ(catalog_drives().size(), 5u);
  const CatalogDrive* s17 = catalog_drive(17);
  ASSERT_NE(s17, nullptr);
  EXPECT_DOUBLE_EQ(s17->k2_Nm_per_rad, 1.4e4);
  EXPECT_DOUBLE_EQ(s17->rated_torque_Nm, 31.0);
  // The reference's check: size 17 at T2 = 12 N·m gives 3.9/1.0e4 + 8.1/1.4e4 = 9.69e-4 rad.
  EXPECT_NEAR(s17->t1_Nm / s17->k1_Nm_per_rad + (s17->t2_Nm - s17->t1_Nm) / s17->k2_Nm_per_rad, 9.69e-4, 0.005e-4);
  for (const auto& d : catalog_drives())  // the size number is the pitch diameter in tenths of an inch (0.1 mm)
    EXPECT_NEAR(d.pitch_diameter_m, d.size * 2.54e-3, 0.06e-3) << d.size;
  EXPECT_FALSE(catalog_drive(25)->has_stiffness());
  EXPECT_TRUE(catalog_drive(25)->has_rated_torque());
  EXPECT_FALSE(catalog_drive(32)->has_rated_torque());
  EXPECT_EQ(catalog_drive(18), nullptr);
  EXPECT_EQ(catalog_sizes_text(), "14, 17, 20, 25, 32");
}

// The case written for every size and ratio loads through the case reader, passes the flexspline validation (root
// circle on the rim) and the bearing's, and the basic geometry check on the cam curve finds the teeth set to zero
// backlash: no pair overlapping at rest and the tightest one touching (0.1 nm apart as designed, 0 to 1 nm read back:
// the case text's 9 digits move the geometry by about 1e-9 of 20 mm), with the tips passing at the minor axis. Same rule set for all:
// nothing here depends on the size.
TEST(Design, EveryWrittenCaseLoadsValidatesAndHasZeroBacklashAtRest) {
  for (const int size : {8, 14, 17, 20, 25, 32, 65}) {  // the accepted range's ends and the catalog sizes
    for (const int ratio : {30, 50, 80, 100, 120, 160}) {
      const CupDesign d = design_cup(size, ratio);
      const Case c = parse_case(design_case_toml(d), "design.toml");
      SCOPED_TRACE("size " + std::to_string(size) + " ratio " + std::to_string(ratio));
      ASSERT_TRUE(c.gear && c.wave_generator && c.wave_generator->bearing && c.circular_spline);
      EXPECT_NO_THROW(validate_flexspline(c.flexspline, c.mesh));
      EXPECT_NO_THROW(check_teeth_on_rim(c.flexspline, c.gear));
      EXPECT_EQ(c.gear->teeth_flexspline, 2 * ratio);
      EXPECT_EQ(c.gear->teeth_circular, 2 * ratio + 2);
      EXPECT_NEAR(c.gear->module_m * c.gear->teeth_flexspline / (size * 2.54e-3), 1.0, 1e-8);  // 9 digits in the text
      EXPECT_NEAR(*c.wave_generator->radial_deformation_m, c.gear->module_m, 1e-9);
      EXPECT_EQ(c.catalog_size.has_value(), catalog_drive(size) != nullptr);
      ASSERT_TRUE(c.load.rated_torque_Nm.has_value());
      if (catalog_drive(size) && catalog_drive(size)->has_rated_torque())
        EXPECT_DOUBLE_EQ(*c.load.rated_torque_Nm, catalog_drive(size)->rated_torque_Nm);
      const GeometryCheck g = check_geometry(
          *c.gear, cam_neutral_curve(rim_mean_radius(c.flexspline), *c.wave_generator->radial_deformation_m));
      EXPECT_FALSE(g.interference) << "worst clearance " << g.worst_clearance_m * 1e6 << " um";
      EXPECT_GE(g.worst_clearance_m, 0.0);
      EXPECT_LT(g.worst_clearance_m, 1e-9);
      EXPECT_LT(g.working_depth_m, g.two_w0_m);
      EXPECT_GT(g.minor_axis_tip_clearance_m, 0.0);
      if (size == 17)
        std::printf("[design] ratio %d: x_c - x_f = %.5f, the tightest pair at %.1f deg (%s), the major axis's dead "
                    "band %.3f arcmin, working depth %.3f m\n", ratio, d.zero_backlash.shift_difference,
                    d.zero_backlash.tightest_angle_deg, d.zero_backlash.tightest_parts.c_str(),
                    d.zero_backlash.major_axis_play_rad * 10800 / 3.141592653589793,
                    g.working_depth_m / c.gear->module_m);
    }
  }
}

// Zero backlash is the smallest shift that keeps the pairs apart: 1e-5 less and the tightest pair overlaps. (The
// clearance moves by about 1e-4 m per unit of x_c on size 17 (m·sin α = 7.4e-5 m on a flank), so 1e-5 less is about
// 1 nm of overlap, where 1e-6 less can stay inside the 0.1 nm left.) On any curve: here the ring under the seed
// paper's four forces, w0 the cam's.
TEST(Design, ZeroBacklashIsTheSmallestShiftWithoutOverlap) {
  CupDesign d = design_cup(17, 100);
  const double r_m = rim_mean_radius(d.flexspline), w0 = *d.wave_generator.radial_deformation_m;
  WaveGeneratorParams ring = d.wave_generator;
  ring.model = FourForce{};
  const NeutralCurve curve = generator_neutral_curve(r_m, w0, ring);
  set_zero_backlash(d, {curve});
  EXPECT_EQ(d.zero_backlash.curve, curve.source);
  EXPECT_NEAR(d.gear.profile_shift_circular - d.gear.profile_shift_flexspline, d.zero_backlash.shift_difference, 1e-15);
  const TightestPair at = tightest_pair_at_rest(make_backlash_model(d.gear, curve));
  EXPECT_GE(at.clearance_m, 1e-10);  // left 0.1 nm apart, so that the case text's 9 digits keep them apart
  EXPECT_LT(at.clearance_m, 1e-10 + 1e-11);  // the bisection's 1e-8 on the shift, rounded up: 1e-8·m·sin α = 7e-13 m
  GearParams tighter = d.gear;
  tighter.profile_shift_circular -= 1e-5;
  EXPECT_LT(tightest_pair_at_rest(make_backlash_model(tighter, curve)).clearance_m, 0.0);
  EXPECT_GT(d.zero_backlash.major_axis_play_rad, 0.0);  // involute flanks: not every pair tight at once
}

// Straight teeth on several sections of the face (the cup's coning: each its own deflection): the shift that keeps
// every section clear is the largest of those each section alone needs (to the bisection's 1e-8), the tightest pair
// sits on that section, and the dead band is the middle curve's. Here three cam curves, w0 ± 15 % about the design's.
TEST(Design, ZeroBacklashOnSectionsIsTheLargestOfTheirShifts) {
  CupDesign d = design_cup(17, 100);
  const double r_m = rim_mean_radius(d.flexspline), w0 = *d.wave_generator.radial_deformation_m;
  const std::vector<NeutralCurve> sections = {cam_neutral_curve(r_m, 0.85 * w0), cam_neutral_curve(r_m, w0),
                                              cam_neutral_curve(r_m, 1.15 * w0)};
  std::vector<double> alone;
  std::vector<double> play;
  for (const NeutralCurve& s : sections) {
    CupDesign one = d;
    set_zero_backlash(one, {s});
    alone.push_back(one.zero_backlash.shift_difference);
    play.push_back(one.zero_backlash.major_axis_play_rad);
  }
  set_zero_backlash(d, sections, "three cams");
  const auto largest = std::max_element(alone.begin(), alone.end());
  std::printf("shifts alone %.8f / %.8f / %.8f, together %.8f\n", alone[0], alone[1], alone[2],
              d.zero_backlash.shift_difference);
  EXPECT_NEAR(d.zero_backlash.shift_difference, *largest, 1.01e-8);
  EXPECT_EQ(d.zero_backlash.tightest_section, sections[static_cast<std::size_t>(largest - alone.begin())].source);
  EXPECT_EQ(d.zero_backlash.curve, "three cams");
  // The sections are not all tight at one shift (else the check above says nothing), and the others keep clearance.
  EXPECT_GT(*largest - *std::min_element(alone.begin(), alone.end()), 1e-3);
  for (const NeutralCurve& s : sections)
    EXPECT_GE(tightest_pair_at_rest(make_backlash_model(d.gear, s)).clearance_m, 1e-10);
  // The middle curve's dead band, with the larger shift than its own: wider than its own.
  EXPECT_GE(d.zero_backlash.major_axis_play_rad, play[1]);
  EXPECT_THROW(set_zero_backlash(d, {}), std::invalid_argument);
}

// A curve on which no shift takes the teeth from overlap to clearance (no bulge: nothing engages) is refused in one
// line naming the size, the ratio and the curve.
TEST(Design, ZeroBacklashWithoutEngagementIsRefused) {
  CupDesign d = design_cup(17, 100);
  const NeutralCurve flat = cam_neutral_curve(rim_mean_radius(d.flexspline), 1e-9);
  const std::string what = sw::testing::message_of([&] { set_zero_backlash(d, {flat}); });
  EXPECT_EQ(what.rfind("size 17, ratio 100: no profile shift difference x_c - x_f in [-0.2, 0.3]", 0), 0u) << what;
  EXPECT_NE(what.find(flat.source), std::string::npos) << what;
}

TEST(Design, RatedTorqueOfAnUnlistedSizeScalesWithTheCubeOfTheDiameter) {
  const CupDesign d32 = design_cup(32, 100), d40 = design_cup(40, 100);
  // Size 32 has no rated torque in the reference: from size 25's 87 N·m by (32/25)³.
  EXPECT_NEAR(d32.rated_torque_Nm, 87.0 * std::pow(32.0 / 25.0, 3), 1e-9);
  EXPECT_NEAR(d40.rated_torque_Nm, 87.0 * std::pow(40.0 / 25.0, 3), 1e-9);
  EXPECT_NE(d32.rated_torque_from.find("ISO 6336"), std::string::npos);
}

TEST(Design, ProportionsScaleWithThePitchDiameter) {
  const CupDesign a = design_cup(14, 100), b = design_cup(28, 100);
  EXPECT_NEAR(b.flexspline.inner_radius_m / a.flexspline.inner_radius_m, 2.0, 1e-12);
  EXPECT_NEAR(b.flexspline.length_m / a.flexspline.length_m, 2.0, 1e-12);
  EXPECT_NEAR(b.flexspline.wall_thickness_m / a.flexspline.wall_thickness_m, 2.0, 1e-12);
  // The written case has no [mesh]: the mesh derived from the part scales with it, corner grading included.
  const Case ca = parse_case(design_case_toml(a), "a.toml"), cb = parse_case(design_case_toml(b), "b.toml");
  EXPECT_NEAR(cb.mesh.size_m / ca.mesh.size_m, 2.0, 1e-8);  // 9 digits in the text
  EXPECT_EQ(cb.mesh.wall_layers, ca.mesh.wall_layers);
  EXPECT_EQ(cb.mesh.corner_levels, ca.mesh.corner_levels);
}

// A hand-written cup of catalog size 25 or 40 with no [mesh] (the design's proportions; `design` writes no [mesh]
// either): the mesh derived from the part fits a 24 GB machine, estimated under 16 GB and not refused. The fixed
// default it replaced (0.6 mm, 2 layers) needed 2.5e6 equations and 34 GB at size 25.
TEST(Design, HandWrittenCupsOfSize25And40WithoutAMeshTableFitTheMachine) {
  constexpr double kBudgetBytes = 16e9;
  for (const int size : {25, 40}) {
    const std::string text = design_case_toml(design_cup(size, 100));
    ASSERT_EQ(text.find("\n[mesh]"), std::string::npos);
    const Case c = parse_case(text, "size" + std::to_string(size) + ".toml");
    EXPECT_FALSE(c.mesh.size_from.empty());
    const ModelSizeEstimate e = estimate_model_size(c.flexspline, c.gear, c.mesh);
    std::printf("size %d: mesh %.4g mm, %d layer, corner levels %d: %.3g equations, %.3g GB estimated\n", size,
                c.mesh.size_m * 1e3, c.mesh.wall_layers, c.mesh.corner_levels, e.equations, e.peak_bytes / 1e9);
    EXPECT_LT(e.peak_bytes, kBudgetBytes) << size;
    EXPECT_NO_THROW(refuse_if_too_large(e, kBudgetBytes, c.path)) << size;
  }
}

// Ivanov's three ranges (rim 0.01–0.015 d, wall 0.6–0.9 rim, face 0.15–0.2 d) are the design's to choose within:
// each sets its length exactly, the rules that follow from them follow (the diaphragm from the rim, the fillet from
// the wall, the generator's band and place from the face), the rest of the drive does not move, and the written case
// says which options made it, so that it can be made again.
TEST(Design, ProportionsWithinIvanovsRangesSetTheirLengthsAndWhatFollowsFromThem) {
  const CupDesign n = design_cup(17, 100);
  const CupDesign t = design_cup(17, 100, {.rim_per_d = 0.01, .wall_per_rim = 0.6, .face_per_d = 0.2});
  const double d = t.pitch_diameter_m;
  EXPECT_DOUBLE_EQ(t.flexspline.rim_thickness_m, 0.01 * d);
  EXPECT_DOUBLE_EQ(t.flexspline.wall_thickness_m, 0.6 * 0.01 * d);
  EXPECT_DOUBLE_EQ(t.flexspline.rim_width_m, 0.2 * d);
  EXPECT_DOUBLE_EQ(t.flexspline.diaphragm_thickness_m / t.flexspline.rim_thickness_m,
                   n.flexspline.diaphragm_thickness_m / n.flexspline.rim_thickness_m);
  EXPECT_DOUBLE_EQ(t.flexspline.fillet_radius_m / t.flexspline.wall_thickness_m,
                   n.flexspline.fillet_radius_m / n.flexspline.wall_thickness_m);
  EXPECT_DOUBLE_EQ(t.wave_generator.band_width_m / t.flexspline.rim_width_m,
                   n.wave_generator.band_width_m / n.flexspline.rim_width_m);
  EXPECT_DOUBLE_EQ(t.wave_generator.axial_position_m / t.flexspline.rim_width_m,
                   n.wave_generator.axial_position_m / n.flexspline.rim_width_m);
  // The root circle is the rim's outside whatever its thickness; the teeth, the cup's length and boss do not move.
  EXPECT_DOUBLE_EQ(t.flexspline.inner_radius_m + t.flexspline.rim_thickness_m,
                   n.flexspline.inner_radius_m + n.flexspline.rim_thickness_m);
  EXPECT_EQ(t.gear.teeth_flexspline, n.gear.teeth_flexspline);
  EXPECT_DOUBLE_EQ(t.flexspline.length_m, n.flexspline.length_m);
  EXPECT_DOUBLE_EQ(t.flexspline.boss_radius_m, n.flexspline.boss_radius_m);
  const std::string text = design_case_toml(t);
  EXPECT_NE(text.find("`strainwave design --size 17 --ratio 100 --rim-per-d 0.01 --wall-per-rim 0.6 --face-per-d 0.2`"),
            std::string::npos) << text.substr(0, 200);
  EXPECT_NE(text.find("rim under the teeth 0.01 d, body wall 0.6 x rim, toothed face width 0.2 d"), std::string::npos);
  const Case c = parse_case(text, "thin.toml");
  EXPECT_NEAR(c.flexspline.rim_thickness_m, 0.01 * d, 1e-9 * d);  // 9 digits in the text
  // The defaults name no option: the shipped cases stay `design --size N`'s output.
  EXPECT_EQ(design_proportion_options({}), "");
  EXPECT_NE(design_case_toml(n).find("`strainwave design --size 17 --ratio 100`"), std::string::npos);
}

// Rounded tip corners only take material off the teeth, so the zero-backlash cut with them needs no larger a shift
// than the sharp one; where the sharp cut is decided by a tip corner it needs a smaller one. Here the designed size 17
// on three cam sections about the design's deflection (the coning), sharp against rounded by 0.05 m; the written case
// carries the rounding and its option, and loads with it.
TEST(Design, RoundedTipsAreCutWithNoLargerShiftAndTheCaseCarriesThem) {
  CupDesign sharp = design_cup(17, 100);
  const double r_m = rim_mean_radius(sharp.flexspline), w0 = *sharp.wave_generator.radial_deformation_m;
  const std::vector<NeutralCurve> sections = {cam_neutral_curve(r_m, 0.85 * w0), cam_neutral_curve(r_m, w0),
                                              cam_neutral_curve(r_m, 1.15 * w0)};
  CupDesign rounded = sharp;
  round_tips(rounded, 0.05);
  EXPECT_DOUBLE_EQ(rounded.gear.tip_rounding_flexspline_m, 0.05 * rounded.gear.module_m);
  EXPECT_DOUBLE_EQ(rounded.gear.tip_rounding_circular_m, 0.05 * rounded.gear.module_m);
  set_zero_backlash(sharp, sections, "three cams");
  set_zero_backlash(rounded, sections, "three cams");
  std::printf("sharp: x_c - x_f %.8f, tightest at %.1f deg (%s); rounded 0.05 m: %.8f at %.1f deg (%s)\n",
              sharp.zero_backlash.shift_difference, sharp.zero_backlash.tightest_angle_deg,
              sharp.zero_backlash.tightest_parts.c_str(), rounded.zero_backlash.shift_difference,
              rounded.zero_backlash.tightest_angle_deg, rounded.zero_backlash.tightest_parts.c_str());
  EXPECT_LE(rounded.zero_backlash.shift_difference, sharp.zero_backlash.shift_difference + 1.01e-8);
  if (sharp.zero_backlash.tightest_parts.find("tip corner") != std::string::npos)
    EXPECT_LT(rounded.zero_backlash.shift_difference, sharp.zero_backlash.shift_difference - 1e-6);
  for (const NeutralCurve& s : sections)
    EXPECT_GE(tightest_pair_at_rest(make_backlash_model(rounded.gear, s)).clearance_m, 1e-10);

  const std::string text = design_case_toml(rounded);
  EXPECT_NE(text.find("--ratio 100 --tip-rounding-per-m 0.05`"), std::string::npos);
  const Case c = parse_case(text, "rounded.toml");
  ASSERT_TRUE(c.gear.has_value());
  EXPECT_NEAR(c.gear->tip_rounding_flexspline_m, rounded.gear.tip_rounding_flexspline_m, 1e-12);
  EXPECT_NEAR(c.gear->tip_rounding_circular_m, rounded.gear.tip_rounding_circular_m, 1e-12);
  EXPECT_EQ(design_case_toml(sharp).find("tip_rounding_"), std::string::npos);  // sharp: the keys' default, not written
}

// A rounding that is negative, not a number, or whose arc does not fit on both teeth is one line naming the option.
TEST(Design, ATipRoundingThatDoesNotFitIsOneClearLine) {
  const CupDesign designed = design_cup(17, 100);
  for (const auto& [value, expected] : std::vector<std::pair<double, std::string>>{
           {-0.01, "--tip-rounding-per-m -0.01; must be in [0, 1)"},
           {std::nan(""), "--tip-rounding-per-m nan; must be in [0, 1)"},
           {0.9, "--tip-rounding-per-m 0.9 (0.19431 mm); the rounding must end on both teeth's flanks"}}) {
    CupDesign d = designed;
    const GearParams before = d.gear;
    const std::string what = sw::testing::message_of([&] { round_tips(d, value); });
    EXPECT_EQ(what.rfind(expected, 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_EQ(d.gear.tip_rounding_flexspline_m, before.tip_rounding_flexspline_m);  // nothing half done
    EXPECT_EQ(d.tip_rounding_per_module, 0.0);
  }
}

TEST(Design, AProportionOutsideIvanovsRangeIsOneClearLine) {
  auto error_of = [](const DesignProportions& p) {
    try {
      design_cup(17, 100, p);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of({.rim_per_d = 0.0099}).rfind("--rim-per-d 0.0099; must be in [0.01, 0.015] (Ivanov's rim", 0), 0u)
      << error_of({.rim_per_d = 0.0099});
  EXPECT_EQ(error_of({.rim_per_d = 0.016}).rfind("--rim-per-d 0.016; must be in [0.01, 0.015]", 0), 0u);
  EXPECT_EQ(error_of({.wall_per_rim = 0.95}).rfind("--wall-per-rim 0.95; must be in [0.6, 0.9] (Ivanov's body wall", 0),
            0u);
  EXPECT_EQ(error_of({.face_per_d = 0.1}).rfind("--face-per-d 0.1; must be in [0.15, 0.2] (Ivanov's toothed face", 0),
            0u);
  EXPECT_EQ(error_of({.face_per_d = std::nan("")}).rfind("--face-per-d nan; must be in [0.15, 0.2]", 0), 0u)
      << error_of({.face_per_d = std::nan("")});
  // The ranges' own ends are the source's and are taken.
  EXPECT_EQ(error_of({.rim_per_d = 0.015, .wall_per_rim = 0.9, .face_per_d = 0.15}), "no error");
}

TEST(Design, BadSizeOrRatioIsOneClearLine) {
  auto error_of = [](int size, int ratio) {
    try {
      design_cup(size, ratio);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of(7, 100).rfind("--size 7; must be an integer in [8, 65]", 0), 0u) << error_of(7, 100);
  EXPECT_EQ(error_of(17, 29).rfind("--ratio 29; must be an integer in [30, 160]", 0), 0u) << error_of(17, 29);
  EXPECT_EQ(error_of(17, 161).rfind("--ratio 161;", 0), 0u);
}

}  // namespace
}  // namespace sw
