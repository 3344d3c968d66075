// The sheet's figures of the loaded contact, on a contact analysis made by hand: what the hysteresis figure counts.
#include <gtest/gtest.h>

#include <numbers>
#include <string>

#include "datasheet/datasheet.hpp"

namespace sw {
namespace {

constexpr double kArcminPerRad = 10800 / std::numbers::pi;

ContactAnalysis loop_with_play(double play_rad) {
  ContactAnalysis a;
  a.solver = "fourier";
  a.play_rad = play_rad;
  FrictionLoop f;
  f.friction_coefficient = 0.1;
  f.hysteresis_loss_rad = play_rad > 0 ? 1e-12 : 5e-5;
  f.widest = {1.25e-4, 17.05};
  a.friction = f;
  return a;
}

DatasheetInputs inputs(const ContactAnalysis& a) {
  DatasheetInputs in;
  in.rated_torque_Nm = 31;
  in.rated_torque_origin = "[load] rated_torque_Nm";
  in.ratio = 100;
  in.contact = &a;
  return in;
}

// With play the loop's gap at zero torque is nothing, and the sheet says why and where the loop is wide: the
// hysteresis figure is the gap at zero torque, its method names the widest gap and its torque (the lens the flanks'
// friction draws between zero and the corners) and what a rig would read more (its output stops at the dead band's
// edge it arrives at). Without play the dead band's sentences are not there.
TEST(SheetHysteresis, TheFigureIsTheGapAtZeroTorqueAndItsMethodNamesTheWidestGap) {
  const ContactAnalysis with_play = loop_with_play(2e-5);
  const Datasheet sheet = make_datasheet(inputs(with_play));
  const DatasheetFigure* h = sheet.find("hysteresis_loss_arcmin");
  ASSERT_NE(h, nullptr);
  ASSERT_TRUE(h->value.has_value());
  EXPECT_DOUBLE_EQ(*h->value, 1e-12 * kArcminPerRad);
  EXPECT_NE(h->method.find("closes through the dead band"), std::string::npos) << h->method;
  EXPECT_NE(h->method.find("reads the play as well: 0.069 arcmin more"), std::string::npos) << h->method;
  EXPECT_NE(h->method.find("the loop is widest at 17.05 N·m, 0.430 arcmin"), std::string::npos) << h->method;

  const ContactAnalysis preloaded = loop_with_play(0);
  const DatasheetFigure* p = make_datasheet(inputs(preloaded)).find("hysteresis_loss_arcmin");
  ASSERT_NE(p, nullptr);
  EXPECT_DOUBLE_EQ(*p->value, 5e-5 * kArcminPerRad);
  EXPECT_EQ(p->method.find("dead band"), std::string::npos) << p->method;
  EXPECT_NE(p->method.find("widest at 17.05 N·m"), std::string::npos) << p->method;
}

}  // namespace
}  // namespace sw
