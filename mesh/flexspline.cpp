#include "mesh/flexspline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/estimate.hpp"
#include "mesh/revolve.hpp"
#include "mesh/shapes.hpp"

namespace sw {
namespace {

// Profile under construction: edges are added once each; mesh_revolved merges repeated vertices and splits edges
// at the layer lines that end on them.
struct ProfileBuilder {
  RevolvedProfile p;
  void line(Eigen::Vector2d a, Eigen::Vector2d b, int marker, double size) {
    if ((b - a).norm() <= 1e-12) return;
    ProfileSurface s;
    s.a = a;
    s.b = b;
    s.marker = marker;
    add(a, b, s, size);
  }
  void add(Eigen::Vector2d a, Eigen::Vector2d b, const ProfileSurface& s, double size) {
    const int ia = static_cast<int>(p.vertices.size());
    p.vertices.push_back(a);
    p.vertices.push_back(b);
    p.surfaces.push_back(s);
    p.edges.push_back({ia, ia + 1, static_cast<int>(p.surfaces.size()) - 1});
    p.edge_size_m.push_back(size);
  }
  void region(double r, double z, int id, double size) { p.regions.push_back({Eigen::Vector2d(r, z), id, size}); }
};

// The explicit rim's prism: the tooth outline extruded over the rim width, from the inner radius r_p (the outermost
// rim layer cylinder, shared with the revolved part) out to the outline.
struct ToothedRim {
  std::vector<Eigen::Vector2d> outline;  // closed CCW cross-section, metres
  std::vector<double> layer_radii_m;     // layer cylinders through the rim's revolved part; the last is r_p
  double inner_radius_m = 0.0;           // r_p
  double tooth_size_m = 0.0;             // target edge across a tooth
  double axial_size_m = 0.0;             // axial spacing of the flank quads
  Eigen::Vector2d seed = Eigen::Vector2d::Zero();  // (x, y) inside tooth 0
};

// Layer cylinders through a rim from the inner radius ri to r_outer over a body wall ri..ro: the body's own layer
// radii continued (so the body/rim interface z = length - rim_width carries no near-coincident rings: a rim layered
// on its own, at ri + k (r_outer - ri) / n, put a ring 0.04 mm outside r_o for a 0.4 mm wall, whose thin annulus
// gave 2.7 degree slivers), then r_o and cylinders up to r_outer at about the body's layer thickness when the rim
// reaches at least half a layer beyond r_o. Empty for a one-layer body under a thin rim.
std::vector<double> rim_layer_radii(double ri, double ro, double r_outer, const MeshParams& mesh) {
  const WallSize wb = wall_size(ro - ri, mesh);
  std::vector<double> radii;
  for (int k = 1; k < wb.layers; ++k) radii.push_back(ri + k * wb.across_m);
  const double beyond = r_outer - ro;
  if (beyond >= 0.5 * wb.across_m) {
    const int m = std::max(1, static_cast<int>(std::lround(beyond / wb.across_m)));
    for (int j = 0; j < m; ++j) radii.push_back(ro + j * beyond / m);
  }
  return radii;
}

// Drops outline points closer than min_spacing to the last point kept, pitch by pitch (every pitch the same, so the
// teeth stay identical; each pitch starts at its gap centre, which is kept). The shaper-cut root fillet can be far
// smaller than a tooth (0.013 mm deep at the seed case, 0.01 mm segments against 0.16 mm flank edges): extruded, such
// segments give needle faces whose tets are slivers, and resolving them would take ~0.01 mm tets along the whole rim
// width. Dropping them replaces the fillet and the root arc's ends by one chord, moving the boundary by less than
// the fillet's depth.
std::vector<Eigen::Vector2d> simplify_outline(const std::vector<Eigen::Vector2d>& outline, int teeth,
                                              double min_spacing) {
  const std::size_t per = outline.size() / static_cast<std::size_t>(teeth);
  std::vector<std::size_t> keep = {0};
  for (std::size_t i = 1; i < per; ++i)
    if ((outline[i] - outline[keep.back()]).norm() >= min_spacing && (outline[i] - outline[per]).norm() >= min_spacing)
      keep.push_back(i);
  std::vector<Eigen::Vector2d> out;
  out.reserve(keep.size() * teeth);
  for (int k = 0; k < teeth; ++k)
    for (const std::size_t i : keep) out.push_back(outline[k * per + i]);
  return out;
}

// Sizes: a tooth at mid height is t_mid thick; its cross-section gets edges of t_mid / 2 (two quadratic tets
// across), the flanks a point every such edge, the extrusion kToothAxialAspect times that axially.
// The rim's layer cylinders are the body's (so the body/rim interface has no near-coincident rings), plus
// cylinders from the body's outer radius r_o up to the root circle when the rim base reaches half a layer beyond
// r_o; the prism then starts at the last of them, so its base under the tooth roots is never a thin strip.
ToothedRim toothed_rim(const FlexsplineParams& f, const GearParams& g, const MeshParams& mesh) {
  const GearRadii r = gear_radii(g);
  const double ri = f.inner_radius_m, ro = ri + f.wall_thickness_m;
  const WallSize wb = wall_size(ro - ri, mesh);
  ToothedRim t;
  const ToothMeshSize size = tooth_mesh_size(g, mesh);
  t.tooth_size_m = size.across_m;
  t.axial_size_m = size.axial_m;
  const int per_flank = std::max(3, static_cast<int>(std::ceil((r.tip_f - r.form_f) / t.tooth_size_m - 1e-9)) + 1);
  t.outline = simplify_outline(flexspline_outline(g, per_flank), g.teeth_flexspline, 0.4 * t.tooth_size_m);
  t.layer_radii_m = rim_layer_radii(ri, ro, r.root_f, mesh);
  if (t.layer_radii_m.empty()) t.layer_radii_m.push_back(0.5 * (ri + r.root_f));  // the prism needs an inner ring
  t.inner_radius_m = t.layer_radii_m.back();
  t.seed = Eigen::Vector2d(0.5 * (r.form_f + r.tip_f), 0.0);
  return t;
}

// Appends the prism to the revolved PLC: the outline at M + 1 levels z_j from L - w to L, flank quads between
// them (marker: a Fixed surface, kSurfaceRimOuter), the open end z = L between the ring r_p and the outline, the
// shoulder z = L - w between the ring max(r_o, r_p) and the outline, and region 1 with the volume of a regular tet
// of the axial size as its bound (a cap only: the flank quads set the sizes in the teeth).
void add_toothed_prism(RevolvedPlc& revolved, std::vector<ProfileSurface>& surfaces, const ToothedRim& t,
                       const FlexsplineParams& f) {
  const double ri = f.inner_radius_m, ro = ri + f.wall_thickness_m, L = f.length_m, zr = L - f.rim_width_m;
  auto surface = [&](ProfileSurface s) {
    surfaces.push_back(s);
    return static_cast<int>(surfaces.size());  // marker = index + 1
  };
  ProfileSurface flank;
  flank.kind = ProfileSurface::Kind::Fixed;
  flank.marker = kSurfaceRimOuter;
  ProfileSurface top;
  top.a = Eigen::Vector2d(0.0, L);
  top.b = Eigen::Vector2d(1.0, L);
  top.marker = kSurfaceOpenEnd;
  ProfileSurface shoulder = top;
  shoulder.a.y() = shoulder.b.y() = zr;
  shoulder.marker = kSurfaceRimStep;
  const int flank_marker = surface(flank), top_marker = surface(top), shoulder_marker = surface(shoulder);

  Plc& plc = revolved.plc;
  const int P = static_cast<int>(t.outline.size());
  const int M = std::max(1, static_cast<int>(std::ceil(f.rim_width_m / t.axial_size_m - 1e-9)));
  const int first = static_cast<int>(plc.points.size());
  for (int j = 0; j <= M; ++j) {
    const double z = j == M ? L : zr + f.rim_width_m * j / M;
    for (const auto& q : t.outline) plc.points.emplace_back(q.x(), q.y(), z);
  }
  auto at = [&](int i, int j) { return first + j * P + (i % P); };
  for (int j = 0; j < M; ++j)
    for (int i = 0; i < P; ++i)
      plc.facets.push_back({{{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}}, {}, flank_marker});
  auto level = [&](int j) {
    std::vector<int> v(P);
    for (int i = 0; i < P; ++i) v[i] = at(i, j);
    return v;
  };
  plc.facets.push_back({{level(M), revolved.ring(t.inner_radius_m, L)}, {Eigen::Vector3d(0, 0, L)}, top_marker});
  plc.facets.push_back(
      {{level(0), revolved.ring(std::max(ro, t.inner_radius_m), zr)}, {Eigen::Vector3d(0, 0, zr)}, shoulder_marker});
  const double h = t.axial_size_m;
  plc.regions.push_back({Eigen::Vector3d(t.seed.x(), t.seed.y(), L - 0.5 * f.rim_width_m), 1,
                         h * h * h / (6.0 * std::sqrt(2.0))});
}

// The cup or tube profile's radii, heights and edge sizes (m): r_i, r_o, the rim's outer radius r_rim, length L, rim
// width w, the body/rim boundary z_r = L - w, the diaphragm's thickness t_d (0 for a tube), boss radius r_b and
// height h_b = 2 t_d, fillet radius r_f; the body wall's, rim's and diaphragm's layering and the edge sizes along them.
struct ProfileSizes {
  double ri, ro, L, w, rr, zr, td, rb, hb, rf;
  WallSize wb, wr, wd;
  double sb, sr, sd, sboss;
};

ProfileSizes profile_sizes(const FlexsplineParams& f, const std::optional<GearParams>& gear, const MeshParams& mesh) {
  const bool cup = f.shape == FlexsplineShape::Cup;
  ProfileSizes s;
  s.ri = f.inner_radius_m;
  s.ro = s.ri + f.wall_thickness_m;
  s.L = f.length_m;
  s.w = f.rim_width_m;
  s.rr = rim_outer_radius(f, gear);
  s.zr = s.L - s.w;
  s.td = cup ? f.diaphragm_thickness_m : 0.0;
  s.rb = f.boss_radius_m;
  s.hb = 2.0 * s.td;
  s.rf = cup ? f.fillet_radius_m : 0.0;
  s.wb = wall_size(s.ro - s.ri, mesh);
  s.wr = wall_size(s.rr - s.ri, mesh);
  s.wd = cup ? wall_size(s.td, mesh) : s.wb;
  s.sb = s.wb.along_m;
  s.sr = s.wr.along_m;
  s.sd = s.wd.along_m;
  s.sboss = kBossSizeFactor * mesh.size_m;
  return s;
}

using V2 = Eigen::Vector2d;

// Revolved part of an explicit toothed rim: inner wall, open end and layer cylinders up to the prism's inner radius
// r_p (the prism itself is added to the PLC by add_toothed_prism).
void add_toothed_rim_profile(ProfileBuilder& b, const ProfileSizes& s, const ToothedRim& teeth) {
  const double rp = teeth.inner_radius_m, sp = teeth.axial_size_m;
  b.line(V2(s.ri, s.L), V2(s.ri, s.zr), kSurfaceInner, std::min(s.sr, s.sb));
  b.line(V2(s.ri, s.L), V2(rp, s.L), kSurfaceOpenEnd, s.sb);
  b.line(V2(s.ri, s.zr), V2(s.ro, s.zr), kSurfaceOther, s.sb);
  if (rp > s.ro) b.line(V2(s.ro, s.zr), V2(rp, s.zr), kSurfaceRimStep, s.sb);
  double r0 = s.ri;
  for (const double r : teeth.layer_radii_m) {
    b.line(V2(r, s.zr), V2(r, s.L), kSurfaceOther, r == rp ? sp : s.sb);
    b.region(0.5 * (r0 + r), s.L - 0.5 * s.w, 1, s.sb);
    r0 = r;
  }
}

// A revolved rim (teeth "none" or "ring"): inner wall, open end, outer surface, shoulder, body/rim interface, layer
// lines.
void add_revolved_rim_profile(ProfileBuilder& b, const ProfileSizes& s, const MeshParams& mesh) {
  b.line(V2(s.ri, s.L), V2(s.ri, s.zr), kSurfaceInner, std::min(s.sr, s.sb));
  b.line(V2(s.ri, s.L), V2(s.rr, s.L), kSurfaceOpenEnd, s.sr);
  b.line(V2(s.rr, s.L), V2(s.rr, s.zr), kSurfaceRimOuter, s.sr);
  b.line(V2(s.rr, s.zr), V2(s.ro, s.zr), kSurfaceRimStep, s.sr);
  b.line(V2(s.ri, s.zr), V2(s.ro, s.zr), kSurfaceOther, std::min(s.sr, s.sb));
  double r0 = s.ri;
  for (const double r : rim_layer_radii(s.ri, s.ro, s.rr, mesh)) {
    b.line(V2(r, s.zr), V2(r, s.L), kSurfaceOther, s.sr);
    b.region(0.5 * (r0 + r), s.L - 0.5 * s.w, 1, s.sr);
    r0 = r;
  }
  b.region(0.5 * (r0 + s.rr), s.L - 0.5 * s.w, 1, s.sr);
}

// Body: outer wall, layer lines, inner wall down to the fillet (or to z = 0 for the tube).
void add_body_profile(ProfileBuilder& b, const ProfileSizes& s) {
  const WallSize& wb = s.wb;
  b.line(V2(s.ro, s.zr), V2(s.ro, s.td), kSurfaceOuter, s.sb);
  for (int k = 1; k < wb.layers; ++k)
    b.line(V2(s.ri + k * wb.across_m, s.td), V2(s.ri + k * wb.across_m, s.zr), kSurfaceOther, s.sb);
  for (int k = 0; k < wb.layers; ++k) b.region(s.ri + (k + 0.5) * wb.across_m, 0.5 * (s.zr + s.td + s.rf), 0, s.sb);
  b.line(V2(s.ri, s.zr), V2(s.ri, s.td + s.rf), kSurfaceInner, s.sb);
}

// Fillet: quarter circle from the diaphragm's top face (r_i - r_f, t_d) to the inner wall (r_i, t_d + r_f).
void add_fillet_profile(ProfileBuilder& b, const ProfileSizes& s) {
  if (!(s.rf > 0)) return;
  ProfileSurface arc;
  arc.kind = ProfileSurface::Kind::Circle;
  arc.centre = V2(s.ri - s.rf, s.td + s.rf);
  arc.radius = s.rf;
  arc.marker = kSurfaceDiaphragm;
  const int n = std::max(2, static_cast<int>(std::ceil(0.5 * kPi * s.rf / s.sb)));
  for (int i = 0; i < n; ++i) {
    const double a0 = -0.5 * kPi + 0.5 * kPi * i / n, a1 = -0.5 * kPi + 0.5 * kPi * (i + 1) / n;
    b.add(arc.centre + s.rf * V2(std::cos(a0), std::sin(a0)), arc.centre + s.rf * V2(std::cos(a1), std::sin(a1)), arc,
          s.sb);
  }
}

// Diaphragm: top face, body/diaphragm interface, outer edge, bottom face, layer lines; then the boss: interface with
// the diaphragm, clamped side, top and bottom, and the axis.
void add_diaphragm_and_boss_profile(ProfileBuilder& b, const ProfileSizes& s) {
  const double ri = s.ri, ro = s.ro, td = s.td, rb = s.rb, hb = s.hb, rf = s.rf, sd = s.sd;
  b.line(V2(rb, td), V2(ri - rf, td), kSurfaceDiaphragm, sd);
  b.line(V2(ri - rf, td), V2(ro, td), kSurfaceOther, std::min(s.sb, sd));
  b.line(V2(ro, td), V2(ro, 0), kSurfaceOuter, std::min(s.sb, sd));
  b.line(V2(ro, 0), V2(rb, 0), kSurfaceDiaphragm, sd);
  for (int k = 1; k < s.wd.layers; ++k) b.line(V2(rb, k * s.wd.across_m), V2(ro, k * s.wd.across_m), kSurfaceOther, sd);
  for (int k = 0; k < s.wd.layers; ++k) b.region(0.5 * (rb + ri - rf), (k + 0.5) * s.wd.across_m, 2, sd);
  b.line(V2(rb, 0), V2(rb, td), kSurfaceOther, sd);  // the diaphragm's side sets the ring at rb
  b.line(V2(rb, td), V2(rb, hb), kSurfaceClamped, sd);
  b.line(V2(rb, hb), V2(0, hb), kSurfaceClamped, s.sboss);
  b.line(V2(0, 0), V2(rb, 0), kSurfaceClamped, s.sboss);
  b.line(V2(0, hb), V2(0, 0), kSurfaceOther, s.sboss);  // the axis: sweeps nothing
  b.region(0.5 * rb, 0.5 * hb, 3, s.sboss);
}

// TetGen's node budget: as many added points as the estimate's TET10 nodes, about 7× the corner points expected
// (the estimate is within a few per cent on the cases), so only a refinement that runs away is stopped.
std::int64_t node_budget(const FlexsplineParams& f, const std::optional<GearParams>& gear, const MeshParams& mesh) {
  return static_cast<std::int64_t>(std::ceil(estimate_model_size(f, gear, mesh).nodes)) + 1000;
}

}  // namespace

TetMesh mesh_flexspline(const FlexsplineParams& f, const std::optional<GearParams>& gear, const MeshParams& mesh) {
  validate_flexspline(f, mesh);
  check_teeth_on_rim(f, gear);
  if (f.teeth == TeethModel::Layer)
    throw InputError("flexspline.teeth = \"layer\": the tooth layer is the harmonic solver's (a homogenised, "
                     "orthotropic layer); the TET10 mesh takes teeth = \"none\", \"ring\" or \"explicit\"");
  const bool cup = f.shape == FlexsplineShape::Cup;
  if (!cup && f.teeth == TeethModel::None)
    return mesh_tube(f.inner_radius_m, f.inner_radius_m + f.wall_thickness_m, f.length_m, mesh);

  const ProfileSizes s = profile_sizes(f, gear, mesh);
  ProfileBuilder b;
  std::optional<ToothedRim> teeth;
  if (f.teeth == TeethModel::Explicit) {
    teeth = toothed_rim(f, *gear, mesh);
    add_toothed_rim_profile(b, s, *teeth);
  } else {
    add_revolved_rim_profile(b, s, mesh);
  }
  add_body_profile(b, s);
  if (!cup) {
    b.line(V2(s.ri, 0), V2(s.ro, 0), kSurfaceClamped, s.sb);
  } else {
    add_fillet_profile(b, s);
    add_diaphragm_and_boss_profile(b, s);
    b.p.refine = corner_size_field(f, mesh);
  }
  const std::int64_t budget = node_budget(f, gear, mesh);
  if (!teeth) return mesh_revolved(b.p, mesh, budget);
  RevolvedPlc revolved = revolve_profile(b.p);
  std::vector<ProfileSurface> surfaces = b.p.surfaces;
  add_toothed_prism(revolved, surfaces, *teeth, f);
  return mesh_revolved_plc(revolved, surfaces, mesh, budget);
}

}  // namespace sw
