#pragma once
// One small SVG line-plot helper for the reports people open: nice tick values (1-2-5 steps), axis labels with units,
// a legend, self-contained SVG text (no scripts, no network). Used by the run report (io/report.hpp).
#include <string>
#include <vector>

namespace sw {

struct PlotSeries {
  std::string label;
  std::vector<double> x, y;   ///< same length; NaN in y breaks the line
  std::string colour = "#1f77b4";
  bool dashed = false;
  bool markers = false;       ///< draw a dot at each point instead of a line
};

struct LinePlot {
  std::string title;
  std::string x_label, y_label;  ///< with units, e.g. "angle from the major axis (deg)"
  std::vector<PlotSeries> series;
  double width = 760, height = 380;
  bool zero_line = true;         ///< a black line at y = 0 when it is inside the range
};

/// Tick values with a 1-2-5 step covering [lo, hi] with about `target` intervals.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

/// The plot as an <svg> element (inline in HTML or written as a .svg file).
std::string svg_line_plot(const LinePlot& plot);

/// Escapes &, <, > and quotes for HTML/SVG text.
std::string html_escape(const std::string& text);

}  // namespace sw
