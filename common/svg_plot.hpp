#pragma once
// The one SVG plotting helper of the tool's pages and figures (report.html, backlash.svg, contact.svg, dynamics.svg,
// reconcile.html, sweep.svg): nice tick values (1-2-5 steps; 15/30/45/90 on axes in degrees), axis labels with units,
// a legend, shaded ranges and marker lines, log axes, long series thinned so a page stays small; self-contained SVG
// text (no scripts, no network). Part of sw::common, the floor below every stage, so every stage can draw without
// linking another.
#include <string>
#include <utility>
#include <vector>

namespace sw {

struct PlotSeries {
  std::string label;          ///< legend text; empty: no legend entry
  std::vector<double> x, y;   ///< same length; NaN in y breaks the line
  std::string colour = "#1f77b4";
  bool dashed = false;
  bool markers = false;       ///< a dot at each point instead of a line
  double line_width = 1.8;
  double marker_radius = 2.5;
  double opacity = 1.0;       ///< below 1 for dense scatter (a recording's samples)
};

struct LinePlot {
  std::string title;
  std::string x_label, y_label;  ///< with units, e.g. "angle from the major axis (deg)": "(deg)" selects angle ticks
  std::vector<PlotSeries> series;
  double width = 760, height = 380;
  bool zero_line = true;         ///< a black line at y = 0 when it is inside the range
  /// Fixed axis ranges (lo < hi); otherwise the data's range widened to the enclosing ticks.
  std::pair<double, double> x_range{0, 0}, y_range{0, 0};
  bool log_y = false;            ///< decades on y (values <= 0 are left out)
  std::vector<std::pair<double, double>> x_bands;  ///< shaded x ranges (e.g. where a mismatch is located)
  std::vector<double> x_marks;   ///< dashed vertical lines (e.g. a frequency and its harmonics)
};

/// Plots stacked in one SVG document (in `columns` columns), under header lines and over footer lines of plain text.
struct Figure {
  std::vector<std::string> header, footer;  ///< the first header line is the figure's title
  std::vector<LinePlot> panels;
  int columns = 1;
};

/// Tick values covering [lo, hi] with about `target` intervals: steps of 1, 2 or 5 times a power of ten, or with
/// `degrees` 15, 30, 45, 90 or 180 where those fit better. Ticks may extend beyond [lo, hi] by less than a step.
std::vector<double> nice_ticks(double lo, double hi, int target = 6, bool degrees = false);

/// The plot as an <svg> element (inline in HTML or written as a .svg file).
std::string svg_line_plot(const LinePlot& plot);

/// The figure as an <svg> document.
std::string svg_figure(const Figure& figure);

/// Escapes &, <, > and quotes for HTML/SVG text.
std::string html_escape(const std::string& text);

/// Series longer than this are thinned for drawing: lines keep each bucket's extremes (narrow peaks survive),
/// markers every k-th point.
inline constexpr std::size_t kMaxPlotPoints = 2000;

}  // namespace sw
