#include "mesh/tooth_slab.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/tetgen_mesh.hpp"

namespace sw {

namespace {

/// The closed outline (points in order, each segment's marker) extruded from z = 0 to `depth`: a cap at each level
/// (z = 0, depth and the cuts between: inner ones are facets the tets do not cross) and one quad per segment and
/// layer, TET10 through TetGen with tets no larger than a regular one of edge `max_edge` (0 = no bound).
TetMesh extrude(const std::vector<Eigen::Vector2d>& pts, const std::vector<int>& seg_marker, double depth,
                double max_edge, const std::vector<double>& cuts) {
  const int n = static_cast<int>(pts.size());
  std::vector<double> levels{0.0};
  for (const double c : cuts) levels.push_back(c * depth);
  levels.push_back(depth);
  Plc plc;
  for (const double zz : levels)
    for (const auto& p : pts) plc.points.emplace_back(p.x(), p.y(), zz);
  for (std::size_t l = 0; l < levels.size(); ++l) {
    PlcFacet cap;
    cap.polygons.emplace_back();
    for (int i = 0; i < n; ++i) cap.polygons[0].push_back(static_cast<int>(l) * n + i);
    plc.facets.push_back(cap);
  }
  for (std::size_t l = 0; l + 1 < levels.size(); ++l)
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n, b = static_cast<int>(l) * n, t = b + n;
      PlcFacet quad;
      quad.polygons.push_back({b + i, b + j, t + j, t + i});
      quad.marker = seg_marker[i];
      plc.facets.push_back(quad);
    }
  TetgenOptions t;
  t.time_limit_s = 10.0;
  t.max_radius_edge_ratio = 2.0;
  t.max_volume_m3 = max_edge * max_edge * max_edge / (6 * std::sqrt(2.0));
  return tetrahedralize_plc(plc, t);
}

/// The body's sides and bore arc below an outline that runs from angle −a_end to +a_end at radius `top_m`: the right
/// side down to the bore, the bore arc back, the left side up (its last point is followed by the outline's first).
/// The sides are chains of points every four spacings, or, with `straight_sides`, one segment each (TetGen splits it
/// where its size and quality bounds ask). Why both (extrude_with_retries): points placed along a side,
/// rad·(cos a, sin a), are collinear only to round-off (~1e-19 m off the line, either way), and TetGen 1.5 triangulates
/// a cap holding such a chain from exact orientation tests but a floating in-circle test with a relative tolerance
/// (incircle3d, 1e-8); the two disagree on the slivers the chain makes, and its segment recovery asserts
/// (sscoutsegment) or its flips loop without end. Which outline trips it is a matter of the last bit: the ring slab of
/// `strainwave design --size 14 --ratio 50` failed at the case's bore (17.4556104 mm read as 1e-3 x mm) and meshed
/// 1 ulp smaller; over the 15 designs of sizes 14/17/20 and ratios 30-160, each rescaled by 1 + k·1.3e-9 (k < 8),
/// sides of 5 segments failed 18 of 240 first attempts, sides of one segment none.
void close_with_body(double top_m, double bore_m, double a_end, double spacing, int extra, bool straight_sides,
                     std::vector<Eigen::Vector2d>& pts, std::vector<int>& seg_marker) {
  const double body = top_m - bore_m;
  const int n_side = straight_sides ? 1 : std::max(2, static_cast<int>(std::ceil(body / (4 * spacing))));
  for (int i = 0; i < n_side; ++i) {
    const double rad = top_m - body * i / n_side;
    pts.emplace_back(rad * std::cos(a_end), rad * std::sin(a_end));
    seg_marker.push_back(kSurfaceRimStep);
  }
  const int n_arc = std::max(4, static_cast<int>(std::ceil(2 * a_end * bore_m / (6 * spacing)))) + extra;
  for (int i = 0; i < n_arc; ++i) {
    const double a = a_end - 2 * a_end * i / n_arc;
    pts.emplace_back(bore_m * std::cos(a), bore_m * std::sin(a));
    seg_marker.push_back(kSurfaceClamped);
  }
  for (int i = 0; i < n_side; ++i) {
    const double rad = bore_m + body * i / n_side;
    pts.emplace_back(rad * std::cos(-a_end), rad * std::sin(-a_end));
    seg_marker.push_back(kSurfaceRimStep);
  }
}

/// The outline on top (points and markers, from angle −a_end to +a_end at radius `top_m`) closed with the body down to
/// the bore and extruded. The first attempt draws the sides as chains (the meshes every tooth compliance so far was
/// measured on; most outlines mesh so in well under a second); should TetGen refuse it or run out of its 10 s budget,
/// the sides become single segments (close_with_body says why that meshes them), then one more point on the bore arc
/// (a circle: no collinear chain); three attempts the most.
ToothSlab extrude_with_retries(const std::vector<Eigen::Vector2d>& outline, const std::vector<int>& outline_markers,
                               double top_m, const ToothSlabOptions& o, double a_end, double spacing) {
  for (int attempt = 0;; ++attempt) {
    std::vector<Eigen::Vector2d> pts = outline;
    std::vector<int> seg_marker = outline_markers;
    const double depth = o.depth_over_spacing * spacing;
    close_with_body(top_m, o.bore_radius_m, a_end, spacing, attempt == 2 ? 1 : 0, attempt > 0, pts, seg_marker);
    try {
      return ToothSlab{extrude(pts, seg_marker, depth, o.max_edge_over_spacing * spacing, o.depth_cuts), depth};
    } catch (const InputError&) {
      if (attempt == 2) throw;
    }
  }
}

void check_cuts(const std::vector<double>& cuts) {
  for (std::size_t i = 0; i < cuts.size(); ++i)
    if (!(cuts[i] > 0 && cuts[i] < 1) || (i > 0 && !(cuts[i] > cuts[i - 1])))
      throw InputError("tooth slab: depth cut " + std::to_string(cuts[i]) + " must lie in (0, 1), ascending");
}

}  // namespace

ToothSlab mesh_tooth_slab(const GearParams& g, const ToothSlabOptions& o) {
  check_cuts(o.depth_cuts);
  const GearRadii r = gear_radii(g);
  if (!(o.bore_radius_m > 0 && o.bore_radius_m < r.root_f) || o.teeth_each_side < 0 ||
      2 * o.teeth_each_side + 1 > g.teeth_flexspline) {
    std::ostringstream s;
    s << "tooth slab: bore radius " << o.bore_radius_m * 1e3 << " mm, " << o.teeth_each_side
      << " teeth each side; need 0 < bore < root radius " << r.root_f * 1e3 << " mm and 2K + 1 <= z";
    throw InputError(s.str());
  }
  const int z = g.teeth_flexspline, K = o.teeth_each_side;
  const int n_fine = std::max(8, o.points_per_flank);
  const double spacing = (r.tip_f - r.form_f) / (n_fine - 1);
  // A dense outline (every flank point 1/400 of the flank apart) resampled at nearly even arc lengths: `spacing` on the
  // loaded tooth, twice that on its neighbours. Even segments keep TetGen's quality refinement from chasing the very
  // short segments the radius-graded outline has at the root.
  const auto dense = flexspline_outline(g, 400);
  const std::size_t per = dense.size() / z;
  std::vector<Eigen::Vector2d> pts;
  std::vector<int> seg_marker;
  auto rotate = [](const Eigen::Vector2d& p, double a) {
    return Eigen::Vector2d(std::cos(a) * p.x() - std::sin(a) * p.y(), std::sin(a) * p.x() + std::cos(a) * p.y());
  };
  for (int k = -K; k <= K; ++k) {
    std::vector<Eigen::Vector2d> line(dense.begin(), dense.begin() + per);
    line.push_back(rotate(dense[0], 2 * kPi / z));  // the next pitch's first point closes this one
    double length = 0;
    for (std::size_t i = 1; i < line.size(); ++i) length += (line[i] - line[i - 1]).norm();
    const int n_seg = std::max(4, static_cast<int>(std::round(length / (k == 0 ? spacing : 2 * spacing))));
    const double step = length / n_seg;
    double walked = 0;  // arc length at line[i - 1]
    std::size_t i = 1;
    for (int j = 0; j < n_seg; ++j) {  // points at s = j·step (the closing point belongs to the next pitch)
      const double s_j = j * step;
      while (i + 1 < line.size() && walked + (line[i] - line[i - 1]).norm() < s_j) walked += (line[i] - line[i - 1]).norm(), ++i;
      const double seg = (line[i] - line[i - 1]).norm();
      const double t = seg > 0 ? std::clamp((s_j - walked) / seg, 0.0, 1.0) : 0.0;
      pts.push_back(rotate(line[i - 1] + t * (line[i] - line[i - 1]), 2 * kPi * k / z));
      seg_marker.push_back(k == 0 ? kSurfaceRimOuter : kSurfaceOther);
    }
  }
  const double a_end = (K + 0.5) * 2 * kPi / z;
  return extrude_with_retries(pts, seg_marker, r.root_f, o, a_end, spacing);
}

ToothSlab mesh_ring_slab(const GearParams& g, const ToothSlabOptions& o, double r_o) {
  check_cuts(o.depth_cuts);
  const GearRadii r = gear_radii(g);
  if (!(o.bore_radius_m > 0 && o.bore_radius_m < r_o) || o.teeth_each_side < 0 ||
      2 * o.teeth_each_side + 1 > g.teeth_flexspline) {
    std::ostringstream s;
    s << "ring slab: bore radius " << o.bore_radius_m * 1e3 << " mm, " << o.teeth_each_side
      << " teeth each side; need 0 < bore < outer radius " << r_o * 1e3 << " mm and 2K + 1 <= z";
    throw InputError(s.str());
  }
  const double spacing = (r.tip_f - r.form_f) / (std::max(8, o.points_per_flank) - 1);
  const double a_end = (o.teeth_each_side + 0.5) * 2 * kPi / g.teeth_flexspline;
  std::vector<Eigen::Vector2d> pts;
  std::vector<int> seg_marker;
  const int n_out = static_cast<int>(std::ceil(2 * a_end * r_o / spacing));
  for (int i = 0; i < n_out; ++i) {  // the ring's outer arc, −a_end to +a_end
    const double a = -a_end + 2 * a_end * i / n_out;
    pts.emplace_back(r_o * std::cos(a), r_o * std::sin(a));
    seg_marker.push_back(kSurfaceRimOuter);
  }
  return extrude_with_retries(pts, seg_marker, r_o, o, a_end, spacing);
}

}  // namespace sw
