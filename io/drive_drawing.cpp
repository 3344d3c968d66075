#include "io/drive_drawing.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <vector>

#include <Eigen/Core>

#include "common/constants.hpp"
#include "common/svg_plot.hpp"
#include "gear/tooth_profile.hpp"

namespace sw {
namespace {

constexpr int kFlankPoints = 6;     // segments per flank: the teeth read as teeth at the enlarged views' scale
constexpr int kCirclePoints = 360;  // the rings' curves, every degree

using Point = Eigen::Vector2d;
using Polygon = std::vector<Point>;

/// The point of the flexspline's section at radius R at rest and material angle φ, moved by the generator as the
/// neutral curve moves (radially by w, along the rim by v): the bore and the generator's rings follow the rim.
Point deformed(const NeutralCurve& c, double phi_rad, double radius_m) {
  const NeutralPoint p = c.at(phi_rad);
  const double r = radius_m + p.w_m, a = phi_rad + p.v_m / c.mean_radius_m;
  return {r * std::cos(a), r * std::sin(a)};
}

Polygon deformed_circle(const NeutralCurve& c, double radius_m) {
  Polygon out;
  for (int i = 0; i < kCirclePoints; ++i) out.push_back(deformed(c, 2 * kPi * i / kCirclePoints, radius_m));
  return out;
}

Polygon circle(double radius_m, Point centre = {0, 0}, int points = kCirclePoints) {
  Polygon out;
  for (int i = 0; i < points; ++i) {
    const double a = 2 * kPi * i / points;
    out.push_back(centre + radius_m * Point(std::cos(a), std::sin(a)));
  }
  return out;
}

/// The flexspline's toothed outside at generator angle 0: each tooth's cw flank up, its tip, its ccw flank down, the
/// root lands between teeth as straight lines (as the backlash model places the teeth).
Polygon flexspline_outline(const BacklashModel& m) {
  const Involute& f = m.flank_f;
  Polygon tooth;
  for (int i = 0; i <= kFlankPoints; ++i) {
    const Point q = involute_point(f, f.u_min + (f.u_max - f.u_min) * i / kFlankPoints);
    tooth.emplace_back(q.x(), -q.y());
  }
  for (int i = kFlankPoints; i >= 0; --i) tooth.push_back(involute_point(f, f.u_min + (f.u_max - f.u_min) * i / kFlankPoints));
  Polygon out;
  for (int k = 0; k < m.gear.teeth_flexspline; ++k) {
    const ToothPlacement t = place_tooth(m.curve, tooth_material_angle(m.gear, k, 0.0), 0.0);
    const double c = std::cos(t.angle_rad), s = std::sin(t.angle_rad);
    for (const Point& q : tooth) out.emplace_back(c * q.x() - s * q.y() + t.offset_m.x(), s * q.x() + c * q.y() + t.offset_m.y());
  }
  return out;
}

/// The circular spline's toothed inside: each space's cw side from the tip circle out to the form circle and its ccw
/// side back in; the tip lands between spaces as straight lines.
Polygon circular_outline(const BacklashModel& m) {
  const Involute& f = m.flank_c;
  Polygon out;
  for (int j = 0; j < m.gear.teeth_circular; ++j) {
    const double a = 2 * kPi * j / m.gear.teeth_circular, c = std::cos(a), s = std::sin(a);
    for (int i = 0; i <= kFlankPoints; ++i) {
      const Point q = involute_point(f, f.u_min + (f.u_max - f.u_min) * i / kFlankPoints);
      out.emplace_back(c * q.x() + s * q.y(), s * q.x() - c * q.y());
    }
    for (int i = kFlankPoints; i >= 0; --i) {
      const Point q = involute_point(f, f.u_min + (f.u_max - f.u_min) * i / kFlankPoints);
      out.emplace_back(c * q.x() - s * q.y(), s * q.x() + c * q.y());
    }
  }
  return out;
}

/// A closed sub-path in whole micrometres (a tenth of a pixel in the enlarged views), y down as SVG's: the first point
/// absolute, the rest as steps between the rounded points (so the steps add up to each rounded point exactly).
std::string sub_path(const Polygon& p) {
  std::string out;
  char buf[48];
  long x0 = 0, y0 = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const long x = std::lround(p[i].x() * 1e6), y = std::lround(-p[i].y() * 1e6);
    std::snprintf(buf, sizeof buf, i == 0 ? "M%ld %ld" : "l%ld %ld", x - x0, y - y0);
    out += buf;
    x0 = x;
    y0 = y;
  }
  return out + "Z";
}

/// A filled region between closed curves (even-odd: a ring between an outside and an inside).
std::string region(const std::vector<Polygon>& curves, const char* fill, const char* id = nullptr) {
  std::string d;
  for (const Polygon& p : curves) d += sub_path(p);
  std::string out = "<path";
  if (id) out += std::string(" id=\"") + id + "\"";
  return out + " d=\"" + d + "\" fill=\"" + fill +
         "\" fill-rule=\"evenodd\" stroke=\"#222\" stroke-width=\"0.8\" vector-effect=\"non-scaling-stroke\"/>\n";
}

struct View {
  double x, y, width, height;  ///< the panel on the page, px
  Point centre_m;              ///< the model point at the panel's centre
  double px_per_m;
  double rotate_deg = 0;       ///< the model turned on the page (−90: the major axis's outward direction up)
};

/// The model's drawing placed in a panel, clipped to it, with a frame, a title and a scale bar of `bar_m`.
std::string view(const View& v, const std::string& id, const std::string& title, double bar_m, const char* bar_label) {
  std::ostringstream o;
  const double s = v.px_per_m * 1e-6;  // px per µm
  o << "<clipPath id=\"clip-" << id << "\"><rect x=\"" << v.x << "\" y=\"" << v.y << "\" width=\"" << v.width
    << "\" height=\"" << v.height << "\"/></clipPath>\n";
  o << "<g clip-path=\"url(#clip-" << id << ")\"><g transform=\"translate(" << v.x + v.width / 2 << " "
    << v.y + v.height / 2 << ") rotate(" << v.rotate_deg << ") scale(" << s << ") translate(" << -v.centre_m.x() * 1e6
    << " " << v.centre_m.y() * 1e6 << ")\"><use href=\"#drive\"/></g></g>\n";
  o << "<rect x=\"" << v.x << "\" y=\"" << v.y << "\" width=\"" << v.width << "\" height=\"" << v.height
    << "\" fill=\"none\" stroke=\"#888\"/>\n";
  o << "<text x=\"" << v.x + 8 << "\" y=\"" << v.y + 18 << "\" font-size=\"13\">" << html_escape(title) << "</text>\n";
  const double bar_px = bar_m * v.px_per_m, bx = v.x + v.width - bar_px - 14, by = v.y + v.height - 14;
  o << "<line x1=\"" << bx << "\" y1=\"" << by << "\" x2=\"" << bx + bar_px << "\" y2=\"" << by
    << "\" stroke=\"#000\" stroke-width=\"3\"/><text x=\"" << bx + bar_px / 2 << "\" y=\"" << by - 6
    << "\" font-size=\"12\" text-anchor=\"middle\">" << bar_label << "</text>\n";
  return o.str();
}

/// A label at (x, y) px with a leader line to the point (tx, ty) px.
std::string label(double x, double y, double tx, double ty, const std::string& text, const char* anchor = "start") {
  std::ostringstream o;
  o << "<line x1=\"" << x << "\" y1=\"" << y - 4 << "\" x2=\"" << tx << "\" y2=\"" << ty
    << "\" stroke=\"#333\" stroke-width=\"0.8\"/><circle cx=\"" << tx << "\" cy=\"" << ty
    << "\" r=\"2.5\" fill=\"#333\"/><text x=\"" << x << "\" y=\"" << y << "\" font-size=\"13\" text-anchor=\"" << anchor
    << "\">" << html_escape(text) << "</text>\n";
  return o.str();
}

}  // namespace

std::string drive_svg(const BacklashModel& m, const DriveOutline& o, const std::string& title) {
  const NeutralCurve& c = m.curve;
  const double r_cs = o.circular_spline_outer_radius_m, bore = o.bore_radius_m;
  const double hub = 0.35 * bore;  // the generator's hub bore: a picture's choice, not a case key
  std::ostringstream defs;
  defs << "<g id=\"drive\">\n"
       << region({circle(r_cs), circular_outline(m)}, "#aab4bf", "circular-spline")
       << region({flexspline_outline(m), deformed_circle(c, bore)}, "#8fbfe0", "flexspline");
  std::string generator = "wave generator (" + o.generator + ")";
  if (o.bearing) {
    const GeneratorBearing& b = *o.bearing;
    const double D = b.ball_diameter_m, rp = b.pitch_radius_m;
    defs << region({deformed_circle(c, bore), deformed_circle(c, bore - kOuterRingWallPerBallDiameter * D)}, "#d9d9d9")
         << region({deformed_circle(c, rp - 0.5 * D), deformed_circle(c, rp - 0.75 * D)}, "#d9d9d9")
         << region({deformed_circle(c, rp - 0.75 * D), circle(hub)}, "#e8c98a");
    for (int k = 0; k < b.balls; ++k) defs << region({circle(0.5 * D, deformed(c, 2 * kPi * k / b.balls, rp), 24)}, "#555");
    generator = "wave generator: " + o.generator + " in a ball bearing (" + std::to_string(b.balls) + " balls)";
  } else {
    defs << region({deformed_circle(c, bore), circle(hub)}, "#e8c98a");
  }
  defs << "</g>\n";

  const int zf = m.gear.teeth_flexspline, zc = m.gear.teeth_circular;
  const double pitch_m = kPi * m.gear.module_m;
  const double mesh_r = 0.5 * (m.radii.tip_c + m.radii.root_f);
  const double w_major = c.at(0).w_m, w_minor = c.at(kPi / 2).w_m;
  const View whole{10, 50, 640, 640, {0, 0}, 300 / r_cs};
  const double zoom_px_per_m = 560 / (9 * pitch_m);
  const View major{670, 50, 560, 300, {mesh_r + w_major, 0}, zoom_px_per_m, -90};
  const View minor{670, 390, 560, 300, {0, mesh_r + w_minor}, zoom_px_per_m};
  const double whole_bar = std::pow(10.0, std::floor(std::log10(r_cs)));  // 10 mm on a drive of 40 to 100 mm
  const double zoom_bar = std::pow(10.0, std::floor(std::log10(4 * pitch_m)));

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1240\" height=\"760\" viewBox=\"0 0 1240 760\" "
         "font-family=\"sans-serif\">\n<rect width=\"1240\" height=\"760\" fill=\"#fff\"/>\n<defs>\n"
      << defs.str() << "</defs>\n";
  svg << "<text x=\"10\" y=\"22\" font-size=\"16\" font-weight=\"bold\">The drive's three parts: " << html_escape(title)
      << "</text>\n<text x=\"10\" y=\"40\" font-size=\"12\">to scale, section through the teeth, generator at 0 (its "
         "major axis horizontal), unloaded; the flexspline's teeth on the generator-deformed rim</text>\n";
  char whole_label[32], zoom_label[32];
  std::snprintf(whole_label, sizeof whole_label, "%g mm", whole_bar * 1e3);
  std::snprintf(zoom_label, sizeof zoom_label, "%g mm", zoom_bar * 1e3);
  svg << view(whole, "whole", "whole drive", whole_bar, whole_label)
      << view(major, "major", "at the major axis: the teeth in mesh (outward up)", zoom_bar, zoom_label)
      << view(minor, "minor", "at the minor axis: the teeth apart (outward up)", zoom_bar, zoom_label);
  // The axes and the labels on the whole view.
  const double cx = whole.x + whole.width / 2, cy = whole.y + whole.height / 2, k = whole.px_per_m;
  svg << "<line x1=\"" << whole.x << "\" y1=\"" << cy << "\" x2=\"" << whole.x + whole.width << "\" y2=\"" << cy
      << "\" stroke=\"#c0392b\" stroke-dasharray=\"8 5\"/><text x=\"" << whole.x + whole.width - 6 << "\" y=\""
      << cy - 6 << "\" font-size=\"12\" fill=\"#c0392b\" text-anchor=\"end\">major axis</text>\n";
  svg << "<line x1=\"" << cx << "\" y1=\"" << whole.y << "\" x2=\"" << cx << "\" y2=\"" << whole.y + whole.height
      << "\" stroke=\"#2c3e50\" stroke-dasharray=\"3 4\"/><text x=\"" << cx + 6 << "\" y=\"" << whole.y + 34
      << "\" font-size=\"12\" fill=\"#2c3e50\">minor axis</text>\n";
  const double a_cs = 0.75 * kPi, a_fs = 0.62 * kPi;
  const double r_mid_cs = 0.5 * (r_cs + m.radii.root_c) * k, r_mid_fs = 0.5 * (bore + m.radii.tip_f) * k;
  svg << label(whole.x + 14, whole.y + 50, cx + r_mid_cs * std::cos(a_cs), cy - r_mid_cs * std::sin(a_cs),
               "circular spline: " + std::to_string(zc) + " internal teeth, fixed")
      << label(whole.x + 14, whole.y + 74, cx + r_mid_fs * std::cos(a_fs), cy - r_mid_fs * std::sin(a_fs),
               "flexspline: " + std::to_string(zf) + " external teeth on a thin rim, the output")
      << label(whole.x + 14, whole.y + whole.height - 40, cx - 0.6 * bore * k, cy + 0.25 * bore * k,
               generator + ", the input");
  svg << "<text x=\"10\" y=\"" << 722 << "\" font-size=\"12\">The generator bends the flexspline's rim into an oval "
      << "(radial " << std::lround(w_major * 1e6) << " µm at the major axis): its teeth mesh with the circular "
      << "spline's there and part at the minor axis.</text>\n<text x=\"10\" y=\"" << 740 << "\" font-size=\"12\">"
      << "A turn of the generator turns the flexspline back by " << zc - zf << " teeth: the ratio is "
      << zf / std::max(1, zc - zf) << ":1 with the circular spline fixed.</text>\n</svg>\n";
  return svg.str();
}

}  // namespace sw
