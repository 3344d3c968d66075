#pragma once
// A cup-type strain wave gear for a catalog size from one set of proportions: every length is a fixed multiple of the
// pitch diameter d = size × 2.54 mm (or of the module m = d/z_f), the tooth numbers follow from the ratio, and nothing
// is tuned per size. Each rule and where it comes from is in proportions.cpp beside the rule and in the header
// comment of the written case. Since all lengths scale with d, the drive of one ratio is the same shape at every size;
// the teeth's geometry in modules depends on the ratio alone.
#include <string>
#include <vector>

#include "common/material.hpp"
#include "contact/circular_spline.hpp"
#include "gear/gear.hpp"
#include "generator/wave_generator.hpp"
#include "kinematics/neutral_curve.hpp"
#include "mesh/flexspline_params.hpp"

namespace sw {

/// Sizes and ratios `strainwave design` accepts: the component sets' sizes 8–65 and the catalog ratios 30–160
/// (z_f = 2·ratio; the short-tooth rule is verified against interference over this range of ratios).
inline constexpr int kDesignSizeMin = 8, kDesignSizeMax = 65;
inline constexpr int kDesignRatioMin = 30, kDesignRatioMax = 160;

/// How the teeth were set to zero backlash (set_zero_backlash): the circular spline's profile shift that leaves the
/// tightest engaged pair touching at rest, and what the involute flanks leave elsewhere.
struct ZeroBacklash {
  std::string curve;               ///< the rim's neutral curves it was solved on ("cam w0·cos2φ ...", "FEM ...")
  std::string tightest_section;    ///< the curve (a section of the face) on which the tightest pair sits
  double shift_difference = 0;     ///< x_c − x_f
  double tightest_clearance_m = 0; ///< the tightest pair's clearance at rest: 0.1 nm, so that the case text keeps it ≥ 0
  double tightest_angle_deg = 0;   ///< where that pair is: its material angle's distance from the major axis, 0..90°
  std::string tightest_parts;      ///< "tip corner / tip corner": where the two outlines touch there
  /// The output's dead band at the major-axis pair (closing angles of both flanks) on the middle curve of those given
  /// (the face's centre when they are its sections).
  double major_axis_play_rad = 0;
};

/// The design's teeth are straight across the face, as shaped or hobbed (no relief along it), so the cup's coning
/// gives every section of the face its own clearance: the loaded contact meshes them in this many sections, the
/// face's two ends and its centre (contact/contact_body.hpp face_slice), and the teeth are set to zero backlash on
/// all of them (the design's [contact] face_slices).
inline constexpr int kDesignFaceSections = 3;

/// The three proportions Ivanov gives as ranges (M. N. Ivanov, Volnovye zubchatye peredachi, 1981, the steel
/// flexspline's recommendations): the design takes one point of each range, by default the one `design` has always
/// used. Every other rule follows from these (the diaphragm from the rim, the fillet from the wall, the generator's
/// band and axial place from the face). A designer picks within the ranges; outside them the rules are not the
/// source's and `validate_design_proportions` refuses them.
struct DesignProportions {
  double rim_per_d = 0.014;    ///< rim under the teeth over the pitch diameter, in [0.01, 0.015]
  double wall_per_rim = 0.7;   ///< body wall over the rim, in [0.6, 0.9]
  double face_per_d = 0.15;    ///< toothed face width over the pitch diameter, in [0.15, 0.2]
  bool operator==(const DesignProportions&) const = default;
};

/// One of the three proportions: the command line option that sets it, its member, Ivanov's range and what it is.
struct DesignProportion {
  const char* option;                  ///< "--rim-per-d"
  double DesignProportions::*member;   ///< &DesignProportions::rim_per_d
  double min, max;                     ///< Ivanov's range, closed
  const char* meaning;                 ///< "rim under the teeth over the pitch diameter"
};

/// The three proportions, in the order `design` lists them: the one table validation, the command line and the
/// written case's header read.
inline constexpr DesignProportion kDesignProportions[] = {
    {"--rim-per-d", &DesignProportions::rim_per_d, 0.01, 0.015, "rim under the teeth over the pitch diameter"},
    {"--wall-per-rim", &DesignProportions::wall_per_rim, 0.6, 0.9, "body wall over the rim"},
    {"--face-per-d", &DesignProportions::face_per_d, 0.15, 0.2, "toothed face width over the pitch diameter"},
};

/// Checks each proportion against its range. Throws InputError "--rim-per-d 0.02; must be in [0.01, 0.015]
/// (Ivanov's rim under the teeth over the pitch diameter)", naming the command line option that sets it.
void validate_design_proportions(const DesignProportions& p);

/// The options that set `p` where it differs from the defaults ("" for the defaults): " --rim-per-d 0.01 ...".
std::string design_proportion_options(const DesignProportions& p);

/// Everything the written case holds (SI), with where the rated torque came from.
struct CupDesign {
  int size = 0;
  int ratio = 0;
  DesignProportions proportions;
  double pitch_diameter_m = 0;  ///< z_f·m = size × 2.54 mm
  GearParams gear;
  FlexsplineParams flexspline;
  Material material;
  WaveGeneratorParams wave_generator;  ///< cam, w0 = m, with its bearing
  CircularSplineParams circular_spline;
  double rated_torque_Nm = 0;
  std::string rated_torque_from;  ///< "catalog size 17 (CSG, ratio 100)" or the scaling used
  ZeroBacklash zero_backlash;     ///< on the cam's curve from design_cup; on the FEM's when `design` has solved it
  double tip_rounding_per_module = 0;  ///< both gears' tip corners rounded by this × m (round_tips); 0: sharp
};

/// The design of a size (kDesignSizeMin..kDesignSizeMax) and ratio (kDesignRatioMin..kDesignRatioMax) with the
/// proportions `p`. Throws InputError "--size 7; must be an integer in [8, 65] ..." for a size or ratio outside them,
/// and validate_design_proportions' for a proportion outside its range.
CupDesign design_cup(int size, int ratio, const DesignProportions& p = {});

/// Rounds both gears' tip corners by ρ = per_module·m (gear.tip_rounding_*): the designer's choice, since no
/// standard this tool cites gives an edge rounding for such teeth; `design` leaves them sharp, as generated, unless
/// asked (--tip-rounding-per-m). Rounded corners change which pairs are tightest (on the designed size 17 at ratio 100
/// the sharp tip corners at ±52.6° decide the cut; rounded by 0.05 m the tightest pair is at the major axis and the
/// play at the locked generator closes: contact/README.md), so it comes before set_zero_backlash. Throws InputError
/// "--tip-rounding-per-m 0.9 (0.1943 mm); ..." for a negative value or one whose arc does not fit on both teeth.
void round_tips(CupDesign& d, double per_module);

/// Sets the circular spline's profile shift x_c for zero backlash on the rim's neutral curves `sections` (rigid teeth;
/// the sections of the face the contact meshes, each with the rim as the generator leaves it there): the smallest
/// x_c − x_f (bisection to 1e-8, rounded up) at which no engaged pair on any of them comes within 0.1 nm at rest, so
/// that the tightest pair touches and the output has no free turn there, and no section of a straight tooth
/// interferes (the largest of the shifts each section alone would need). Makers cut harmonic drive teeth without
/// backlash; with involute flanks and the cup's coning the pairs are not all tight at once, which
/// major_axis_play_rad states. `what` names the curves in the written case (empty: the first one's source). Throws
/// InputError when no x_c − x_f in [−0.2, 0.3] brackets it (the teeth interfere whatever the shift), and
/// std::invalid_argument for no curve.
void set_zero_backlash(CupDesign& d, const std::vector<NeutralCurve>& sections, const std::string& what = "");
/// The same for any gear on any rim's curves (its x_c left as it is; the shift is x_f + shift_difference), `drive`
/// naming it in the error ("size 14, ratio 30").
ZeroBacklash zero_backlash(const GearParams& g, const std::vector<NeutralCurve>& sections, const std::string& drive,
                           const std::string& what = "");

/// The design as a case file (TOML, lengths in mm) with a header comment naming the source of every proportion.
/// It loads with io/case.hpp's load_case and passes the flexspline, gear and bearing validation.
std::string design_case_toml(const CupDesign& d);

}  // namespace sw
