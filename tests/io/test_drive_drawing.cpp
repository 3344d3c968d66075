// drive.svg: the drawing of the drive's parts puts them where the backlash model has them. Its paths are read back and
// their radii held against the gear's circles (the coordinates are whole micrometres: a radius read back is within
// √2/2 µm of the drawn point's).
#include <algorithm>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gear/tooth_profile.hpp"
#include "io/case.hpp"
#include "io/drive_drawing.hpp"
#include "kinematics/neutral_curve.hpp"

namespace {

using namespace sw;

/// The closed sub-paths ("M x yL x y…Z") of the path with this id, as lists of radii (µm).
std::vector<std::vector<double>> radii_of(const std::string& svg, const std::string& id) {
  const std::size_t at = svg.find("id=\"" + id + "\"");
  EXPECT_NE(at, std::string::npos) << id;
  const std::size_t d0 = svg.find(" d=\"", at) + 4, d1 = svg.find('"', d0);
  std::vector<std::vector<double>> out;
  const std::string d = svg.substr(d0, d1 - d0);
  const std::regex point("([Ml])(-?[0-9]+) (-?[0-9]+)");
  double x = 0, y = 0;
  for (auto it = std::sregex_iterator(d.begin(), d.end(), point); it != std::sregex_iterator(); ++it) {
    if ((*it)[1] == "M") {
      out.emplace_back();
      x = y = 0;
    }
    x += std::stod((*it)[2]);
    y += std::stod((*it)[3]);
    out.back().push_back(std::hypot(x, y));
  }
  return out;
}

double largest(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }
double smallest(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

// The size-17 cup with its generator bearing, on the cam's curve w0·cos 2φ: the circular spline's outline runs from
// its tip circle to its outside; the flexspline's teeth reach tip_f + w0 at the major axis and its bore swings between
// bore ± w0; every ball is drawn and the labels name the parts with their tooth counts.
TEST(DriveDrawing, PartsSitOnTheirCircles) {
  const Case c = load_case("cases/cup_size17.toml");
  const double w0 = *c.wave_generator->radial_deformation_m;
  const BacklashModel m = make_backlash_model(*c.gear, cam_neutral_curve(rim_mean_radius(c.flexspline), w0));
  DriveOutline o;
  o.bore_radius_m = c.flexspline.inner_radius_m;
  o.circular_spline_outer_radius_m = 30e-3;
  o.bearing = c.wave_generator->bearing;
  o.generator = "cam";
  const std::string svg = drive_svg(m, o, "size 17");
  constexpr double kTol_um = 0.71;
  const auto cs = radii_of(svg, "circular-spline");
  ASSERT_EQ(cs.size(), 2u);
  EXPECT_NEAR(smallest(cs[0]), 30e3, kTol_um);
  EXPECT_NEAR(largest(cs[0]), 30e3, kTol_um);
  EXPECT_NEAR(smallest(cs[1]), m.radii.tip_c * 1e6, kTol_um);
  EXPECT_LT(largest(cs[1]), m.radii.root_c * 1e6);
  const auto fs = radii_of(svg, "flexspline");
  ASSERT_EQ(fs.size(), 2u);
  EXPECT_NEAR(largest(fs[0]), (m.radii.tip_f + w0) * 1e6, kTol_um);
  EXPECT_NEAR(largest(fs[1]), (o.bore_radius_m + w0) * 1e6, kTol_um);
  EXPECT_NEAR(smallest(fs[1]), (o.bore_radius_m - w0) * 1e6, kTol_um);
  EXPECT_EQ(fs[0].size(), static_cast<std::size_t>(c.gear->teeth_flexspline) * 14);  // 2 flanks × 7 points a tooth
  std::size_t paths = 0;
  for (std::size_t at = svg.find("<path"); at != std::string::npos; at = svg.find("<path", at + 1)) ++paths;
  EXPECT_EQ(paths, 5u + static_cast<std::size_t>(o.bearing->balls));  // the two gears, two rings, the cam, the balls
  for (const std::string& text : {std::to_string(c.gear->teeth_circular) + " internal teeth",
                                  std::to_string(c.gear->teeth_flexspline) + " external teeth",
                                  std::to_string(o.bearing->balls) + " balls", std::string("major axis"),
                                  std::string("minor axis")})
    EXPECT_NE(svg.find(text), std::string::npos) << text;
}

}  // namespace
