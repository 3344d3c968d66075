#include "io/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace sw {

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) { const double d = std::max(std::abs(lo) * 0.1, 1e-12); lo -= d; hi += d; }
  const double raw = (hi - lo) / std::max(target, 1);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double f : {1.0, 2.0, 5.0, 10.0})
    if (f * mag >= raw) { step = f * mag; break; }
  std::vector<double> t;
  for (double v = std::floor(lo / step) * step; v <= hi + 1e-9 * step; v += step) t.push_back(std::abs(v) < 1e-12 * step ? 0.0 : v);
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
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 6), v);
  return buf;
}

}  // namespace

std::string svg_line_plot(const LinePlot& p) {
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
  for (const auto& s : p.series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xlo = std::min(xlo, s.x[i]); xhi = std::max(xhi, s.x[i]);
      ylo = std::min(ylo, s.y[i]); yhi = std::max(yhi, s.y[i]);
    }
  if (!std::isfinite(xlo)) { xlo = 0; xhi = 1; ylo = 0; yhi = 1; }
  const std::vector<double> xt = nice_ticks(xlo, xhi), yt = nice_ticks(ylo, yhi);
  xlo = std::min(xlo, xt.front()); xhi = std::max(xhi, xt.back());
  ylo = std::min(ylo, yt.front()); yhi = std::max(yhi, yt.back());
  const double W = p.width, H = p.height, L = 78, R = 20, T = 36, B = 52;
  auto X = [&](double x) { return L + (x - xlo) / (xhi - xlo) * (W - L - R); };
  auto Y = [&](double y) { return T + (yhi - y) / (yhi - ylo) * (H - T - B); };
  std::ostringstream s;
  s.precision(6);
  s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H << "' viewBox='0 0 " << W << " "
    << H << "' font-family='sans-serif' font-size='12'>\n<rect width='100%' height='100%' fill='white'/>\n";
  s << "<text x='" << W / 2 << "' y='20' text-anchor='middle' font-size='14'>" << html_escape(p.title) << "</text>\n";
  const double xs = xt.size() > 1 ? xt[1] - xt[0] : 1, ys = yt.size() > 1 ? yt[1] - yt[0] : 1;
  for (double v : xt) {
    s << "<line x1='" << X(v) << "' y1='" << T << "' x2='" << X(v) << "' y2='" << H - B << "' stroke='#eee'/>";
    s << "<text x='" << X(v) << "' y='" << H - B + 16 << "' text-anchor='middle'>" << tick_label(v, xs) << "</text>\n";
  }
  for (double v : yt) {
    s << "<line x1='" << L << "' y1='" << Y(v) << "' x2='" << W - R << "' y2='" << Y(v) << "' stroke='"
      << (p.zero_line && v == 0.0 ? "#000" : "#eee") << "'/>";
    s << "<text x='" << L - 6 << "' y='" << Y(v) + 4 << "' text-anchor='end'>" << tick_label(v, ys) << "</text>\n";
  }
  s << "<rect x='" << L << "' y='" << T << "' width='" << W - L - R << "' height='" << H - T - B
    << "' fill='none' stroke='#333'/>\n";
  s << "<text x='" << (L + W - R) / 2 << "' y='" << H - 14 << "' text-anchor='middle'>" << html_escape(p.x_label)
    << "</text>\n";
  s << "<text transform='translate(16," << (T + H - B) / 2 << ") rotate(-90)' text-anchor='middle'>"
    << html_escape(p.y_label) << "</text>\n";
  int legend = 0;
  for (const auto& ser : p.series) {
    if (ser.markers) {
      for (size_t i = 0; i < ser.x.size() && i < ser.y.size(); ++i)
        if (std::isfinite(ser.y[i]))
          s << "<circle cx='" << X(ser.x[i]) << "' cy='" << Y(ser.y[i]) << "' r='2.5' fill='" << ser.colour << "'/>";
    } else {
      std::string d;
      bool pen = false;
      for (size_t i = 0; i < ser.x.size() && i < ser.y.size(); ++i) {
        if (!std::isfinite(ser.y[i])) { pen = false; continue; }
        char buf[64];
        std::snprintf(buf, sizeof buf, "%s%.2f,%.2f", pen ? " L" : " M", X(ser.x[i]), Y(ser.y[i]));
        d += buf;
        pen = true;
      }
      s << "<path d='" << d << "' fill='none' stroke='" << ser.colour << "' stroke-width='1.8'"
        << (ser.dashed ? " stroke-dasharray='6,4'" : "") << "/>";
    }
    const double ly = T + 14 + 16 * legend++;
    s << "\n<line x1='" << W - R - 230 << "' y1='" << ly << "' x2='" << W - R - 200 << "' y2='" << ly << "' stroke='"
      << ser.colour << "' stroke-width='2'" << (ser.dashed ? " stroke-dasharray='6,4'" : "") << "/><text x='"
      << W - R - 194 << "' y='" << ly + 4 << "'>" << html_escape(ser.label) << "</text>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace sw
