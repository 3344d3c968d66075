// Where the generator is locked ([contact] generator_angle_deg), on the designed size-17 drive (cases/cup_size17.toml,
// harmonic solver, three face sections). Two symmetries of the mesh hold exactly in the model, and a generator angle
// that placed the teeth by any other rule (the flexspline's tooth count for the circular spline's, the wrong sense)
// breaks them; a third check makes sure the angle moves the teeth at all, so the first two cannot pass on a key that
// is ignored:
//  - period: turning the generator by one circular-spline pitch 2π/z_c puts every flexspline tooth where its
//    neighbour was (material angle 2πk/z_f − angle·z_c/z_f), so the drive is the same: the curves agree to round-off.
//  - mirror: the teeth, the generator and the cup are symmetric about the major axis, so the generator at 2π/z_c − δ
//    (that is, −δ) is the mirror image of the generator at δ: the twist at T there is minus the twist at −T here.
//  - a quarter pitch from a tooth on the major axis the teeth sit elsewhere: the curve differs.
// Tolerances: the flanks' problem is solved exactly (active sets), but the generator's balls are a nonlinear law
// settled by secants to 1e-4 of the largest preload's approach (contact/loaded_contact.cpp), a twist below 1e-4
// arcmin: both symmetries are asserted to 2e-5 of the twist at rated torque (some 1e-4 arcmin; 1.5e-7 and 2e-7
// measured), the angle's effect to more than 1e-3 of it (3e-2 measured).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "contact/loaded_contact.hpp"
#include "tests/contact/size17_harmonic.hpp"

namespace sw {
namespace {

ContactAnalysis locked_at(double generator_angle_rad) {
  const test::Size17Harmonic& s = test::size17_harmonic();
  ContactOptions o = s.options;
  o.contact.generator_angle_rad = generator_angle_rad;
  return analyse_contact(flexspline_model(s.c), *s.body, s.readout, o);
}

/// The generator with a tooth on the major axis (both tests' reference), solved once.
const ContactAnalysis& tooth_on_the_major_axis() {
  static const ContactAnalysis a = locked_at(0.0);
  return a;
}

double pitch_c_rad() { return 2 * std::numbers::pi / test::size17_harmonic().c.gear->teeth_circular; }

TEST(GeneratorAngle, OneCircularSplinePitchLaterTheDriveIsTheSame) {
  const ContactAnalysis& a = tooth_on_the_major_axis();
  const ContactAnalysis b = locked_at(pitch_c_rad());
  ASSERT_EQ(a.curve.twist_rad.size(), b.curve.twist_rad.size());
  const double scale = std::abs(a.curve.twist_rad.back());
  double worst = 0;
  for (std::size_t i = 0; i < a.curve.twist_rad.size(); ++i) {
    ASSERT_EQ(a.curve.torque_Nm[i], b.curve.torque_Nm[i]);
    worst = std::max(worst, std::abs(a.curve.twist_rad[i] - b.curve.twist_rad[i]));
  }
  std::printf("one circular-spline pitch on: the curve moves by %.2e of the twist at rated\n", worst / scale);
  EXPECT_LT(worst, 2e-5 * scale);
}

TEST(GeneratorAngle, TheGeneratorOnTheOtherSideIsTheMirrorImage) {
  const double delta = 0.3 * pitch_c_rad();
  const ContactAnalysis a = locked_at(delta), b = locked_at(pitch_c_rad() - delta);
  const ContactAnalysis& zero = tooth_on_the_major_axis();
  const std::size_t n = a.curve.twist_rad.size();
  ASSERT_EQ(n, b.curve.twist_rad.size());
  const double scale = std::abs(a.curve.twist_rad.back());
  double worst = 0, moved = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = n - 1 - i;  // the curve runs from −rated to +rated
    ASSERT_EQ(a.curve.torque_Nm[i], -b.curve.torque_Nm[j]);
    worst = std::max(worst, std::abs(a.curve.twist_rad[i] + b.curve.twist_rad[j]));
    moved = std::max(moved, std::abs(a.curve.twist_rad[i] - zero.curve.twist_rad[i]));
  }
  std::printf("generator at +-%.4f deg: mirror images to %.2e of the twist at rated; %.2e from a tooth on the "
              "major axis; play %.4f vs %.4f arcmin there\n", delta * 180 / std::numbers::pi, worst / scale,
              moved / scale, a.play_rad * 10800 / std::numbers::pi, zero.play_rad * 10800 / std::numbers::pi);
  EXPECT_LT(worst, 2e-5 * scale);
  EXPECT_GT(moved, 1e-3 * scale);
}

}  // namespace
}  // namespace sw
