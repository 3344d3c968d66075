// Case files: the values arrive in SI, and every kind of bad input is one clear line naming file, key and value.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <fstream>
#include <iterator>

#include "common/error.hpp"
#include "io/case.hpp"

namespace sw {
namespace {

std::string error_of(const std::string& toml) {
  try {
    parse_case(toml, "cases/x.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

constexpr const char* kTube = "[flexspline]\nshape = \"tube\"\ninner_radius_mm = 18.5\nwall_thickness_mm = 1.0\n"
                              "length_mm = 30\nteeth = \"none\"\n";

TEST(CaseFile, ConvertsMillimetresToMetresOnce) {
  const Case c = parse_case(kTube, "t.toml");
  EXPECT_DOUBLE_EQ(c.flexspline.inner_radius_m, 18.5e-3);
  EXPECT_DOUBLE_EQ(c.flexspline.wall_thickness_m, 1.0e-3);
  EXPECT_EQ(c.flexspline.shape, FlexsplineShape::Tube);
  EXPECT_FALSE(c.gear.has_value());
  EXPECT_FALSE(c.wave_generator.has_value());
}

// [mesh] keys the file leaves out are derived from the part (mesh/flexspline_params.hpp derive_mesh) and printed with
// what they were derived from; a key the file gives stays as given and the others are still derived.
TEST(CaseFile, MeshKeysLeftOutAreDerivedFromThePartAndSaySo) {
  const Case c = parse_case(kTube, "t.toml");
  EXPECT_DOUBLE_EQ(c.mesh.size_m, 1.0e-3);  // one layer through the 1 mm wall
  EXPECT_EQ(c.mesh.wall_layers, 1);
  EXPECT_EQ(c.mesh.corner_levels, 0);
  const std::string d = describe_case(c);
  EXPECT_NE(d.find("[mesh]\nsize_mm = 1  # derived: flexspline.wall_thickness_mm = 1 (one layer through the body "
                   "wall)\nwall_layers = 1  # derived: the rule of one quadratic tet through each wall\n"
                   "corner_levels = 0  # derived: the shape: a tube has no clamp corner\n"),
            std::string::npos)
      << d;
  const Case given = parse_case(std::string(kTube) + "[mesh]\nsize_mm = 2\n", "t.toml");
  EXPECT_DOUBLE_EQ(given.mesh.size_m, 2e-3);
  EXPECT_TRUE(given.mesh.size_from.empty());
  EXPECT_EQ(given.mesh.wall_layers, 1);
  EXPECT_NE(describe_case(given).find("size_mm = 2\nwall_layers = 1  # derived"), std::string::npos);
  EXPECT_EQ(error_of(std::string(kTube) + "[mesh]\nwall_layers = 0\n"),
            "cases/x.toml:8: mesh.wall_layers = 0; must be >= 1");
}

TEST(CaseFile, NegativeThicknessNamesFileKeyAndValue) {
  std::string t = kTube;
  t.replace(t.find("1.0"), 3, "-0.4");
  EXPECT_EQ(error_of(t), "cases/x.toml:4: flexspline.wall_thickness_mm = -0.4; must be > 0");
}

TEST(CaseFile, MalformedTomlGivesLineAndColumn) {
  const std::string e = error_of("[flexspline]\nshape = \"tube\nlength_mm = 3\n");
  EXPECT_NE(e.find("cases/x.toml:2:"), std::string::npos) << e;
  EXPECT_NE(e.find("malformed TOML"), std::string::npos) << e;
}

TEST(CaseFile, UnknownKeyIsRejectedWithItsPath) {
  const std::string e = error_of(std::string(kTube) + "wall_thicknes_mm = 2\n");
  EXPECT_NE(e.find("flexspline.wall_thicknes_mm = 2; unknown key"), std::string::npos) << e;
}

TEST(CaseFile, UnknownTableIsRejected) {
  EXPECT_NE(error_of(std::string(kTube) + "[solvers]\nx = 1\n").find("[solvers] is not a known table"),
            std::string::npos);
}

TEST(CaseFile, SolverTable) {
  const Case c = parse_case(std::string(kTube) + "[solver]\nmethod = \"fourier\"\nharmonics = 32\n", "t.toml");
  EXPECT_EQ(c.solver.method, SolverMethod::Fourier);
  EXPECT_EQ(c.solver.harmonics, 32);
  // "auto", the default: the harmonic solver for a body of revolution, TET10 for explicit teeth or the petsc backend.
  EXPECT_EQ(parse_case(kTube, "t.toml").solver.method, SolverMethod::Fourier);
  EXPECT_EQ(parse_case(std::string(kTube) + "[solver]\nbackend = \"petsc\"\n", "t.toml").solver.method,
            SolverMethod::Tet10);
  EXPECT_EQ(parse_case(std::string(kTube) + "[solver]\nmethod = \"tet10\"\n", "t.toml").solver.method,
            SolverMethod::Tet10);
  EXPECT_EQ(parse_case(std::string(kTube) + "[solver]\nmethod = \"auto\"\n", "t.toml").solver.method,
            SolverMethod::Fourier);
  EXPECT_NE(error_of(std::string(kTube) + "[solver]\nmethod = \"fft\"\n").find("solver.method = 'fft'; expected one of"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kTube) + "[solver]\nharmonics = -1\n")
                .find("solver.harmonics = -1; must be in [0, 4096]"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kTube) + "[solver]\nharmonic = 8\n").find("solver.harmonic = 8; unknown key"),
            std::string::npos);
}

// The tooth layer is the harmonic solver's: "auto" picks it, TET10 refuses it in one line, and it needs the gear.
TEST(CaseFile, ToothLayerIsTheHarmonicSolvers) {
  std::ifstream in("cases/seed_190_192.toml");
  ASSERT_TRUE(in) << "run from the project root";
  std::string seed((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  seed.replace(seed.find("teeth = \"ring\""), 14, "teeth = \"layer\"");
  const Case c = parse_case(seed, "cases/x.toml");
  EXPECT_EQ(c.flexspline.teeth, TeethModel::Layer);
  EXPECT_EQ(c.solver.method, SolverMethod::Fourier);
  EXPECT_EQ(error_of(seed + "[solver]\nmethod = \"tet10\"\n"),
            "cases/x.toml: solver.method = \"tet10\" meshes the teeth as solids or a ring; flexspline.teeth = "
            "\"layer\" is the harmonic solver's (use method = \"fourier\", or teeth = \"explicit\")");
  std::string tube = kTube;
  tube.replace(tube.find("teeth = \"none\""), 14, "teeth = \"layer\"\nrim_width_mm = 5\nrim_thickness_mm = 1.5");
  EXPECT_EQ(error_of(tube), "cases/x.toml: flexspline.teeth = \"layer\" needs a [gear] table (module and teeth), or "
                            "set teeth = \"none\"");
}

TEST(CaseFile, SolverBackend) {
  EXPECT_EQ(parse_case(kTube, "t.toml").solver.backend, SolverBackend::Cholmod);
  EXPECT_EQ(parse_case(std::string(kTube) + "[solver]\nbackend = \"petsc\"\n", "t.toml").solver.backend,
            SolverBackend::Petsc);
  EXPECT_NE(error_of(std::string(kTube) + "[solver]\nbackend = \"mumps\"\n")
                .find("solver.backend = 'mumps'; expected one of \"cholmod\", \"petsc\""),
            std::string::npos)
      << error_of(std::string(kTube) + "[solver]\nbackend = \"mumps\"\n");
  const std::string e = error_of(std::string(kTube) + "[solver]\nmethod = \"fourier\"\nbackend = \"petsc\"\n");
  EXPECT_EQ(e, "cases/x.toml: solver.backend = \"petsc\" solves the TET10 model; solver.method = \"fourier\" runs in "
               "one process (use method = \"tet10\", or backend = \"cholmod\")");
}

TEST(CaseFile, WrongTypeSaysWhatWasExpected) {
  std::string t = kTube;
  t.replace(t.find("30"), 2, "\"thirty\"");
  EXPECT_NE(error_of(t).find("flexspline.length_mm = 'thirty'; expected a number"), std::string::npos) << error_of(t);
}

TEST(CaseFile, TubeRejectsCupOnlyKeys) {
  EXPECT_NE(error_of(std::string(kTube) + "boss_radius_mm = 5\n").find("boss_radius_mm = 5; unknown key"),
            std::string::npos);
}

TEST(CaseFile, FlexsplineWithMoreTeethThanCircularSplineIsRejected) {
  const std::string e = error_of(std::string(kTube) + "[gear]\nteeth_flexspline = 28\nteeth_circular = 26\n");
  EXPECT_NE(e.find("gear.teeth_circular = 26; must be > gear.teeth_flexspline = 28"), std::string::npos) << e;
}

// The tip rounding arrives in metres; a negative one, or one of a module or more, is one line naming the key (one that
// does not fit the tooth is refused by the gear geometry, tests/kinematics).
TEST(CaseFile, TipRoundingIsReadInMillimetresAndChecked) {
  const Case c = parse_case(std::string(kTube) + "[gear]\ntip_rounding_flexspline_mm = 0.02\ntip_rounding_circular_mm = 0.03\n"
                                                 "[circular_spline]\nouter_radius_mm = 30\nwidth_mm = 5\n",
                            "cases/x.toml");
  EXPECT_NEAR(c.gear->tip_rounding_flexspline_m, 2e-5, 1e-18);
  EXPECT_NEAR(c.gear->tip_rounding_circular_m, 3e-5, 1e-18);
  const std::string e = error_of(std::string(kTube) + "[gear]\ntip_rounding_circular_mm = -0.01\n");
  EXPECT_NE(e.find("cases/x.toml:8: gear.tip_rounding_circular_mm = -0.01; must be >= 0"), std::string::npos) << e;
  const std::string big = error_of(std::string(kTube) + "[gear]\ntip_rounding_flexspline_mm = 0.2\n");
  EXPECT_NE(big.find("gear.tip_rounding_flexspline_mm = 0.2; must be in [0, module)"), std::string::npos) << big;
}

TEST(CaseFile, ContactFaceSlicesAreAnIntegerFromOneToSixteen) {
  EXPECT_EQ(parse_case(kTube, "cases/x.toml").contact.face_slices, 1);
  EXPECT_EQ(parse_case(std::string(kTube) + "[contact]\nface_slices = 3\n", "cases/x.toml").contact.face_slices, 3);
  const std::string zero = error_of(std::string(kTube) + "[contact]\nface_slices = 0\n");
  EXPECT_NE(zero.find("x.toml:8: contact.face_slices = 0; must be in [1, 16]"), std::string::npos) << zero;
  const std::string many = error_of(std::string(kTube) + "[contact]\nface_slices = 17\n");
  EXPECT_NE(many.find("contact.face_slices = 17; must be in [1, 16]"), std::string::npos) << many;
  const std::string other = error_of(std::string(kTube) + "[contact]\nslices = 3\n");
  EXPECT_NE(other.find("contact.slices"), std::string::npos) << other;
}

// Coulomb's μ on the flanks: 0 by default (frictionless), any value in [0, 1]; outside it one line naming the key's line.
TEST(CaseFile, ContactFrictionCoefficientIsANumberFromZeroToOne) {
  EXPECT_EQ(parse_case(kTube, "cases/x.toml").contact.friction_coefficient, 0.0);
  EXPECT_EQ(parse_case(std::string(kTube) + "[contact]\nfriction_coefficient = 0.05\n", "cases/x.toml")
                .contact.friction_coefficient, 0.05);
  const std::string negative = error_of(std::string(kTube) + "[contact]\nfriction_coefficient = -0.1\n");
  EXPECT_NE(negative.find("x.toml:8: contact.friction_coefficient = -0.1; must be in [0, 1]"), std::string::npos)
      << negative;
  EXPECT_EQ(negative.find('\n'), std::string::npos) << negative;
  const std::string above = error_of(std::string(kTube) + "[contact]\nfriction_coefficient = 1.5\n");
  EXPECT_NE(above.find("contact.friction_coefficient = 1.5; must be in [0, 1]"), std::string::npos) << above;
  const std::string text = error_of(std::string(kTube) + "[contact]\nfriction_coefficient = \"low\"\n");
  EXPECT_NE(text.find("contact.friction_coefficient"), std::string::npos) << text;
}

// Where the generator is locked: 0 by default (a tooth on the major axis), degrees in [0, 360), read as radians.
TEST(CaseFile, ContactGeneratorAngleIsDegreesFromZeroToAFullTurn) {
  EXPECT_EQ(parse_case(kTube, "cases/x.toml").contact.generator_angle_rad, 0.0);
  EXPECT_NEAR(parse_case(std::string(kTube) + "[contact]\ngenerator_angle_deg = 0.45\n", "cases/x.toml")
                  .contact.generator_angle_rad, 0.45 * 3.141592653589793 / 180, 1e-15);
  const std::string full = error_of(std::string(kTube) + "[contact]\ngenerator_angle_deg = 360\n");
  EXPECT_NE(full.find("x.toml:8: contact.generator_angle_deg = 360; must be in [0, 360)"), std::string::npos) << full;
  EXPECT_EQ(full.find('\n'), std::string::npos) << full;
  const std::string negative = error_of(std::string(kTube) + "[contact]\ngenerator_angle_deg = -1\n");
  EXPECT_NE(negative.find("contact.generator_angle_deg = -1; must be in [0, 360)"), std::string::npos) << negative;
}

TEST(CaseFile, TeethNeedAGearTable) {
  std::string t = kTube;
  t.replace(t.find("\"none\""), 6, "\"ring\"\nrim_width_mm = 5\nrim_thickness_mm = 1.2");
  EXPECT_NE(error_of(t).find("needs a [gear] table"), std::string::npos) << error_of(t);
}

TEST(CaseFile, MissingFileIsAClearError) {
  try {
    load_case("cases/does_not_exist.toml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "cases/does_not_exist.toml: cannot open the case file (does it exist?)");
  }
}

TEST(CaseFile, ForcesListIsReadWithDegreesAndWeights) {
  const Case c = parse_case(std::string(kTube) +
                                "[wave_generator]\nmodel = \"forces\"\nforce_N = 10\n"
                                "forces = [{angle_deg = 30, weight = 2.0}, {angle_deg = 210}]\n",
                            "f.toml");
  ASSERT_EQ(std::get<GivenForces>(c.wave_generator->model).forces.size(), 2u);
  EXPECT_NEAR(std::get<GivenForces>(c.wave_generator->model).forces[0].angle_rad, 30.0 * 3.14159265358979 / 180.0, 1e-12);
  EXPECT_DOUBLE_EQ(std::get<GivenForces>(c.wave_generator->model).forces[1].weight, 1.0);
}

TEST(CaseFile, CamProfileAndFitAreReadAndChecked) {
  const std::string cam = std::string(kTube) + "[wave_generator]\nmodel = \"cam\"\nradial_deformation_mm = 0.2\n";
  const Case c = parse_case(cam + "profile = \"ellipse\"\nfit_um = 5\n", "c.toml");
  EXPECT_EQ(std::get<Cam>(c.wave_generator->model).profile, CamProfile::Ellipse);
  EXPECT_DOUBLE_EQ(std::get<Cam>(c.wave_generator->model).clearance_m, 5e-6);
  EXPECT_EQ(std::get<Cam>(parse_case(cam, "c.toml").wave_generator->model).profile, CamProfile::Polar);  // the default
  EXPECT_NE(error_of(cam + "fit_um = 300\n").find("wave_generator.fit_um = 300; must be smaller"), std::string::npos);
  EXPECT_NE(error_of(cam + "profile = \"oval\"\n").find("wave_generator.profile"), std::string::npos);
  // A force model has no cam profile.
  EXPECT_NE(error_of(std::string(kTube) + "[wave_generator]\nfit_um = 5\n").find("fit_um"), std::string::npos);
}

// A listed cam: radius against angle over a half turn; w0 is the radius at 0° less the bore (18.5 mm here), a given
// radial_deformation_mm must match it; bad lists give one line naming the point.
TEST(CaseFile, CamProfileListIsReadAndChecked) {
  const std::string cam = std::string(kTube) + "[wave_generator]\nmodel = \"cam\"\nprofile = \"list\"\n";
  std::string points = "profile_points = [";
  for (int deg = 0; deg < 180; deg += 15)
    points += (deg ? ", " : "") + std::string("{angle_deg = ") + std::to_string(deg) + ", radius_mm = " +
              std::to_string(18.5 + 0.2 * std::cos(2 * deg * 3.14159265358979 / 180)) + "}";
  points += "]\n";
  const Case c = parse_case(cam + points, "c.toml");
  EXPECT_EQ(std::get<Cam>(c.wave_generator->model).profile, CamProfile::List);
  ASSERT_EQ(std::get<Cam>(c.wave_generator->model).points.size(), 12u);
  EXPECT_NEAR(std::get<Cam>(c.wave_generator->model).points[1].angle_rad, 15 * 3.14159265358979 / 180, 1e-12);
  EXPECT_NEAR(*c.wave_generator->radial_deformation_m, 0.2e-3, 1e-9);  // the listed point at 0° (to print precision)
  // What describe_case prints reads back to the same list.
  const std::string text = describe_case(c);
  ASSERT_NE(text.find("profile_points = ["), std::string::npos);
  EXPECT_NO_THROW(parse_case(cam + points + "radial_deformation_mm = 0.2\n", "c.toml"));
  EXPECT_NE(error_of(cam + points + "radial_deformation_mm = 0.25\n").find("must match the listed cam"),
            std::string::npos);
  EXPECT_NE(error_of(cam + "profile_points = [{angle_deg = 0, radius_mm = 18.7}]\n").find("fewer than 4 points"),
            std::string::npos);
  std::string backwards = points;
  backwards.replace(backwards.find("angle_deg = 15"), 14, "angle_deg = -5");
  EXPECT_NE(error_of(cam + backwards).find("profile_points[1].angle_deg = -5; must be in [0, 180)"), std::string::npos);
  std::string repeated = points;
  repeated.replace(repeated.find("angle_deg = 30"), 14, "angle_deg = 15");
  EXPECT_NE(error_of(cam + repeated).find("profile_points[2].angle_deg = 15; must be larger"), std::string::npos);
  EXPECT_NE(error_of(std::string(kTube) + "[wave_generator]\nmodel = \"cam\"\nradial_deformation_mm = 0.2\n" + points)
                .find("is for profile = \"list\" only"),
            std::string::npos);
}

TEST(CaseFile, FatigueDataComeInPairsBelowTheUltimateStrength) {
  const std::string mat = std::string(kTube) + "[material]\n";
  const Case c = parse_case(mat + "fatigue_limit_MPa = 500\nultimate_strength_MPa = 1100\n", "m.toml");
  EXPECT_DOUBLE_EQ(*c.material.fatigue_limit_Pa, 500e6);
  EXPECT_DOUBLE_EQ(*c.material.ultimate_strength_Pa, 1100e6);
  EXPECT_NE(error_of(mat + "fatigue_limit_MPa = 500\n").find("go together"), std::string::npos);
  EXPECT_NE(error_of(mat + "fatigue_limit_MPa = 1200\nultimate_strength_MPa = 1100\n")
                .find("material.fatigue_limit_MPa = 1200; must be < material.ultimate_strength_MPa = 1100"),
            std::string::npos);
}

TEST(CaseFile, TheYieldStrengthIsPositiveAndNotAboveTheUltimate) {
  const std::string mat = std::string(kTube) + "[material]\n";
  EXPECT_DOUBLE_EQ(*parse_case(mat + "yield_strength_MPa = 900\n", "m.toml").material.yield_strength_Pa, 900e6);
  EXPECT_NE(error_of(mat + "yield_strength_MPa = -5\n").find("material.yield_strength_MPa = -5; must be > 0"),
            std::string::npos);
  EXPECT_NE(error_of(mat + "fatigue_limit_MPa = 500\nultimate_strength_MPa = 1100\nyield_strength_MPa = 1200\n")
                .find("material.yield_strength_MPa = 1200; must be <= material.ultimate_strength_MPa = 1100"),
            std::string::npos);
}

// Found by bench/fuzz/fuzz_case: toml++ 3.3 reaches undefined behaviour (TOML_UNREACHABLE) when it tests some
// non-ASCII characters for whitespace; the case reader refuses them outside comments first.
TEST(CaseFile, NonAsciiOutsideCommentsIsRefusedWithLineAndColumn) {
  EXPECT_EQ(error_of("_r\xCD\x8D"),  // U+034D after a bare key: the input the fuzzer found
            "cases/x.toml:1:3: malformed TOML: non-ASCII character outside a comment; keys and values of a case are "
            "ASCII");
  // U+00A7 after a line-ending backslash in a multi-line string (upstream marzer/tomlplusplus#190).
  EXPECT_NE(error_of("s = \"\"\"\\\n\xC2\xA7\"\"\"\n").find("cases/x.toml:2:1: malformed TOML: non-ASCII"),
            std::string::npos);
  // U+FE7F in a literal string inside an array (the fuzzer's third input).
  EXPECT_NE(error_of("h= [0[['\xEF\xB9\xBF" "l\n.\n'").find("cases/x.toml:1:9: malformed TOML: non-ASCII"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kTube) + "length_mm = 30\xC2\xA0\n").find("cases/x.toml:7:15:"), std::string::npos);
  // A NUL inside a string, then U+01E0 after it (the fuzzer's second input): refused at the NUL.
  EXPECT_EQ(error_of(std::string("hap=[\"\0\0[\xC7\xA0\"]", 13)),
            "cases/x.toml:1:7: malformed TOML: control character 0x00; TOML allows only tab, CR and LF");
}

TEST(CaseFile, NonAsciiInCommentsIsKept) {
  // Comments with symbols, also after a string holding '#'; in a string value it is refused with its place.
  const Case c = parse_case("# r + w\xE2\x82\x80\xC2\xB7" "cos2\xCF\x86\n" + std::string(kTube) +
                                "[mesh]\n# \xC2\xB1 0.5 \xC2\xB5m\n",
                            "t.toml");
  EXPECT_EQ(c.flexspline.shape, FlexsplineShape::Tube);
  const std::string e = error_of(std::string(kTube) + "[wave_generator]\nprofile = \"#\" # \xCF\x86\n");
  EXPECT_NE(e.find("cases/x.toml:8: wave_generator.profile"), std::string::npos) << e;
  EXPECT_NE(error_of("[flexspline]\nshape = \"tu\xCF\x86" "be\"\n").find("cases/x.toml:2:12: malformed TOML: non-ASCII"),
            std::string::npos);
}

TEST(CaseFile, AnIntegerBeyondTheRangeOfIntIsRefusedNotWrapped) {
  // 4294967496 = 2^32 + 200 would wrap to 200 teeth in a 32-bit int.
  const std::string e = error_of(std::string(kTube) + "[gear]\nteeth_flexspline = 4294967496\nteeth_circular = 202\n");
  EXPECT_NE(e.find("gear.teeth_flexspline = 4294967496; must be <= 2147483647"), std::string::npos) << e;
}


// A cup with teeth (the seed's gear set), for the keys that need [gear].
constexpr const char* kCup = "[gear]\n[flexspline]\nshape = \"cup\"\nrim_thickness_mm = 0.6425\n";  // on the root circle

TEST(CaseFile, RatedTorqueFromTheCaseOrTheCatalogSize) {
  const Case own = parse_case(std::string(kTube) + "[load]\nrated_torque_Nm = 44.1\n", "t.toml");
  EXPECT_DOUBLE_EQ(*own.load.rated_torque_Nm, 44.1);
  EXPECT_FALSE(parse_case(kTube, "t.toml").load.rated_torque_Nm.has_value());
  const Case cat = parse_case(std::string(kTube) + "[catalog]\nsize = 17\n", "t.toml");
  EXPECT_EQ(*cat.catalog_size, 17);
  EXPECT_DOUBLE_EQ(*cat.load.rated_torque_Nm, 31.0);  // the catalog's rated torque when the case gives none
  EXPECT_NE(describe_case(cat).find("rated_torque_Nm = 31  # from catalog size 17"), std::string::npos)
      << describe_case(cat);
  EXPECT_NE(describe_case(cat).find("[catalog]\nsize = 17\n"), std::string::npos);
  // The case's own value wins over the catalog's.
  EXPECT_DOUBLE_EQ(*parse_case(std::string(kTube) + "[load]\nrated_torque_Nm = 20\n[catalog]\nsize = 17\n", "t.toml")
                        .load.rated_torque_Nm,
                   20.0);
  // Size 32 is listed without a rated torque: none is made up.
  EXPECT_FALSE(parse_case(std::string(kTube) + "[catalog]\nsize = 32\n", "t.toml").load.rated_torque_Nm.has_value());
  EXPECT_NE(error_of(std::string(kTube) + "[load]\nrated_torque_Nm = -3\n").find("load.rated_torque_Nm = -3; must be > 0"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kTube) + "[catalog]\nsize = 18\n")
                .find("catalog.size = 18; must be a listed catalog size (14, 17, 20, 25, 32)"),
            std::string::npos)
      << error_of(std::string(kTube) + "[catalog]\nsize = 18\n");
  EXPECT_NE(error_of(std::string(kTube) + "[catalog]\n").find("catalog.size is missing"), std::string::npos);
  EXPECT_NE(error_of(std::string(kTube) + "[catalog]\nsize = 17\nratio = 100\n").find("catalog.ratio = 100; unknown key"),
            std::string::npos);
}

TEST(CaseFile, GeneratorBearingIsReadCheckedAndPrinted) {
  const std::string wg = std::string(kTube) + "[wave_generator]\nmodel = \"cam\"\nradial_deformation_mm = 0.2\n";
  const Case c = parse_case(wg + "bearing = { balls = 23, ball_diameter_mm = 3.969, inner_groove_conformity = 0.515 }\n",
                            "b.toml");
  ASSERT_TRUE(c.wave_generator->bearing.has_value());
  const GeneratorBearing& b = *c.wave_generator->bearing;
  EXPECT_EQ(b.balls, 23);
  EXPECT_DOUBLE_EQ(b.ball_diameter_m, 3.969e-3);
  EXPECT_DOUBLE_EQ(b.inner_groove_conformity, 0.515);
  EXPECT_DOUBLE_EQ(b.outer_groove_conformity, 0.53);  // the default
  EXPECT_NEAR(b.pitch_radius_m, 18.5e-3 - 0.75 * 3.969e-3, 1e-15);  // from the bore (inner_radius_mm = 18.5)
  EXPECT_NE(describe_case(c).find("bearing = {balls = 23, ball_diameter_mm = 3.969, inner_groove_conformity = 0.515, "
                                  "outer_groove_conformity = 0.53}"),
            std::string::npos)
      << describe_case(c);
  EXPECT_FALSE(parse_case(wg, "b.toml").wave_generator->bearing.has_value());  // absent: a rigid generator
  EXPECT_NE(describe_case(parse_case(wg, "b.toml")).find("# no bearing: the generator is rigid"), std::string::npos);
  EXPECT_NE(error_of(wg + "bearing = { balls = 23 }\n").find("wave_generator.bearing.ball_diameter_mm is missing"),
            std::string::npos);
  EXPECT_NE(error_of(wg + "bearing = { ball_diameter_mm = 4 }\n").find("wave_generator.bearing.balls is missing"),
            std::string::npos);
  EXPECT_NE(error_of(wg + "bearing = { balls = 23, ball_diameter_mm = 3.969, outer_groove_conformity = 0.45 }\n")
                .find("cases/x.toml:10: wave_generator.bearing.outer_groove_conformity = 0.45; must be in (0.5, 1)"),
            std::string::npos)
      << error_of(wg + "bearing = { balls = 23, ball_diameter_mm = 3.969, outer_groove_conformity = 0.45 }\n");
  EXPECT_NE(error_of(wg + "bearing = { balls = 40, ball_diameter_mm = 3.969 }\n").find("wave_generator.bearing.balls = 40"),
            std::string::npos);
  EXPECT_NE(error_of(wg + "bearing = { balls = 23, ball_diameter_mm = -1 }\n")
                .find("wave_generator.bearing.ball_diameter_mm = -1; must be > 0"),
            std::string::npos);
  EXPECT_NE(error_of(wg + "bearing = { balls = 23, ball_diameter_mm = 3.969, width_mm = 7 }\n")
                .find("wave_generator.bearing.width_mm = 7; unknown key"),
            std::string::npos);
  EXPECT_NE(error_of(wg + "bearing = 3\n").find("wave_generator.bearing = 3; expected a table"), std::string::npos);
}

TEST(CaseFile, CircularSplineDefaultsToTheDesignRuleAndIsChecked) {
  const Case c = parse_case(kCup, "c.toml");
  ASSERT_TRUE(c.circular_spline.has_value());
  EXPECT_NEAR(c.circular_spline->outer_radius_m, 0.7 * 192 * 0.2e-3, 1e-15);  // 1.4 × the pitch diameter z_c·m
  EXPECT_DOUBLE_EQ(c.circular_spline->width_m, c.flexspline.rim_width_m);
  const Case given = parse_case(std::string(kCup) + "[circular_spline]\nouter_radius_mm = 30\nwidth_mm = 8\n", "c.toml");
  EXPECT_DOUBLE_EQ(given.circular_spline->outer_radius_m, 30e-3);
  EXPECT_DOUBLE_EQ(given.circular_spline->width_m, 8e-3);
  EXPECT_NE(describe_case(given).find("[circular_spline]\nouter_radius_mm = 30\nwidth_mm = 8\n"), std::string::npos);
  EXPECT_FALSE(parse_case(kTube, "t.toml").circular_spline.has_value());  // no teeth, no circular spline
  EXPECT_NE(error_of(std::string(kTube) + "[circular_spline]\nwidth_mm = 8\n").find("[circular_spline] needs a [gear]"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kCup) + "[circular_spline]\nouter_radius_mm = 15\n")
                .find("cases/x.toml:6: circular_spline.outer_radius_mm = 15; must be > the circular spline's root radius"),
            std::string::npos)
      << error_of(std::string(kCup) + "[circular_spline]\nouter_radius_mm = 15\n");
  EXPECT_NE(error_of(std::string(kCup) + "[circular_spline]\nwidth_mm = 0\n").find("circular_spline.width_mm = 0; must be > 0"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kCup) + "[circular_spline]\nbolts = 6\n").find("circular_spline.bolts = 6; unknown key"),
            std::string::npos);
}

// Every default derived from other keys, on the three kinds of flexspline: a tube without teeth that carries a [gear]
// (for the backlash), a cup with ring teeth, a cup with explicit teeth. Each loads (the derived values pass the
// stages' checks), each derived value is its rule's, and the case lists it with what it came from.
TEST(CaseFile, DerivedDefaultsOfATubeARingCupAndAnExplicitCup) {
  const std::string gear = "[gear]\n";  // 190/192 teeth, module 0.2 mm: the circular spline's pitch diameter 38.4 mm
  const Case tube = parse_case(gear + kTube, "t.toml");
  EXPECT_EQ(tube.flexspline.teeth, TeethModel::None);                                  // a tube's default teeth
  EXPECT_DOUBLE_EQ(tube.flexspline.rim_thickness_m, tube.flexspline.wall_thickness_m);  // no rim: the wall
  EXPECT_FALSE(tube.circular_spline.has_value());  // no toothed face to derive its width from; contact refuses it
  for (const auto& [key, from] : tube.derived_from)  // only the solver's own: "auto" and the harmonics
    EXPECT_TRUE(key == "solver.method" || key == "solver.harmonics") << key << ": " << from;
  EXPECT_EQ(tube.derived_from.at("solver.method"),
            "\"auto\": the flexspline is a body of revolution (teeth \"ring\", \"layer\" or \"none\")");
  for (const char* teeth : {"ring", "explicit"}) {
    const Case cup = parse_case(std::string(kCup) + "teeth = \"" + teeth + "\"\n", "c.toml");
    ASSERT_TRUE(cup.circular_spline.has_value()) << teeth;
    EXPECT_NEAR(cup.circular_spline->outer_radius_m, 0.7 * 192 * 0.2e-3, 1e-15) << teeth;
    EXPECT_DOUBLE_EQ(cup.circular_spline->width_m, cup.flexspline.rim_width_m) << teeth;
    EXPECT_EQ(cup.derived_from.at("circular_spline.outer_radius_mm"), "0.7 x the pitch diameter z_c m (design rule)");
    EXPECT_EQ(cup.derived_from.at("circular_spline.width_mm"), "flexspline.rim_width_mm = 6 (the toothed face width)");
    EXPECT_EQ(cup.solver.method, std::string(teeth) == "ring" ? SolverMethod::Fourier : SolverMethod::Tet10) << teeth;
    EXPECT_EQ(cup.solver.harmonics, std::max(64, 190 / 2));  // z_f/2 beyond the base's 64 (and the stations')
  }
  // The given keys are not derived.
  const Case given = parse_case(std::string(kCup) + "[circular_spline]\nwidth_mm = 8\n", "c.toml");
  EXPECT_EQ(given.derived_from.count("circular_spline.width_mm"), 0u);
  EXPECT_EQ(given.derived_from.count("circular_spline.outer_radius_mm"), 1u);
}

// A derived value out of range names what it was derived from and the key that sets it. Eight and ten teeth with a
// profile shift of 0.8 on the circular spline put its root circle (1.41 mm) just beyond the rule's outer radius 0.7·z_c·m (1.4 mm).
TEST(CaseFile, ADerivedValueOutOfRangeSaysWhereItCameFromAndWhichKeyToWrite) {
  const std::string gear = "[gear]\nmodule_mm = 0.2\nteeth_flexspline = 8\nteeth_circular = 10\ncutter_teeth = 8\n"
                           "profile_shift_flexspline = 0\nprofile_shift_circular = 0.8\n";
  const std::string e = error_of(gear + kTube + "[circular_spline]\nwidth_mm = 2\n");
  EXPECT_NE(e.find("cases/x.toml: circular_spline.outer_radius_mm = 1.4 (not in the file: derived from 0.7 x the pitch "
                   "diameter z_c m (design rule)); must be > the circular spline's root radius"),
            std::string::npos) << e;
  EXPECT_NE(e.find("; write circular_spline.outer_radius_mm to set it"), std::string::npos) << e;
}

// A stage's own range check (here the dynamics stage's) reaches the user as the reader's own messages do: file, the
// key's line, key, value, expectation.
TEST(CaseFile, StageRangesAreReportedWithTheKeysLine) {
  const std::string t = std::string(kTube) + "[dynamics]\nduration_s = 0.1\ndamping_Ns_per_m = -1\n";
  const std::string e = error_of(t);
  const auto lines = std::count(t.begin(), t.end(), '\n');  // the key is on the last line
  EXPECT_EQ(e, "cases/x.toml:" + std::to_string(lines) + ": dynamics.damping_Ns_per_m = -1; must be >= 0") << e;
}

// [lubricant]: the base oil's two viscosities and the temperature, kind defaulting to grease; it reads back from the
// resolved case; a key left out, a bad kind and viscosities in the wrong order are one line with file, line and key.
TEST(CaseFile, LubricantTable) {
  const std::string oil = std::string(kTube) +
                          "[lubricant]\nviscosity_40C_mm2_s = 68\nviscosity_100C_mm2_s = 8.6\ntemperature_C = 20\n";
  const Case c = parse_case(oil, "t.toml");
  ASSERT_TRUE(c.lubricant.has_value());
  EXPECT_EQ(c.lubricant->kind, "grease");
  EXPECT_DOUBLE_EQ(c.lubricant->viscosity_40C_mm2_s, 68.0);
  EXPECT_DOUBLE_EQ(c.lubricant->viscosity_100C_mm2_s, 8.6);
  EXPECT_DOUBLE_EQ(c.lubricant->temperature_C, 20.0);
  const Case back = parse_case(describe_case(c), "back.toml");
  ASSERT_TRUE(back.lubricant.has_value());
  EXPECT_EQ(back.lubricant->viscosity_100C_mm2_s, 8.6);
  EXPECT_FALSE(parse_case(kTube, "t.toml").lubricant.has_value());
  EXPECT_EQ(error_of(std::string(kTube) + "[lubricant]\nviscosity_40C_mm2_s = 68\ntemperature_C = 20\n"),
            "cases/x.toml: lubricant.viscosity_100C_mm2_s is missing; [lubricant] gives the base oil's kinematic "
            "viscosities at 40 and 100 C and the temperature it works at");
  EXPECT_NE(error_of(oil + "kind = \"butter\"\n").find("cases/x.toml:11: lubricant.kind = 'butter'; expected one of"),
            std::string::npos)
      << error_of(oil + "kind = \"butter\"\n");
  const std::string swapped = std::string(kTube) +
                              "[lubricant]\nviscosity_40C_mm2_s = 8\nviscosity_100C_mm2_s = 68\ntemperature_C = 20\n";
  EXPECT_EQ(error_of(swapped).rfind("cases/x.toml:8: lubricant.viscosity_40C_mm2_s = 8; must be > "
                                    "viscosity_100C_mm2_s = 68", 0), 0u) << error_of(swapped);
}

}  // namespace

}  // namespace sw
