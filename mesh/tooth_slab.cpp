#include "mesh/tooth_slab.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "common/error.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/tetgen_mesh.hpp"

namespace sw {

ToothSlab mesh_tooth_slab(const GearParams& g, const ToothSlabOptions& o) {
  constexpr double kPi = std::numbers::pi;
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
  // TetGen 1.5 rejects a few of these outlines in its segment recovery (an assertion, not a geometric defect: the
  // polygon is simple and evenly sampled); one more point on the sides and the bore arc meshes them.
  const std::vector<Eigen::Vector2d> tooth_pts = pts;
  const std::vector<int> tooth_markers = seg_marker;
  for (int attempt = 0;; ++attempt) {
    pts = tooth_pts;
    seg_marker = tooth_markers;
    const double a_end = (K + 0.5) * 2 * kPi / z;
    const double depth = o.depth_over_spacing * spacing;
    const double body = r.root_f - o.bore_radius_m;
    const int n_side = std::max(2, static_cast<int>(std::ceil(body / (4 * spacing)))) + attempt;
    for (int i = 0; i < n_side; ++i) {  // right side, root circle down to the bore
      const double rad = r.root_f - body * i / n_side;
      pts.emplace_back(rad * std::cos(a_end), rad * std::sin(a_end));
      seg_marker.push_back(kSurfaceRimStep);
    }
    const int n_arc = std::max(4, static_cast<int>(std::ceil(2 * a_end * o.bore_radius_m / (6 * spacing)))) + attempt;
    for (int i = 0; i < n_arc; ++i) {  // bore arc, +a_end to −a_end
      const double a = a_end - 2 * a_end * i / n_arc;
      pts.emplace_back(o.bore_radius_m * std::cos(a), o.bore_radius_m * std::sin(a));
      seg_marker.push_back(kSurfaceClamped);
    }
    for (int i = 0; i < n_side; ++i) {  // left side, bore up to the root circle (the first point closes it)
      const double rad = o.bore_radius_m + body * i / n_side;
      pts.emplace_back(rad * std::cos(-a_end), rad * std::sin(-a_end));
      seg_marker.push_back(kSurfaceRimStep);
    }

    // Extrude: points i (z = 0) and n + i (z = depth); the two caps and one quad per outline segment.
    const int n = static_cast<int>(pts.size());
    Plc plc;
    for (double zz : {0.0, depth})
      for (const auto& p : pts) plc.points.emplace_back(p.x(), p.y(), zz);
    PlcFacet bottom, top;
    bottom.polygons.emplace_back();
    top.polygons.emplace_back();
    for (int i = 0; i < n; ++i) {
      bottom.polygons[0].push_back(i);
      top.polygons[0].push_back(n + i);
    }
    plc.facets.push_back(bottom);
    plc.facets.push_back(top);
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      PlcFacet quad;
      quad.polygons.push_back({i, j, n + j, n + i});
      quad.marker = seg_marker[i];
      plc.facets.push_back(quad);
    }
    TetgenOptions t;
    t.max_radius_edge_ratio = 2.0;
    const double edge = o.max_edge_over_spacing * spacing;
    t.max_volume_m3 = edge * edge * edge / (6 * std::sqrt(2.0));
    try {
      return ToothSlab{tetrahedralize_plc(plc, t), depth};
    } catch (const InputError&) {
      if (attempt == 3) throw;
    }
}
}

}  // namespace sw
