#include "design/proportions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <optional>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "common/case_keys.hpp"
#include "common/error.hpp"
#include "contact/contact_params.hpp"
#include "design/catalog.hpp"
#include "fem/fem_params.hpp"
#include "gear/tooth_profile.hpp"
#include "kinematics/backlash.hpp"

namespace sw {
namespace {

// ---- The rules. Every one is a fixed number for every size and ratio; `d` is the pitch diameter, `m` the module.
// Sources:
//  [Musser]   C. W. Musser, "Strain wave gearing", US patent 2,906,143 (1959): two lobes, a tooth difference of two,
//             the flexspline's radial deflection at the major axis half the tooth difference in modules: w0 = m.
//  [Ivanov]   M. N. Ivanov, "Volnovye zubchatye peredachi" (Wave gear drives), Vysshaya shkola, Moscow 1981: the
//             steel flexspline's design recommendations as usually quoted: rim under the teeth 0.01–0.015·d, body
//             wall thinner than the rim (0.6–0.9 of it), toothed face width 0.15–0.2·d.
//  [ISO 53]   the basic rack: h_a* = 1, h_f* = 1.25 (c* = 0.25), α = 20°.
//  [Seed]     the backlash paper's gear set (shared/seeds/backlash_fem_paper.txt): z = 190/192, m = 0.2 mm,
//             x_f = 1.52, x_c = 1.57 (x_c − x_f = 0.05), shaper cutter z_0 = 80; this tool's seed case shortens its
//             teeth to h_a* = 0.7 after the geometry check (cases/seed_190_192.toml). Its x_c − x_f = 0.05 leaves
//             1.2 arcmin of play at ratio 100; the design sets x_c for zero backlash instead ([Zero]).
//  [Zero]     harmonic drive component sets are sold as zero-backlash gearing (the maker's CSF/CSG catalog: lost
//             motion below 1 arcmin with the elastic twist included, ../shared/reference/catalog_torsional_stiffness.md;
//             "the HDs are usually designed with zero backlash at the gear mesh": Materials 14 (2021) 5057, the
//             introduction of its lost-motion sensitivity study): the teeth are cut so that the tightest pair touches
//             at rest (set_zero_backlash).
//  [Harris]   T. A. Harris, M. N. Kotzalas, Rolling Bearing Analysis, 5th ed., ch. 2: deep-groove groove conformity
//             0.515–0.53 (inner race closer than outer).
//  [ISO 6336] ISO 6336-3 tooth-root stress σ_F ∝ F_t/(b·m) = 2T/(d·b·m): with b, m ∝ d the torque capacity of
//             geometrically similar gears grows as d³.
//  [Estimate] our reading of the CSF/CSG component sets' published outline dimensions, not the maker's drawing.
constexpr double kMmPerSize = 2.54;              // the size number is the pitch diameter in tenths of an inch
constexpr double kPressureAngleDeg = 20.0;       // [ISO 53]
constexpr double kShiftFlexspline = 1.52;        // [Seed] x_f
constexpr int kCutterTeeth = 80;                 // [Seed] z_0 of the shaper cutter
constexpr double kAddendum = 0.7;                // short teeth on both gears: working depth 1.4·m < 2·w0 = 2·m, the
                                                 // tips pass at the minor axis ([Seed] case; the geometry check)
constexpr double kTipClearance = 0.25;           // [ISO 53] c*: h_f* = h_a* + c*
constexpr double kW0PerModule = 1.0;             // [Musser] w0 = m·(z_c − z_f)/2
// [Ivanov] the rim under the teeth (0.01–0.015·d), the body wall (0.6–0.9 of the rim) and the toothed face width
// (0.15–0.2·d): DesignProportions (proportions.hpp), its defaults 0.014·d, 0.7 and 0.15·d.
constexpr double kLengthPerD = 0.6;              // [Estimate] the short cup of the CSF/CSG generation, L ≈ 0.6·d
                                                 // (Ivanov's older recommendation: L ≥ 0.8·d)
constexpr double kDiaphragmPerRim = 2.0;         // [Estimate] diaphragm twice the rim: a plate that carries the
                                                 // torque to the boss in shear
constexpr double kBossPerD = 0.2;                // [Estimate] hub (boss) radius 0.2·d
constexpr double kFilletPerWall = 2.5;           // [Estimate] diaphragm-to-wall fillet 2.5 walls
constexpr double kBandPerFaceWidth = 0.65;       // [Estimate] generator band (the bearing's outer ring) under the
                                                 // toothed rim, centred on it
constexpr double kBallPerD = 0.09;               // [Estimate] ball diameter ≈ 0.09·d, rounded to 1/64 inch (ISO 3290
                                                 // grade balls in inch sizes): size 17 → 5/32" = 3.969 mm
constexpr double kBallPitchPerBall = 1.2;        // [Estimate] ball spacing on the pitch circle ≥ 1.2·D (cage bars)
constexpr double kInnerConformity = 0.52, kOuterConformity = 0.53;  // [Harris]

std::string fixed(double v, int digits) {
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}

/// One line of a table `design` writes: a key of the table's schema, a comment line before it, a comment after it.
struct DesignLine {
  const char* key;
  const char* comment_before = "";
  const char* comment_after = "";
};

/// The keys `lines` of `t` by its table's schema (common/case_keys.hpp): names and units the reader's, numbers to 9
/// significant digits (the design's precision, a person's reading), words quoted; one key a line, or, with a
/// separator, the inner part of an inline table.
template <class T>
std::string key_lines(const T& t, const std::vector<CaseKey<T>>& keys, std::initializer_list<DesignLine> lines,
                      const char* separator = nullptr) {
  std::string s;
  for (const DesignLine& l : lines) {
    const CaseKey<T>& k = key_named(keys, l.key);
    const std::optional<KeyValue> v = k.get(t);
    if (!v || !k.applies_to(t))
      throw std::logic_error(std::string("design writes ") + l.key + ", which its case lacks");
    const auto* x = std::get_if<double>(&*v);
    if (separator && !s.empty()) s += separator;
    if (*l.comment_before) s += std::string("# ") + l.comment_before + "\n";
    s += k.name + " = " + (x ? num(*x) : key_value_toml(*v));
    if (*l.comment_after) s += std::string("   # ") + l.comment_after;
    if (!separator) s += "\n";
  }
  return s;
}

}  // namespace

void validate_design_proportions(const DesignProportions& p) {
  for (const DesignProportion& q : kDesignProportions) {
    const double v = p.*q.member;
    if (v >= q.min && v <= q.max) continue;
    throw InputError(std::string(q.option) + " " + num(v) + "; must be in [" + num(q.min) + ", " + num(q.max) +
                     "] (Ivanov's " + q.meaning + ")");
  }
}

std::string design_proportion_options(const DesignProportions& p) {
  const DesignProportions nominal;
  std::string s;
  for (const DesignProportion& q : kDesignProportions)
    if (p.*q.member != nominal.*q.member) s += std::string(" ") + q.option + " " + num(p.*q.member);
  return s;
}

void round_tips(CupDesign& d, double per_module) {
  const std::string option = "--tip-rounding-per-m " + num(per_module);
  if (!(per_module >= 0 && per_module < 1))
    throw InputError(option + "; must be in [0, 1) (both gears' tip rounding over the module; 0: sharp)");
  GearParams g = d.gear;
  g.tip_rounding_flexspline_m = g.tip_rounding_circular_m = per_module * g.module_m;
  try {
    flexspline_tip_rounding(g);
    circular_tip_rounding(g);
  } catch (const InputError&) {
    throw InputError(option + " (" + num(g.tip_rounding_flexspline_m * 1e3) + " mm); the rounding must end on both "
                     "teeth's flanks above their form radius and leave part of their tip lands: make it smaller");
  }
  d.gear = g;
  d.tip_rounding_per_module = per_module;
}

CupDesign design_cup(int size, int ratio, const DesignProportions& p) {
  if (size < kDesignSizeMin || size > kDesignSizeMax)
    throw InputError("--size " + std::to_string(size) + "; must be an integer in [" + std::to_string(kDesignSizeMin) +
                     ", " + std::to_string(kDesignSizeMax) + "] (the pitch diameter in tenths of an inch)");
  if (ratio < kDesignRatioMin || ratio > kDesignRatioMax)
    throw InputError("--ratio " + std::to_string(ratio) + "; must be an integer in [" +
                     std::to_string(kDesignRatioMin) + ", " + std::to_string(kDesignRatioMax) +
                     "] (z_f = 2 x ratio teeth, z_c = z_f + 2; the short-tooth rule is verified in that range)");
  validate_design_proportions(p);
  CupDesign c;
  c.size = size;
  c.ratio = ratio;
  c.proportions = p;
  const double d = size * kMmPerSize * 1e-3;
  c.pitch_diameter_m = d;

  GearParams& g = c.gear;
  g.teeth_flexspline = 2 * ratio;  // ratio = z_f / (z_c − z_f) with z_c − z_f = 2
  g.teeth_circular = g.teeth_flexspline + 2;
  g.module_m = d / g.teeth_flexspline;
  g.pressure_angle_rad = kPressureAngleDeg * std::numbers::pi / 180.0;
  g.profile_shift_flexspline = kShiftFlexspline;
  g.profile_shift_circular = kShiftFlexspline;  // set_zero_backlash below
  g.cutter_teeth = kCutterTeeth;
  g.addendum_coefficient_flexspline = g.addendum_coefficient_circular = kAddendum;
  g.dedendum_coefficient_flexspline = g.dedendum_coefficient_circular = kAddendum + kTipClearance;
  const GearRadii radii = gear_radii(g);

  FlexsplineParams& f = c.flexspline;
  f.shape = FlexsplineShape::Cup;
  // The rim, its outside the teeth's root circle, and on it the teeth as ribs along the face (teeth = "layer"): the
  // teeth's bending and foundation are the contact stage's, in series, built in at the root. Teeth separated by
  // spaces carry almost no hoop or torsional shear (a ring smearing half the tooth layer would over-state the rim's
  // hoop bending, ((t + h/2)/t)³ ≈ 2× here), but each is a solid rib along the face, which stiffens the rim's bending
  // along it: against the explicit teeth in 3-D (bench_teeth_reference) the layer is closer than the bare rim at every
  // face section count.
  f.teeth = TeethModel::Layer;
  f.rim_thickness_m = p.rim_per_d * d;
  f.inner_radius_m = radii.root_f - f.rim_thickness_m;  // the root circle is the rim's outside, exactly
  f.wall_thickness_m = p.wall_per_rim * f.rim_thickness_m;
  f.rim_width_m = p.face_per_d * d;
  f.length_m = kLengthPerD * d;
  f.diaphragm_thickness_m = kDiaphragmPerRim * f.rim_thickness_m;
  f.boss_radius_m = kBossPerD * d;
  f.fillet_radius_m = kFilletPerWall * f.wall_thickness_m;

  c.material.fatigue_limit_Pa = 500e6;  // typical Ni-Cr-Mo flexspline steel, as the other cases
  // A quenched and tempered Ni-Cr-Mo steel, 34CrNiMo6+QT at 16–40 mm (EN 10083-3:2006, Table 6): R_m 1100–1300 MPa
  // (the lower end, as the Goodman line's intercept above), R_e ≥ 900 MPa.
  c.material.ultimate_strength_Pa = 1100e6;
  c.material.yield_strength_Pa = 900e6;

  WaveGeneratorParams& w = c.wave_generator;
  w.model = Cam{};
  w.radial_deformation_m = kW0PerModule * g.module_m * (g.teeth_circular - g.teeth_flexspline) / 2.0;
  w.axial_position_m = 0.5 * f.rim_width_m;
  w.band_width_m = kBandPerFaceWidth * f.rim_width_m;
  GeneratorBearing b;
  const double inch64 = 25.4e-3 / 64.0;
  b.ball_diameter_m = std::max(1.0, std::round(kBallPerD * d / inch64)) * inch64;
  b.pitch_radius_m = bearing_pitch_radius_m(f.inner_radius_m, b.ball_diameter_m);
  b.balls = static_cast<int>(std::floor(2.0 * std::numbers::pi * b.pitch_radius_m / (kBallPitchPerBall * b.ball_diameter_m)));
  b.inner_groove_conformity = kInnerConformity;
  b.outer_groove_conformity = kOuterConformity;
  w.bearing = b;

  c.circular_spline = default_circular_spline(g, f.rim_width_m);
  set_zero_backlash(c, {cam_neutral_curve(rim_mean_radius(f), *w.radial_deformation_m)});

  if (const CatalogDrive* row = catalog_drive(size); row && row->has_rated_torque()) {
    c.rated_torque_Nm = row->rated_torque_Nm;
    c.rated_torque_from = "catalog size " + std::to_string(size) + " (CSG rating at ratio 100)";
  } else {
    // [ISO 6336] d³ scaling from the listed size with a rated torque nearest in diameter.
    const CatalogDrive* ref = nullptr;
    for (const auto& r : catalog_drives())
      if (r.has_rated_torque() && (!ref || std::abs(r.pitch_diameter_m - d) < std::abs(ref->pitch_diameter_m - d)))
        ref = &r;
    c.rated_torque_Nm = ref->rated_torque_Nm * std::pow(d / (ref->size * kMmPerSize * 1e-3), 3);
    c.rated_torque_from = "catalog size " + std::to_string(ref->size) + " scaled by (d/d_" +
                          std::to_string(ref->size) + ")^3 (tooth-root stress, ISO 6336-3)";
  }
  return c;
}

ZeroBacklash zero_backlash(const GearParams& gear, const std::vector<NeutralCurve>& sections, const std::string& drive,
                          const std::string& what) {
  if (sections.empty()) throw std::invalid_argument("zero_backlash: no neutral curve");
  GearParams g = gear;
  std::size_t tightest_on = 0;  // the section of the last call's tightest pair
  auto tightest = [&](double shift_difference) {
    g.profile_shift_circular = g.profile_shift_flexspline + shift_difference;
    TightestPair t;
    for (std::size_t i = 0; i < sections.size(); ++i) {
      const TightestPair ti = tightest_pair_at_rest(make_backlash_model(g, sections[i]));
      if (i == 0 || ti.clearance_m < t.clearance_m) {
        t = ti;
        tightest_on = i;
      }
    }
    return t;
  };
  const NeutralCurve& curve = sections[sections.size() / 2];  // the middle one: the face's centre
  const std::string curves = what.empty() ? sections.front().source : what;
  // The tightest pair is left 0.1 nm apart, not 0: the case text's 9 digits move the geometry by about 1e-9 of its
  // 20 mm radius, 2e-11 m, which must not turn the touch into an overlap when the case is read back.
  constexpr double kLo = -0.2, kHi = 0.3, kStep = 1e-8, kTouch_m = 1e-10;
  double lo = kLo, hi = kHi;
  if (!(tightest(lo).clearance_m < kTouch_m && tightest(hi).clearance_m > kTouch_m)) {
    std::ostringstream os;
    os << drive << ": no profile shift difference x_c - x_f in [" << kLo << ", "
       << kHi << "] takes the teeth from overlap to clearance at rest on the " << curves << " curve";
    throw InputError(os.str());
  }
  while (hi - lo > 0.25 * kStep) {
    const double mid = 0.5 * (lo + hi);
    (tightest(mid).clearance_m < kTouch_m ? lo : hi) = mid;
  }
  // Rounded up to the 1e-8 the case text carries (x_c has 9 digits), so that the written case never overlaps.
  const double shift_difference = std::ceil(hi / kStep) * kStep;
  const TightestPair t = tightest(shift_difference);
  const BacklashModel model = make_backlash_model(g, curve);
  const FlankClearance& touching = t.pair.ccw.clearance_m < t.pair.cw.clearance_m ? t.pair.ccw : t.pair.cw;
  ZeroBacklash z;
  z.curve = curves;
  z.tightest_section = sections[tightest_on].source;
  z.shift_difference = shift_difference;
  z.tightest_clearance_m = t.clearance_m;
  // Its distance from the major axis, 0..90°: the generator and the teeth are symmetric about both axes, so the
  // tightest place is on the four mirror images at once and which one wins is round-off.
  z.tightest_angle_deg = std::abs(std::remainder(t.pair.phi_rad, std::numbers::pi)) * 180.0 / std::numbers::pi;
  z.tightest_parts = std::string(part_name(touching.part_f)) + " / " + part_name(touching.part_c);
  z.major_axis_play_rad =
      closing_angle_rad(model, 0.0, 0.0, Flank::Ccw) + closing_angle_rad(model, 0.0, 0.0, Flank::Cw);
  return z;
}

void set_zero_backlash(CupDesign& d, const std::vector<NeutralCurve>& sections, const std::string& what) {
  d.zero_backlash =
      zero_backlash(d.gear, sections, "size " + std::to_string(d.size) + ", ratio " + std::to_string(d.ratio), what);
  d.gear.profile_shift_circular = d.gear.profile_shift_flexspline + d.zero_backlash.shift_difference;
}

std::string design_case_toml(const CupDesign& c) {
  const auto mm = [](double m) { return num(m * 1e3); };
  const GearParams& g = c.gear;
  const FlexsplineParams& f = c.flexspline;
  const WaveGeneratorParams& w = c.wave_generator;
  const GeneratorBearing& b = *w.bearing;
  std::ostringstream s;
  s << "# Cup-type strain wave gear of catalog size " << c.size << ", ratio " << c.ratio << ": written by `strainwave design --size "
    << c.size << " --ratio " << c.ratio << design_proportion_options(c.proportions)
    << (c.tip_rounding_per_module > 0 ? " --tip-rounding-per-m " + num(c.tip_rounding_per_module) : std::string())
    << "`.\n"
    << "# One set of proportions for every size (design/proportions.cpp), all lengths multiples of the pitch diameter\n"
    << "# d = size x 2.54 mm = " << mm(c.pitch_diameter_m) << " mm; nothing tuned per size. Where each comes from:\n"
    << "# - teeth: z_f = 2 x ratio = " << g.teeth_flexspline << ", z_c = z_f + 2 (two lobes, tooth difference two: Musser, US 2,906,143),\n"
    << "#   module d/z_f = " << mm(g.module_m) << " mm, 20 deg involute (ISO 53), profile shift x_f = " << num(kShiftFlexspline)
    << " and shaper cutter z_0 = " << kCutterTeeth << " (the backlash paper's set),\n"
    << "#   short teeth h_a* = " << num(kAddendum)
    << " on both gears (working depth 1.4 modules < 2 w0), h_f* = h_a* + 0.25 (ISO 53 c*).\n"
    << "# - zero backlash (harmonic drives are cut without it): x_c = x_f + " << num(c.zero_backlash.shift_difference)
    << ", the smallest shift at which no pair overlaps at rest\n#   on the " << c.zero_backlash.curve
    << " curves;\n#   the tightest pairs touch at +-" << fixed(c.zero_backlash.tightest_angle_deg, 1)
    << " deg from the major axis (" << c.zero_backlash.tightest_parts << ") on the "
    << c.zero_backlash.tightest_section << " curve,\n#   the major-axis pair keeps "
    << fixed(c.zero_backlash.major_axis_play_rad * 180.0 / std::numbers::pi * 60.0, 3)
    << " arcmin of dead band at mid-face (involute flanks and the cup's coning: not every pair is tight at once).\n"
    << (c.tip_rounding_per_module > 0
            ? "# - tip corners of both gears rounded by " + num(c.tip_rounding_per_module) + " m = " +
                  mm(c.gear.tip_rounding_flexspline_m) +
                  " mm (the designer's choice: no standard gives one), before the cut.\n"
            : std::string("# - tip corners sharp, as generated (no standard gives an edge rounding; "
                          "--tip-rounding-per-m sets one before the cut).\n"))
    << "# - straight teeth across the face (shaped or hobbed, no relief along it): the contact meshes the face in "
    << kDesignFaceSections << " sections,\n#   its ends and centre, each with the rim as the generator leaves it there "
    << "([contact] face_slices).\n"
    << "# - w0 = m (Musser: half the tooth difference in modules).\n"
    << "# - rim under the teeth " << num(c.proportions.rim_per_d) << " d, body wall " << num(c.proportions.wall_per_rim)
    << " x rim, toothed face width " << num(c.proportions.face_per_d)
    << " d (Ivanov, Wave gear drives, 1981: 0.01-0.015 d,\n"
    << "#   0.6-0.9 x rim, 0.15-0.2 d); the rim's outside is the teeth's root circle. The FEM holds the rim and on it\n"
    << "#   the teeth as ribs along the face (teeth = \"layer\": stiff along the face, free around the rim); their\n"
    << "#   bending and foundation are the contact stage's tooth-pair compliance, built in at the root.\n"
    << "# - estimates from the CSF/CSG component sets' outline (not the maker's drawing): cup length " << num(kLengthPerD)
    << " d, diaphragm " << num(kDiaphragmPerRim) << " x rim,\n"
    << "#   boss radius " << num(kBossPerD) << " d, fillet " << num(kFilletPerWall) << " x wall, generator band "
    << num(kBandPerFaceWidth) << " x face width under the rim, ball diameter " << num(kBallPerD) << " d in 1/64\"\n"
    << "#   steps, balls at >= " << num(kBallPitchPerBall) << " D on the pitch circle, circular spline outer diameter "
    << num(kCircularSplineOuterDiameterPerPitchDiameter) << " x its pitch diameter.\n"
    << "# - circular spline mounting \"" << to_string(c.circular_spline.mounting)
    << "\": bolted by one end face to the housing, as a catalog drive's is and as its\n"
    << "#   stiffness is measured, held on the annulus " << num(kBoltCircleInnerFraction) << "-"
    << num(kBoltCircleOuterFraction) << " of the way from its root circle to its outside (bolt circle and\n"
    << "#   bolt heads, an estimate from the component sets' outline); \"outer\" (its outside held) is the stiffer\n"
    << "#   idealisation.\n"
    << "# - groove conformity 0.52 inner / 0.53 outer (Harris & Kotzalas, Rolling Bearing Analysis, ch. 2).\n"
    << "# - rated torque " << num(c.rated_torque_Nm) << " N m: " << c.rated_torque_from << ".\n"
    << "# Supports: the boss clamped; the cam pushes the bore over its band; the torque on the rim's engagement zones.\n"
    << "# Mesh: no [mesh] table, so the mesh is derived from the part (the same at every size up to scale).\n"
    << "# Run: build/strainwave run CASE.toml (fem, backlash, contact)\n";
  const auto teeth_note = "ribs along the face on the rim; the teeth bend in series (contact)";
  LoadParams load;  // the FEM's torque and the contact's rated torque: the design's rating
  ContactParams contact;
  contact.face_slices = kDesignFaceSections;
  load.torque_Nm = c.rated_torque_Nm;
  load.rated_torque_Nm = c.rated_torque_Nm;
  s << "[gear]\n"
    << key_lines(g, gear_keys(),
                 {{"module_mm"}, {"teeth_flexspline"}, {"teeth_circular"}, {"pressure_angle_deg"},
                  {"profile_shift_flexspline"}, {"profile_shift_circular"}, {"cutter_teeth"},
                  {"addendum_coefficient_flexspline"}, {"addendum_coefficient_circular"},
                  {"dedendum_coefficient_flexspline"}, {"dedendum_coefficient_circular"}})
    << (c.tip_rounding_per_module > 0
            ? key_lines(g, gear_keys(), {{"tip_rounding_flexspline_mm"}, {"tip_rounding_circular_mm"}})
            : std::string())
    << "\n[flexspline]\n"
    << key_lines(f, flexspline_keys(),
                 {{"shape"}, {"inner_radius_mm"}, {"wall_thickness_mm"}, {"length_mm"}, {"rim_width_mm"},
                  {"rim_thickness_mm"}, {"teeth", "", teeth_note}, {"diaphragm_thickness_mm"}, {"boss_radius_mm"},
                  {"fillet_radius_mm"}})
    << "\n[material]\n"
    << key_lines(c.material, material_keys(),
                 {{"youngs_modulus_Pa"}, {"poisson_ratio"}, {"density_kg_m3"},
                  {"fatigue_limit_MPa", "Fatigue (Goodman): typical values for a quenched and tempered Ni-Cr-Mo "
                                        "flexspline steel, not a certificate."},
                  {"ultimate_strength_MPa"},
                  {"yield_strength_MPa", "First yield: the minimum R_e of 34CrNiMo6+QT at 16-40 mm (EN 10083-3), "
                                         "whose R_m range starts at the above."}})
    << "\n[wave_generator]\n"
    << key_lines(w, wave_generator_keys(),
                 {{"model"}, {"radial_deformation_mm"}, {"axial_position_mm"}, {"band_width_mm"}, {"profile"},
                  {"fit_um"}})
    << "bearing = { "
    << key_lines(b, generator_bearing_keys(),
                 {{"balls"}, {"ball_diameter_mm"}, {"inner_groove_conformity"}, {"outer_groove_conformity"}}, ", ")
    << " }\n"
    << "\n[load]\n"
    << key_lines(load, load_keys(), {{"torque_Nm"}, {"rated_torque_Nm"}})
    << "\n[circular_spline]\n"
    << key_lines(c.circular_spline, circular_spline_keys(),
                 {{"outer_radius_mm"}, {"width_mm"}, {"mounting"}, {"bolt_circle_inner_mm"}, {"bolt_circle_outer_mm"}})
    << "\n[contact]\n"
    << key_lines(contact, contact_keys(), {{"face_slices", "", "the face's ends and centre: straight teeth"}});
  if (catalog_drive(c.size)) s << "\n[catalog]\nsize = " << c.size << "\n";
  return s.str();
}

}  // namespace sw
