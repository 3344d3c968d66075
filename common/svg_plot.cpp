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

/// The plot's elements in a width x height box at the origin.
std::string plot_body(const LinePlot& p) {
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
  for (const auto& s : p.series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || (p.log_y && !(s.y[i] > 0))) continue;
      xlo = std::min(xlo, s.x[i]); xhi = std::max(xhi, s.x[i]);
      ylo = std::min(ylo, s.y[i]); yhi = std::max(yhi, s.y[i]);
    }
  const bool degrees = p.x_label.find("(deg)") != std::string::npos;
  const Axis ax = make_axis(xlo, xhi, p.x_range, false, degrees, 8);
  Axis ay = make_axis(ylo, yhi, p.y_range, p.log_y, false, 6);
  const double W = p.width, H = p.height, L = 78, R = 20, T = 30, B = 48;
  auto X = [&](double x) { return L + ax.unit(x) * (W - L - R); };
  auto Y = [&](double y) { return T + (1.0 - ay.unit(y)) * (H - T - B); };
  // The legend, as wide as its longest label (about 6.6 px a character at 12 px), in the corner of the plot area
  // where it hides the least data (as matplotlib's loc='best'): fewest markers and line segments under it, top right
  // first when corners tie. When every corner hides data and the y range is free, the range grows upwards by the
  // legend's height so the legend sits above the data.
  std::size_t chars = 0, entries = 0;
  for (const auto& ser : p.series) {
    std::size_t n = 0;
    for (unsigned char c : ser.label) n += (c & 0xC0) != 0x80;  // UTF-8 characters
    chars = std::max(chars, n);
    entries += !ser.label.empty();
  }
  const double lw = 44 + 6.6 * chars, lh = 16.0 * entries;
  double lx = W - R - 4 - lw, ly0 = T + 4;
  auto place_legend = [&] {
    std::size_t fewest = std::numeric_limits<std::size_t>::max();
    for (const auto& [cx, cy] : {std::pair{W - R - 4 - lw, T + 4}, std::pair{L + 4, T + 4},
                                 std::pair{W - R - 4 - lw, H - B - 4 - lh}, std::pair{L + 4, H - B - 4 - lh}}) {
      const LegendBox box{cx, cy, cx + lw, cy + lh};
      std::size_t hidden = 0;
      for (const auto& ser : p.series) {
        double px = NAN, py = NAN;
        for (std::size_t i : drawn_points(ser)) {
          const bool ok = std::isfinite(ser.x[i]) && std::isfinite(ser.y[i]) && (!p.log_y || ser.y[i] > 0);
          const double qx = ok ? X(ser.x[i]) : NAN, qy = ok ? Y(ser.y[i]) : NAN;
          if (ok && (ser.markers ? box.holds(qx, qy, ser.marker_radius) : std::isfinite(px) && box.crossed_by(px, py, qx, qy)))
            ++hidden;
          px = qx;
          py = qy;
        }
      }
      if (hidden < fewest) { fewest = hidden; lx = cx; ly0 = cy; }
    }
    return fewest;
  };
  const double area = H - T - B, room = lh + 8;
  if (entries > 0 && place_legend() > 0 && !(p.y_range.second > p.y_range.first) && !p.log_y && area > 2 * room &&
      std::isfinite(yhi)) {
    ay = make_axis(ylo, ay.lo + (std::max(yhi, ay.hi) - ay.lo) * area / (area - room), p.y_range, false, false, 6);
    place_legend();
  }
  std::ostringstream s;
  s.precision(6);
  s << "<g font-family='sans-serif' font-size='12'>\n<rect width='" << W << "' height='" << H << "' fill='white'/>\n";
  s << "<text x='" << L << "' y='18' font-size='14' font-weight='bold'>" << html_escape(p.title) << "</text>\n";
  for (const auto& [a, b] : p.x_bands) {
    const double xa = X(std::clamp(std::min(a, b), ax.lo, ax.hi)), xb = X(std::clamp(std::max(a, b), ax.lo, ax.hi));
    s << "<rect x='" << f1(xa) << "' y='" << T << "' width='" << f1(std::max(2.0, xb - xa)) << "' height='" << H - T - B
      << "' fill='#fd6' opacity='0.35'/>\n";
  }
  const double xs = ax.ticks.size() > 1 ? ax.ticks[1] - ax.ticks[0] : 1;
  for (double v : ax.ticks) {
    s << "<line x1='" << f1(X(v)) << "' y1='" << T << "' x2='" << f1(X(v)) << "' y2='" << H - B << "' stroke='#eee'/>";
    s << "<text x='" << f1(X(v)) << "' y='" << H - B + 16 << "' text-anchor='middle'>" << tick_label(v, xs) << "</text>\n";
  }
  const double ys = ay.ticks.size() > 1 ? ay.ticks[1] - ay.ticks[0] : 1;
  for (double v : ay.ticks) {
    s << "<line x1='" << L << "' y1='" << f1(Y(v)) << "' x2='" << W - R << "' y2='" << f1(Y(v)) << "' stroke='"
      << (p.zero_line && v == 0.0 ? "#000" : "#eee") << "'/>";
    s << "<text x='" << L - 6 << "' y='" << f1(Y(v) + 4) << "' text-anchor='end'>"
      << (ay.log ? decade_label(v) : tick_label(v, ys)) << "</text>\n";
  }
  s << "<rect x='" << L << "' y='" << T << "' width='" << W - L - R << "' height='" << H - T - B
    << "' fill='none' stroke='#333'/>\n";
  s << "<text x='" << (L + W - R) / 2 << "' y='" << H - 12 << "' text-anchor='middle'>" << html_escape(p.x_label)
    << "</text>\n";
  s << "<text transform='translate(16," << (T + H - B) / 2 << ") rotate(-90)' text-anchor='middle'>"
    << html_escape(p.y_label) << "</text>\n";
  // The data, clipped to the plot area by an inner viewport with the same coordinates.
  s << "<svg x='" << L << "' y='" << T << "' width='" << W - L - R << "' height='" << H - T - B << "' viewBox='" << L
    << " " << T << " " << W - L - R << " " << H - T - B << "'>\n";
  for (double v : p.x_marks)
    if (v >= ax.lo && v <= ax.hi)
      s << "<line x1='" << f1(X(v)) << "' y1='" << T << "' x2='" << f1(X(v)) << "' y2='" << H - B
        << "' stroke='#555' stroke-dasharray='4,4'/>\n";
  for (const auto& ser : p.series) {
    const std::vector<std::size_t> idx = drawn_points(ser);
    if (idx.empty()) continue;  // a legend entry only
    auto drawable = [&](std::size_t i) { return std::isfinite(ser.x[i]) && std::isfinite(ser.y[i]) && (!p.log_y || ser.y[i] > 0); };
    if (ser.markers) {
      for (std::size_t i : idx)
        if (drawable(i))
          s << "<circle cx='" << f1(X(ser.x[i])) << "' cy='" << f1(Y(ser.y[i])) << "' r='" << ser.marker_radius
            << "' fill='" << ser.colour << "'" << (ser.opacity < 1 ? " opacity='" + std::to_string(ser.opacity) + "'" : "")
            << "/>";
      s << "\n";
      continue;
    }
    std::string d;
    bool pen = false;
    for (std::size_t i : idx) {
      if (!drawable(i)) { pen = false; continue; }
      d += (pen ? " L" : " M") + f1(X(ser.x[i])) + "," + f1(Y(ser.y[i]));
      pen = true;
    }
    s << "<path d='" << d << "' fill='none' stroke='" << ser.colour << "' stroke-width='" << ser.line_width << "'"
      << (ser.dashed ? " stroke-dasharray='6,4'" : "")
      << (ser.opacity < 1 ? " opacity='" + std::to_string(ser.opacity) + "'" : "") << "/>\n";
  }
  s << "</svg>\n";
  int legend = 0;
  for (const auto& ser : p.series) {
    if (ser.label.empty()) continue;
    const double ly = ly0 + 10 + 16 * legend++;
    s << "<rect x='" << f1(lx) << "' y='" << ly - 10 << "' width='" << f1(lw) << "' height='16' fill='white' "
      << "opacity='0.85'/>";
    if (ser.markers)
      s << "<circle cx='" << f1(lx + 21) << "' cy='" << ly << "' r='3' fill='" << ser.colour << "'/>";
    else
      s << "<line x1='" << f1(lx + 6) << "' y1='" << ly << "' x2='" << f1(lx + 36) << "' y2='" << ly << "' stroke='"
        << ser.colour << "' stroke-width='2'" << (ser.dashed ? " stroke-dasharray='6,4'" : "") << "/>";
    s << "<text x='" << f1(lx + 42) << "' y='" << ly + 4 << "'>" << html_escape(ser.label) << "</text>\n";
  }
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
