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
  f.rig_hysteresis_loss_rad = f.hysteresis_loss_rad + play_rad;
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

// The sheet's hysteresis figure is the catalog's as a rig reads it, the output staying where it arrives on returning to
// zero torque: with play the friction's part is nothing (1e-12 rad, shown at the printed 0.000) and the figure is the
// dead band, which the method names as clearance beside the friction's part and the loop's widest gap (the lens the
// flanks' friction draws between zero and the corners). Preloaded, the figure is the friction's gap and the dead band
// is 0.
TEST(SheetHysteresis, TheFigureIsWhatARigReadsAndItsMethodSplitsFrictionFromClearance) {
  const ContactAnalysis with_play = loop_with_play(2e-5);
  const Datasheet sheet = make_datasheet(inputs(with_play));
  const DatasheetFigure* h = sheet.find("hysteresis_loss_arcmin");
  ASSERT_NE(h, nullptr);
  ASSERT_TRUE(h->value.has_value());
  EXPECT_DOUBLE_EQ(*h->value, (2e-5 + 1e-12) * kArcminPerRad);
  EXPECT_NE(h->method.find("the flanks' friction 0.000 arcmin"), std::string::npos) << h->method;
  EXPECT_NE(h->method.find("cross at zero torque 0.069 arcmin (clearance, not friction)"), std::string::npos)
      << h->method;
  EXPECT_NE(h->method.find("the loop is widest at 17.05 N·m, 0.430 arcmin"), std::string::npos) << h->method;

  const ContactAnalysis preloaded = loop_with_play(0);
  const DatasheetFigure* p = make_datasheet(inputs(preloaded)).find("hysteresis_loss_arcmin");
  ASSERT_NE(p, nullptr);
  EXPECT_DOUBLE_EQ(*p->value, 5e-5 * kArcminPerRad);
  EXPECT_NE(p->method.find("the flanks' friction 0.172 arcmin"), std::string::npos) << p->method;
  EXPECT_NE(p->method.find("cross at zero torque 0.000 arcmin"), std::string::npos) << p->method;
  EXPECT_NE(p->method.find("widest at 17.05 N·m"), std::string::npos) << p->method;
}

}  // namespace
}  // namespace sw
