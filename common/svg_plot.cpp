#include "common/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace sw {

std::vector<double> nice_ticks(double lo, double hi, int target, bool degrees) {
  if (!(hi > lo)) { const double d = lo != 0.0 ? std::abs(lo) * 0.1 : 1.0; lo -= d; hi += d; }  // a constant
  const double raw = (hi - lo) / std::max(target, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10.0 * mag;
  for (double f : {1.0, 2.0, 5.0, 10.0})
    if (f * mag >= raw) { step = f * mag; break; }
  if (degrees && raw > 7.5) {
    // Angles read best in fractions of a right angle.
    for (double s : {15.0, 30.0, 45.0, 90.0, 180.0, 360.0})
      if (s >= raw) { step = s; break; }
  }
  std::vector<double> t;
  for (double v = std::floor(lo / step + 1e-9) * step; v <= hi + 1e-9 * step; v += step)
    t.push_back(std::abs(v) < 1e-9 * step ? 0.0 : v);
  if (t.back() < hi - 1e-9 * step) t.push_back(t.back() + step);
  return t;
}

std::string html_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

namespace {

std::string tick_label(double v, double step) {
  char buf[32];
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  if (decimals > 5 || std::abs(v) >= 1e6) std::snprintf(buf, sizeof buf, "%.3g", v);  // tiny or huge: 2e-06, 3e+07
  else std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string decade_label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);  // 1e-06 ... 0.0001 ... 1000 ... 1e+06
  return buf;
}

std::string f1(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

/// An axis: its drawn range and ticks, linear or in decades.
struct Axis {
  double lo = 0, hi = 1;
  std::vector<double> ticks;
  bool log = false;
  double at(double v) const { return log ? std::log10(v) : v; }
  double unit(double v) const { return (at(v) - at(lo)) / (at(hi) - at(lo)); }  // 0 at lo, 1 at hi
};

Axis make_axis(double data_lo, double data_hi, std::pair<double, double> fixed, bool log, bool degrees, int target) {
  Axis a;
  a.log = log;
  const bool is_fixed = fixed.second > fixed.first && (!log || fixed.first > 0);
  if (log) {
    const double lo = is_fixed ? fixed.first : data_lo, hi = is_fixed ? fixed.second : data_hi;
    const int e0 = std::isfinite(lo) && lo > 0 ? static_cast<int>(std::floor(std::log10(lo) + 1e-9)) : 0;
    const int e1 = std::isfinite(hi) && hi > 0 ? std::max(e0 + 1, static_cast<int>(std::ceil(std::log10(hi) - 1e-9))) : e0 + 1;
    a.lo = is_fixed ? lo : std::pow(10.0, e0);
    a.hi = is_fixed ? hi : std::pow(10.0, e1);
    for (int e = e0; e <= e1; ++e)
      if (std::pow(10.0, e) >= a.lo * (1 - 1e-9) && std::pow(10.0, e) <= a.hi * (1 + 1e-9)) a.ticks.push_back(std::pow(10.0, e));
    return a;
  }
  if (is_fixed) {
    a.lo = fixed.first;
    a.hi = fixed.second;
    for (double v : nice_ticks(a.lo, a.hi, target, degrees))
      if (v >= a.lo - 1e-9 * (a.hi - a.lo) && v <= a.hi + 1e-9 * (a.hi - a.lo)) a.ticks.push_back(v);
    return a;
  }
  if (!std::isfinite(data_lo)) { data_lo = 0; data_hi = 1; }
  a.ticks = nice_ticks(data_lo, data_hi, target, degrees);
  a.lo = std::min(data_lo, a.ticks.front());
  a.hi = std::max(data_hi, a.ticks.back());
  return a;
}

/// Indices of a series to draw: all of a short one; of a long one, each bucket's lowest and highest point (lines) or
/// every k-th point (markers). A NaN that breaks a line is kept.
std::vector<std::size_t> drawn_points(const PlotSeries& s) {
  const std::size_t n = std::min(s.x.size(), s.y.size());
  std::vector<std::size_t> idx;
  if (n <= kMaxPlotPoints) {
    for (std::size_t i = 0; i < n; ++i) idx.push_back(i);
    return idx;
  }
  if (s.markers) {
    const std::size_t stride = (n + kMaxPlotPoints - 1) / kMaxPlotPoints;
    for (std::size_t i = 0; i < n; i += stride) idx.push_back(i);
    return idx;
  }
  const std::size_t per = (n + kMaxPlotPoints / 2 - 1) / (kMaxPlotPoints / 2);
  for (std::size_t b = 0; b < n; b += per) {
    const std::size_t end = std::min(n, b + per);
    std::size_t lo = end, hi = end, gap = end;
    for (std::size_t j = b; j < end; ++j) {
      if (!std::isfinite(s.y[j])) { gap = std::min(gap, j); continue; }
      if (lo == end || s.y[j] < s.y[lo]) lo = j;
      if (hi == end || s.y[j] > s.y[hi]) hi = j;
    }
    std::vector<std::size_t> pick;
    for (std::size_t j : {lo, hi, gap})
      if (j < end) pick.push_back(j);
    std::sort(pick.begin(), pick.end());
    pick.erase(std::unique(pick.begin(), pick.end()), pick.end());
    idx.insert(idx.end(), pick.begin(), pick.end());
  }
  return idx;
}

/// A legend's rectangle in drawing coordinates: whether a marker lies under it or a line segment crosses it.
struct LegendBox {
  double x0, y0, x1, y1;
  bool holds(double x, double y, double radius) const {
    return x >= x0 - radius && x <= x1 + radius && y >= y0 - radius && y <= y1 + radius;
  }
  /// Liang-Barsky: the part of the segment inside the box is not empty.
  bool crossed_by(double ax, double ay, double bx, double by) const {
    double t0 = 0, t1 = 1;
    const double dx = bx - ax, dy = by - ay;
    for (const auto& [q, r] : {std::pair{-dx, ax - x0}, std::pair{dx, x1 - ax}, std::pair{-dy, ay - y0},
                               std::pair{dy, y1 - ay}}) {
      if (q == 0) {
        if (r < 0) return false;
        continue;
      }
      const double t = r / q;
      if (q < 0) t0 = std::max(t0, t);
      else t1 = std::min(t1, t);
      if (t0 > t1) return false;
    }
    return true;
  }
};

/// A point is drawn where both coordinates are finite (and y positive on a log axis).
bool drawable(const LinePlot& p, double x, double y) {
  return std::isfinite(x) && std::isfinite(y) && (!p.log_y || y > 0);
}

/// The drawable data's extent; infinite (lo > hi) when there is none.
struct Extent {
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
};

Extent data_extent(const LinePlot& p) {
  Extent e;
  for (const auto& s : p.series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!drawable(p, s.x[i], s.y[i])) continue;
      e.xlo = std::min(e.xlo, s.x[i]); e.xhi = std::max(e.xhi, s.x[i]);
      e.ylo = std::min(e.ylo, s.y[i]); e.yhi = std::max(e.yhi, s.y[i]);
    }
  return e;
}

/// The plot area in a width x height box (margins for the title, ticks and labels) and the map of data onto it.
struct Frame {
  double W = 0, H = 0, L = 78, R = 20, T = 30, B = 48;
  Axis ax, ay;
  double X(double x) const { return L + ax.unit(x) * (W - L - R); }
  double Y(double y) const { return T + (1.0 - ay.unit(y)) * (H - T - B); }
};

/// The legend: as wide as its longest label (about 6.6 px a character at 12 px), 16 px a labelled series, its top left
/// corner at (x, y).
struct Legend {
  std::size_t entries = 0;
  double width = 0, height = 0, x = 0, y = 0;
};

Legend legend_size(const LinePlot& p) {
  std::size_t chars = 0;
  Legend l;
  for (const auto& ser : p.series) {
    std::size_t n = 0;
    for (unsigned char c : ser.label) n += (c & 0xC0) != 0x80;  // UTF-8 characters
    chars = std::max(chars, n);
    l.entries += !ser.label.empty();
  }
  l.width = 44 + 6.6 * chars;
  l.height = 16.0 * l.entries;
  return l;
}

/// How many markers lie under the box and line segments cross it.
std::size_t data_hidden_by(const LinePlot& p, const Frame& f, const LegendBox& box) {
  std::size_t hidden = 0;
  for (const auto& ser : p.series) {
    double px = NAN, py = NAN;
    for (std::size_t i : drawn_points(ser)) {
      const bool ok = drawable(p, ser.x[i], ser.y[i]);
      const double qx = ok ? f.X(ser.x[i]) : NAN, qy = ok ? f.Y(ser.y[i]) : NAN;
      const bool under = ser.markers ? box.holds(qx, qy, ser.marker_radius)
                                     : std::isfinite(px) && box.crossed_by(px, py, qx, qy);
      if (ok && under) ++hidden;
      px = qx;
      py = qy;
    }
  }
  return hidden;
}

/// Puts the legend in the corner of the plot area where it hides the least data (as matplotlib's loc='best'), top
/// right first when corners tie. Returns how much data it hides there.
std::size_t place_legend(const LinePlot& p, const Frame& f, Legend& l) {
  std::size_t fewest = std::numeric_limits<std::size_t>::max();
  const double right = f.W - f.R - 4 - l.width, left = f.L + 4, top = f.T + 4, bottom = f.H - f.B - 4 - l.height;
  for (const auto& [cx, cy] : {std::pair{right, top}, std::pair{left, top}, std::pair{right, bottom},
                               std::pair{left, bottom}}) {
    const std::size_t hidden = data_hidden_by(p, f, LegendBox{cx, cy, cx + l.width, cy + l.height});
    if (hidden < fewest) { fewest = hidden; l.x = cx; l.y = cy; }
  }
  return fewest;
}

/// The axes over the data's extent (or the fixed ranges) and the legend's place. When every corner hides data and
/// the y range is free, the range grows upwards by the legend's height so the legend sits above the data.
Frame frame_and_legend(const LinePlot& p, Legend& legend) {
  const Extent e = data_extent(p);
  Frame f;
  f.W = p.width;
  f.H = p.height;
  const bool degrees = p.x_label.find("(deg)") != std::string::npos;
  f.ax = make_axis(e.xlo, e.xhi, p.x_range, false, degrees, 8);
  f.ay = make_axis(e.ylo, e.yhi, p.y_range, p.log_y, false, 6);
  legend.x = f.W - f.R - 4 - legend.width;
  legend.y = f.T + 4;
  const double area = f.H - f.T - f.B, room = legend.height + 8;
  if (legend.entries > 0 && place_legend(p, f, legend) > 0 && !(p.y_range.second > p.y_range.first) && !p.log_y &&
      area > 2 * room && std::isfinite(e.yhi)) {
    f.ay = make_axis(e.ylo, f.ay.lo + (std::max(e.yhi, f.ay.hi) - f.ay.lo) * area / (area - room), p.y_range, false,
                     false, 6);
    place_legend(p, f, legend);
  }
  return f;
}

std::string opacity_attribute(double opacity) {
  return opacity < 1 ? " opacity='" + std::to_string(opacity) + "'" : "";
}

/// Title, shaded bands, grid lines with tick labels, the plot area's border and the axis labels.
void draw_axes(std::ostream& s, const LinePlot& p, const Frame& f) {
  const double W = f.W, H = f.H, L = f.L, R = f.R, T = f.T, B = f.B;
  s << "<text x='" << L << "' y='18' font-size='14' font-weight='bold'>" << html_escape(p.title) << "</text>\n";
  for (const auto& [a, b] : p.x_bands) {
    const double xa = f.X(std::clamp(std::min(a, b), f.ax.lo, f.ax.hi));
    const double xb = f.X(std::clamp(std::max(a, b), f.ax.lo, f.ax.hi));
    s << "<rect x='" << f1(xa) << "' y='" << T << "' width='" << f1(std::max(2.0, xb - xa)) << "' height='" << H - T - B
      << "' fill='#fd6' opacity='0.35'/>\n";
  }
  const double xs = f.ax.ticks.size() > 1 ? f.ax.ticks[1] - f.ax.ticks[0] : 1;
  for (double v : f.ax.ticks) {
    s << "<line x1='" << f1(f.X(v)) << "' y1='" << T << "' x2='" << f1(f.X(v)) << "' y2='" << H - B
      << "' stroke='#eee'/>";
    s << "<text x='" << f1(f.X(v)) << "' y='" << H - B + 16 << "' text-anchor='middle'>" << tick_label(v, xs)
      << "</text>\n";
  }
  const double ys = f.ay.ticks.size() > 1 ? f.ay.ticks[1] - f.ay.ticks[0] : 1;
  for (double v : f.ay.ticks) {
    s << "<line x1='" << L << "' y1='" << f1(f.Y(v)) << "' x2='" << W - R << "' y2='" << f1(f.Y(v)) << "' stroke='"
      << (p.zero_line && v == 0.0 ? "#000" : "#eee") << "'/>";
    s << "<text x='" << L - 6 << "' y='" << f1(f.Y(v) + 4) << "' text-anchor='end'>"
      << (f.ay.log ? decade_label(v) : tick_label(v, ys)) << "</text>\n";
  }
  s << "<rect x='" << L << "' y='" << T << "' width='" << W - L - R << "' height='" << H - T - B
    << "' fill='none' stroke='#333'/>\n";
  s << "<text x='" << (L + W - R) / 2 << "' y='" << H - 12 << "' text-anchor='middle'>" << html_escape(p.x_label)
    << "</text>\n";
  s << "<text transform='translate(16," << (T + H - B) / 2 << ") rotate(-90)' text-anchor='middle'>"
    << html_escape(p.y_label) << "</text>\n";
}

/// One series: a dot per point, or a path broken where a point is not drawable.
void draw_series(std::ostream& s, const LinePlot& p, const Frame& f, const PlotSeries& ser) {
  const std::vector<std::size_t> idx = drawn_points(ser);
  if (idx.empty()) return;  // a legend entry only
  if (ser.markers) {
    for (std::size_t i : idx)
      if (drawable(p, ser.x[i], ser.y[i]))
        s << "<circle cx='" << f1(f.X(ser.x[i])) << "' cy='" << f1(f.Y(ser.y[i])) << "' r='" << ser.marker_radius
          << "' fill='" << ser.colour << "'" << opacity_attribute(ser.opacity) << "/>";
    s << "\n";
    return;
  }
  std::string d;
  bool pen = false;
  for (std::size_t i : idx) {
    if (!drawable(p, ser.x[i], ser.y[i])) { pen = false; continue; }
    d += (pen ? " L" : " M") + f1(f.X(ser.x[i])) + "," + f1(f.Y(ser.y[i]));
    pen = true;
  }
  s << "<path d='" << d << "' fill='none' stroke='" << ser.colour << "' stroke-width='" << ser.line_width << "'"
    << (ser.dashed ? " stroke-dasharray='6,4'" : "") << opacity_attribute(ser.opacity) << "/>\n";
}

/// The data and the marker lines, clipped to the plot area by an inner viewport with the same coordinates.
void draw_data(std::ostream& s, const LinePlot& p, const Frame& f) {
  const double W = f.W, H = f.H, L = f.L, R = f.R, T = f.T, B = f.B;
  s << "<svg x='" << L << "' y='" << T << "' width='" << W - L - R << "' height='" << H - T - B << "' viewBox='" << L
    << " " << T << " " << W - L - R << " " << H - T - B << "'>\n";
  for (double v : p.x_marks)
    if (v >= f.ax.lo && v <= f.ax.hi)
      s << "<line x1='" << f1(f.X(v)) << "' y1='" << T << "' x2='" << f1(f.X(v)) << "' y2='" << H - B
        << "' stroke='#555' stroke-dasharray='4,4'/>\n";
  for (const auto& ser : p.series) draw_series(s, p, f, ser);
  s << "</svg>\n";
}

void draw_legend(std::ostream& s, const LinePlot& p, const Legend& l) {
  int row = 0;
  for (const auto& ser : p.series) {
    if (ser.label.empty()) continue;
    const double ly = l.y + 10 + 16 * row++;
    s << "<rect x='" << f1(l.x) << "' y='" << ly - 10 << "' width='" << f1(l.width) << "' height='16' fill='white' "
      << "opacity='0.85'/>";
    if (ser.markers)
      s << "<circle cx='" << f1(l.x + 21) << "' cy='" << ly << "' r='3' fill='" << ser.colour << "'/>";
    else
      s << "<line x1='" << f1(l.x + 6) << "' y1='" << ly << "' x2='" << f1(l.x + 36) << "' y2='" << ly << "' stroke='"
        << ser.colour << "' stroke-width='2'" << (ser.dashed ? " stroke-dasharray='6,4'" : "") << "/>";
    s << "<text x='" << f1(l.x + 42) << "' y='" << ly + 4 << "'>" << html_escape(ser.label) << "</text>\n";
  }
}

/// The plot's elements in a width x height box at the origin.
std::string plot_body(const LinePlot& p) {
  Legend legend = legend_size(p);
  const Frame f = frame_and_legend(p, legend);
  std::ostringstream s;
  s.precision(6);
  s << "<g font-family='sans-serif' font-size='12'>\n<rect width='" << f.W << "' height='" << f.H
    << "' fill='white'/>\n";
  draw_axes(s, p, f);
  draw_data(s, p, f);
  draw_legend(s, p, legend);
  s << "</g>\n";
  return s.str();
}

}  // namespace

std::string svg_line_plot(const LinePlot& p) {
  std::ostringstream s;
  s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << p.width << "' height='" << p.height << "' viewBox='0 0 "
    << p.width << " " << p.height << "'>\n" << plot_body(p) << "</svg>\n";
  return s.str();
}

std::string svg_figure(const Figure& f) {
  const int columns = std::max(1, f.columns);
  const double line = 17, top = f.header.empty() ? 8 : 14 + line * f.header.size();
  double width = 0, height = 0;
  std::vector<double> row_height((f.panels.size() + columns - 1) / columns, 0.0), col_width(columns, 0.0);
  for (std::size_t k = 0; k < f.panels.size(); ++k) {
    row_height[k / columns] = std::max(row_height[k / columns], f.panels[k].height);
    col_width[k % columns] = std::max(col_width[k % columns], f.panels[k].width);
  }
  for (double w : col_width) width += w;
  for (double h : row_height) height += h;
  const double total_height = top + height + (f.footer.empty() ? 8 : 10 + line * f.footer.size());
  std::ostringstream s;
  s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='" << total_height << "' viewBox='0 0 "
    << width << " " << total_height << "' font-family='sans-serif'>\n<rect width='100%' height='100%' fill='white'/>\n";
  for (std::size_t i = 0; i < f.header.size(); ++i)
    s << "<text x='12' y='" << 20 + line * i << "' font-size='" << (i == 0 ? 15 : 12) << "'"
      << (i == 0 ? " font-weight='bold'" : "") << ">" << html_escape(f.header[i]) << "</text>\n";
  double y = top;
  for (std::size_t r = 0; r < row_height.size(); ++r) {
    double x = 0;
    for (int c = 0; c < columns && r * columns + c < f.panels.size(); ++c) {
      const LinePlot& p = f.panels[r * columns + c];
      s << "<svg x='" << x << "' y='" << y << "' width='" << p.width << "' height='" << p.height << "' viewBox='0 0 "
        << p.width << " " << p.height << "'>\n" << plot_body(p) << "</svg>\n";
      x += col_width[c];
    }
    y += row_height[r];
  }
  for (std::size_t i = 0; i < f.footer.size(); ++i)
    s << "<text x='12' y='" << y + 18 + line * i << "' font-size='12' fill='#555'>" << html_escape(f.footer[i])
      << "</text>\n";
  s << "</svg>\n";
  return s.str();
}

}  // namespace sw
