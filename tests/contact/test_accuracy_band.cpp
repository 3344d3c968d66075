// Pitch deviations in the loaded contact (contact/loaded_contact.hpp ToothDeviations) and the band over drives of one
// ISO 1328-1 class (contact/accuracy_band.hpp), on the designed size-17 cup on the harmonic solver:
//  - every flexspline tooth moved by the same e along the rim is the output turned by e/r_f before the load: the whole
//    curve shifts by exactly that turn (the forces unchanged), to round-off;
//  - every circular spline tooth turned by the same e/r_c: the curve shifts the other way by that turn, to round-off;
//  - zero deviations are the exact teeth; the draws lie within the class, pair half a turn apart, repeat by seed;
//  - the refusals.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "common/error.hpp"
#include "contact/accuracy_band.hpp"
#include "tests/contact/size17_harmonic.hpp"

namespace sw {
namespace {

struct Solved : test::Size17Harmonic {
  ContactAnalysis exact;
};

const Solved& size17() {
  static const Solved* s = [] {
    auto* k = new Solved{test::size17_harmonic(), {}};
    k->exact = analyse_contact(flexspline_model(k->c), *k->body, k->readout, k->options);
    return k;
  }();
  return *s;
}

ContactAnalysis with(const ToothDeviations& d) {
  const Solved& s = size17();
  ContactOptions o = s.options;
  o.deviations = d;
  return analyse_contact(flexspline_model(s.c), *s.body, s.readout, o);
}

/// The largest difference of the two curves' twists at the same torques less `shift`, over the largest twist.
double curve_difference(const ContactAnalysis& a, const ContactAnalysis& b, double shift) {
  EXPECT_EQ(a.steps.size(), b.steps.size());
  double worst = 0, largest = 0;
  for (std::size_t i = 0; i < a.steps.size() && i < b.steps.size(); ++i) {
    EXPECT_DOUBLE_EQ(a.steps[i].torque_Nm, b.steps[i].torque_Nm);
    worst = std::max(worst, std::abs(b.steps[i].twist_rad - a.steps[i].twist_rad - shift));
    largest = std::max(largest, std::abs(a.steps[i].twist_rad));
  }
  return worst / largest;
}

TEST(PitchDeviations, ZeroDeviationsAreTheExactTeeth) {
  const Solved& s = size17();
  const GearParams& g = *s.c.gear;
  ToothDeviations d;
  d.flexspline_m.assign(g.teeth_flexspline, 0.0);
  d.circular_spline_m.assign(g.teeth_circular, 0.0);
  EXPECT_LT(curve_difference(s.exact, with(d), 0.0), 1e-12);
}

TEST(PitchDeviations, FlexsplineTeethMovedAlikeTurnTheWholeCurve) {
  const Solved& s = size17();
  const GearParams& g = *s.c.gear;
  const double e = 3e-6, r_f = g.module_m * g.teeth_flexspline / 2;
  ToothDeviations d;
  d.flexspline_m.assign(g.teeth_flexspline, e);
  const ContactAnalysis moved = with(d);
  const double diff = curve_difference(s.exact, moved, -e / r_f);
  std::printf("flexspline teeth moved alike: the curve turned by the deviation to %.2e of the twist\n", diff);
  EXPECT_LT(diff, 1e-9);  // 3 µm is 1.4e-4 rad, ~5 % of the twist at rated
  EXPECT_EQ(moved.steps.back().pairs_in_contact, s.exact.steps.back().pairs_in_contact);
}

TEST(PitchDeviations, CircularSplineTeethTurnedAlikeTurnTheCurveBack) {
  const Solved& s = size17();
  const GearParams& g = *s.c.gear;
  const double e = 3e-6, r_c = g.module_m * g.teeth_circular / 2;
  ToothDeviations d;
  d.circular_spline_m.assign(g.teeth_circular, e);
  const ContactAnalysis turned = with(d);
  const double shift = e / r_c;
  std::printf("circular spline teeth turned alike: the curve turned back by the deviation to %.2e of the twist "
              "(the deviation's turn is %.2e of it)\n", curve_difference(s.exact, turned, shift),
              shift / std::abs(s.exact.steps.back().twist_rad));
  // The gap changes by (p_c × n)·e/r_c, the turn closes it at lever = (p_f × n); n lies along p_c − p_f, so the two
  // are equal and the shift exact.
  EXPECT_LT(curve_difference(s.exact, turned, shift), 1e-9);
}

TEST(PitchDeviations, DrawsLieWithinTheClassAndPairHalfATurnApart) {
  const GearParams& g = *size17().c.gear;
  const FlankTolerances t = iso1328_tolerances(g.module_m * 1e3 * g.teeth_flexspline, g.module_m * 1e3, 5);
  const ToothDeviations a = draw_pitch_deviations(g, t.single_pitch_um, 2 * t.single_pitch_um, 7),
                        b = draw_pitch_deviations(g, t.single_pitch_um, 2 * t.single_pitch_um, 7),
                        c = draw_pitch_deviations(g, t.single_pitch_um, 2 * t.single_pitch_um, 8);
  EXPECT_EQ(a.flexspline_m, b.flexspline_m);
  EXPECT_NE(a.flexspline_m, c.flexspline_m);
  const int zf = g.teeth_flexspline, zc = g.teeth_circular;
  double largest = 0;
  for (int k = 0; k < zf; ++k) {
    EXPECT_LE(std::abs(a.flexspline_m[k]), 0.5e-6 * t.single_pitch_um);
    EXPECT_LE(std::abs(a.flexspline_m[k] - a.flexspline_m[(k + 1) % zf]), 1e-6 * t.single_pitch_um);  // f_pt
    EXPECT_EQ(a.flexspline_m[k], a.flexspline_m[(k + zf / 2) % zf]);
    largest = std::max(largest, std::abs(a.flexspline_m[k]));
  }
  EXPECT_GT(largest, 0.4e-6 * t.single_pitch_um);  // the draw spans the class
  for (int k = 0; k < zc; ++k) {
    EXPECT_LE(std::abs(a.circular_spline_m[k]), 1e-6 * t.single_pitch_um);
    EXPECT_EQ(a.circular_spline_m[k], a.circular_spline_m[(k + zc / 2) % zc]);
  }
}

TEST(PitchDeviations, Refusals) {
  const GearParams& g = *size17().c.gear;
  ToothDeviations short_list;
  short_list.flexspline_m.assign(g.teeth_flexspline - 1, 0.0);
  EXPECT_THROW(with(short_list), InputError);
  ToothDeviations unpaired;
  unpaired.circular_spline_m.assign(g.teeth_circular, 0.0);
  unpaired.circular_spline_m[3] = 1e-6;
  EXPECT_THROW(with(unpaired), InputError);
  const Solved& s = size17();
  EXPECT_THROW(accuracy_band(flexspline_model(s.c), *s.body, s.readout, s.options, 12, 4), InputError);
  EXPECT_THROW(accuracy_band(flexspline_model(s.c), *s.body, s.readout, s.options, 5, 1), InputError);
}

// The band: each drive is the contact on its own draw; the spread orders its drives.
TEST(AccuracyBand, EachDriveIsItsDraw) {
  const Solved& s = size17();
  const AccuracyBand band = accuracy_band(flexspline_model(s.c), *s.body, s.readout, s.options, 5, 3);
  ASSERT_EQ(band.drive.size(), 3u);
  const GearParams& g = *s.c.gear;
  const ContactAnalysis second =
      with(draw_pitch_deviations(g, band.flexspline.single_pitch_um, band.circular_spline.single_pitch_um, 2));
  EXPECT_DOUBLE_EQ(band.drive[1].twist_at_rated_rad, second.curve.twist_rad.back());
  EXPECT_DOUBLE_EQ(band.drive[1].k3_Nm_per_rad, second.catalog.k3_Nm_per_rad);
  const Spread k3 = spread({band.drive[0].k3_Nm_per_rad, band.drive[1].k3_Nm_per_rad, band.drive[2].k3_Nm_per_rad});
  EXPECT_LE(k3.min, k3.median);
  EXPECT_LE(k3.median, k3.max);
}

}  // namespace
}  // namespace sw
