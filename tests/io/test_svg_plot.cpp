// The plotting helper's choices people see: tick values (1-2-5 steps, angle steps on degree axes) that cover the data
// with a readable count, log decades, long series thinned to a bounded size, panels stacked in one document.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "common/svg_plot.hpp"

namespace {

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// Step of a tick list (all steps equal to 1e-9 of it).
double step_of(const std::vector<double>& t) {
  const double step = t[1] - t[0];
  for (std::size_t i = 2; i < t.size(); ++i) EXPECT_NEAR(t[i] - t[i - 1], step, 1e-9 * step);
  return step;
}

}  // namespace

TEST(NiceTicks, UnitRangeGoesInFifths) {
  const std::vector<double> t = sw::nice_ticks(0.0, 1.0);
  ASSERT_EQ(t.size(), 6u);
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(t[i], 0.2 * i, 1e-12);
}

TEST(NiceTicks, AnyRangeIsCoveredByThreeToEightTicksOfOneTwoOrFiveTimesAPowerOfTen) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-9.0, 6.0), unit(-1.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    const double scale = std::pow(10.0, exponent(rng));
    double lo = unit(rng) * scale, hi = unit(rng) * scale;
    if (lo > hi) std::swap(lo, hi);
    if (!(hi - lo > 1e-6 * scale)) continue;
    const std::vector<double> t = sw::nice_ticks(lo, hi);
    ASSERT_GE(t.size(), 3u) << lo << " " << hi;
    ASSERT_LE(t.size(), 8u) << lo << " " << hi;  // span/step lies in [6/2.5, 6], plus the two covering ends
    const double step = step_of(t);
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 || std::abs(mantissa - 5) < 1e-9)
        << step;
    EXPECT_LE(t.front(), lo);
    EXPECT_GE(t.back(), hi);
    EXPECT_LT(lo - t.front(), step * (1 + 1e-9));
    EXPECT_LT(t.back() - hi, step * (1 + 1e-9));
    // Multiples of the step (0 is a tick when inside), to the rounding of front/step.
    EXPECT_NEAR(std::remainder(t.front(), step), 0.0, 1e-12 * std::max(std::abs(t.front()), step));
  }
}

TEST(NiceTicks, DegreeAxesStepInFractionsOfARightAngle) {
  const std::vector<double> half = sw::nice_ticks(-90.0, 90.0, 8, true);
  EXPECT_EQ(step_of(half), 30.0);
  EXPECT_EQ(half.front(), -90.0);
  EXPECT_EQ(half.back(), 90.0);
  EXPECT_EQ(step_of(sw::nice_ticks(-180.0, 180.0, 6, true)), 90.0);
  EXPECT_EQ(step_of(sw::nice_ticks(0.0, 360.0, 8, true)), 45.0);
  EXPECT_EQ(step_of(sw::nice_ticks(0.0, 10.0, 6, true)), 2.0);  // small angles: 1-2-5 again
  EXPECT_EQ(step_of(sw::nice_ticks(-90.0, 90.0, 8, false)), 50.0);
}

TEST(NiceTicks, AConstantGetsARangeAroundIt) {
  const std::vector<double> zero = sw::nice_ticks(0.0, 0.0);
  EXPECT_LE(zero.front(), -1.0);
  EXPECT_GE(zero.back(), 1.0);
  const std::vector<double> c = sw::nice_ticks(2e-5, 2e-5);
  EXPECT_LT(c.front(), 2e-5);
  EXPECT_GT(c.back(), 2e-5);
  EXPECT_LT(c.back() - c.front(), 1e-5);
}

TEST(SvgLinePlot, LabelsAxesWithTheirTicksAndFixedRangesEndOnThem) {
  sw::LinePlot p;
  p.x_label = "angle from the major axis (deg)";
  p.y_label = "w (µm)";
  p.x_range = {-90, 90};
  p.series = {{"FEM", {-90, 0, 90}, {-1.5, 3.5, -1.5}}};
  const std::string svg = sw::svg_line_plot(p);
  for (const char* label : {">-90<", ">-60<", ">0<", ">90<", ">-2<", ">4<", "(deg)", "w (µm)", ">FEM<"})
    EXPECT_NE(svg.find(label), std::string::npos) << label;
  EXPECT_EQ(svg.find(">-120<"), std::string::npos);  // a fixed range is not widened
}

TEST(SvgLinePlot, LogAxisLabelsDecades) {
  sw::LinePlot p;
  p.log_y = true;
  p.series = {{"spectrum", {1, 2, 3}, {1e-6, 3e-4, 2e-2}}};
  const std::string svg = sw::svg_line_plot(p);
  for (const char* label : {">1e-06<", ">1e-05<", ">0.0001<", ">0.001<", ">0.01<", ">0.1<"})
    EXPECT_NE(svg.find(label), std::string::npos) << label;
}

TEST(SvgLinePlot, LongSeriesAreThinnedButKeepTheirPeaks) {
  sw::PlotSeries s;
  for (int i = 0; i < 100000; ++i) {
    s.x.push_back(i);
    s.y.push_back(i == 54321 ? 10.0 : std::sin(i * 1e-3));
  }
  sw::LinePlot p;
  p.series = {s};
  const std::string svg = sw::svg_line_plot(p);
  EXPECT_LE(count(svg, " L"), sw::kMaxPlotPoints);
  // The one-sample peak survives: it sets the range (a tick at 10) and is drawn at the plot area's top (y = 30).
  EXPECT_NE(svg.find(">10<"), std::string::npos);
  EXPECT_NE(svg.find(",30.0"), std::string::npos);
}

TEST(SvgFigure, StacksPanelsUnderItsHeaderAndOverItsFooter) {
  sw::Figure f;
  f.header = {"title & more", "second line"};
  f.footer = {"a note"};
  f.columns = 2;
  for (int k = 0; k < 3; ++k) f.panels.push_back(sw::LinePlot{"panel " + std::to_string(k), "x (s)", "y (N)", {{"a", {0, 1}, {0, 1}}}});
  const std::string svg = sw::svg_figure(f);
  EXPECT_EQ(count(svg, "<svg"), 1u + 3u + 3u);  // the document, three panels, each panel's clipped data area
  EXPECT_NE(svg.find("title &amp; more"), std::string::npos);
  EXPECT_NE(svg.find("a note"), std::string::npos);
  EXPECT_NE(svg.find("width='1520'"), std::string::npos);  // two columns of 760
}

namespace {

/// The x of the legend's first white box (the boxes are the only rects with opacity 0.85).
double legend_x(const std::string& svg) {
  const std::size_t at = svg.rfind("<rect x='", svg.find("opacity='0.85'"));
  return std::stod(svg.substr(at + 9));
}

}  // namespace

TEST(SvgLinePlot, TheLegendGoesWhereItHidesTheLeastData) {
  // Default 760 px wide, plot area from x = 78 to 740: a legend on the right starts beyond the middle, on the left
  // at 82.
  sw::LinePlot p;
  p.series = {{"rising", {0, 1}, {0, 1}}};
  EXPECT_LT(legend_x(sw::svg_line_plot(p)), 90.0);  // the line ends in the top right corner
  p.series = {{"falling", {0, 1}, {1, 0}}};
  EXPECT_GT(legend_x(sw::svg_line_plot(p)), 400.0);  // top right is free
  // A lone marker at the top right (the largest force of a scatter) is not covered: the legend moves.
  p.series = {{"forces", {0, 0.5, 0.97, 1}, {0, 0.1, 0.95, 0}, "#000", false, true}};
  const std::string svg = sw::svg_line_plot(p);
  EXPECT_LT(legend_x(svg), 90.0);
  // Data in every corner (a force scatter with zeros along the bottom): the y range grows so the legend sits above.
  p.series = {{"forces", {0, 0.03, 0.03, 0.97, 0.97, 1}, {0, 0.03, 0.97, 0.97, 0.03, 1}, "#000", false, true}};
  const std::string roomy = sw::svg_line_plot(p);
  EXPECT_NE(roomy.find(">1.2<"), std::string::npos);
  p.y_range = {0, 1};  // a fixed range is kept
  EXPECT_EQ(sw::svg_line_plot(p).find(">1.2<"), std::string::npos);
}
