#include "mesh/flexspline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "common/error.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/revolve.hpp"
#include "mesh/shapes.hpp"

namespace sw {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::string mm(double m) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", m * 1e3);
  return buf;
}

[[noreturn]] void reject(const std::string& key, double value_m, const std::string& expectation) {
  throw InputError("flexspline." + key + " = " + mm(value_m) + "; " + expectation);
}

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

}  // namespace

double rim_outer_radius(const FlexsplineParams& f, const std::optional<GearParams>& gear) {
  const double root = f.inner_radius_m + f.rim_thickness_m;
  if (f.teeth == TeethModel::None) return root;
  if (!gear) throw InputError("flexspline.teeth needs the [gear] table (module, teeth, profile shift) for the tooth height");
  const GearRadii r = gear_radii(*gear);
  return root + 0.5 * (r.tip_f - r.root_f);
}

void validate_flexspline(const FlexsplineParams& f, const std::optional<GearParams>& gear, const MeshParams& mesh) {
  wall_size(f.wall_thickness_m, mesh);  // mesh.size_mm > 0, mesh.wall_layers >= 1
  if (!(f.inner_radius_m > 0)) reject("inner_radius_mm", f.inner_radius_m, "must be > 0");
  if (!(f.wall_thickness_m > 0)) reject("wall_thickness_mm", f.wall_thickness_m, "must be > 0");
  if (!(f.length_m > 0)) reject("length_mm", f.length_m, "must be > 0");
  const bool cup = f.shape == FlexsplineShape::Cup;
  const bool rim = cup || f.teeth != TeethModel::None;
  const double below_rim = cup ? f.length_m - f.diaphragm_thickness_m - f.fillet_radius_m : f.length_m;
  if (cup) {
    if (!(f.diaphragm_thickness_m > 0)) reject("diaphragm_thickness_mm", f.diaphragm_thickness_m, "must be > 0");
    if (!(f.boss_radius_m > 0)) reject("boss_radius_mm", f.boss_radius_m, "must be > 0");
    if (!(f.boss_radius_m < f.inner_radius_m))
      reject("boss_radius_mm", f.boss_radius_m, "must be < inner_radius_mm = " + mm(f.inner_radius_m));
    if (!(f.fillet_radius_m >= 0)) reject("fillet_radius_mm", f.fillet_radius_m, "must be >= 0");
    if (!(f.fillet_radius_m < f.inner_radius_m - f.boss_radius_m))
      reject("fillet_radius_mm", f.fillet_radius_m,
             "must be < inner_radius_mm - boss_radius_mm = " + mm(f.inner_radius_m - f.boss_radius_m));
    if (!(f.diaphragm_thickness_m < f.length_m))
      reject("diaphragm_thickness_mm", f.diaphragm_thickness_m, "must be < length_mm = " + mm(f.length_m));
  }
  if (rim) {
    if (!(f.rim_thickness_m > 0)) reject("rim_thickness_mm", f.rim_thickness_m, "must be > 0");
    if (!(f.rim_thickness_m >= f.wall_thickness_m))
      reject("rim_thickness_mm", f.rim_thickness_m,
             "must be >= wall_thickness_mm = " + mm(f.wall_thickness_m) + " (the rim is the thick end of the wall)");
    if (!(f.rim_width_m > 0)) reject("rim_width_mm", f.rim_width_m, "must be > 0");
    if (!(f.rim_width_m < below_rim))
      reject("rim_width_mm", f.rim_width_m,
             cup ? "must be < length_mm - diaphragm_thickness_mm - fillet_radius_mm = " + mm(below_rim)
                 : "must be < length_mm = " + mm(below_rim));
  }
  if (f.teeth != TeethModel::None) {
    if (!gear) throw InputError("flexspline.teeth needs the [gear] table (module, teeth, profile shift)");
    const double root = gear_radii(*gear).root_f;
    const double want = f.inner_radius_m + f.rim_thickness_m;
    if (std::abs(root - want) > 0.25 * gear->module_m)
      throw InputError("flexspline.rim_thickness_mm = " + mm(f.rim_thickness_m) + "; inner_radius_mm + rim_thickness_mm = " +
                       mm(want) + " must match the teeth's root circle " + mm(root) +
                       " mm (from [gear]) within 0.25 module = " + mm(0.25 * gear->module_m) + " mm");
  }
}

TetMesh mesh_flexspline(const FlexsplineParams& f, const std::optional<GearParams>& gear, const MeshParams& mesh) {
  validate_flexspline(f, gear, mesh);
  if (f.teeth == TeethModel::Explicit)
    throw InputError("flexspline.teeth = \"explicit\"; not meshed yet: use \"ring\" or \"none\"");
  const bool cup = f.shape == FlexsplineShape::Cup;
  if (!cup && f.teeth == TeethModel::None)
    return mesh_tube(f.inner_radius_m, f.inner_radius_m + f.wall_thickness_m, f.length_m, mesh);

  const double ri = f.inner_radius_m, ro = ri + f.wall_thickness_m, L = f.length_m, w = f.rim_width_m;
  const double rr = rim_outer_radius(f, gear);
  const double zr = L - w;                          // body / rim boundary
  const double td = cup ? f.diaphragm_thickness_m : 0.0;
  const double rb = f.boss_radius_m, hb = 2.0 * td, rf = cup ? f.fillet_radius_m : 0.0;
  const WallSize wb = wall_size(ro - ri, mesh), wr = wall_size(rr - ri, mesh);
  const WallSize wd = cup ? wall_size(td, mesh) : wb;
  const double sb = wb.along_m, sr = wr.along_m, sd = wd.along_m, sboss = mesh.size_m;

  ProfileBuilder b;
  using V2 = Eigen::Vector2d;
  // Rim: inner wall, open end, outer surface, shoulder, body/rim interface, layer lines.
  b.line(V2(ri, L), V2(ri, zr), kSurfaceInner, std::min(sr, sb));
  b.line(V2(ri, L), V2(rr, L), kSurfaceOpenEnd, sr);
  b.line(V2(rr, L), V2(rr, zr), kSurfaceRimOuter, sr);
  b.line(V2(rr, zr), V2(ro, zr), kSurfaceRimStep, sr);
  b.line(V2(ri, zr), V2(ro, zr), kSurfaceOther, std::min(sr, sb));
  for (int k = 1; k < wr.layers; ++k) b.line(V2(ri + k * wr.across_m, zr), V2(ri + k * wr.across_m, L), kSurfaceOther, sr);
  for (int k = 0; k < wr.layers; ++k) b.region(ri + (k + 0.5) * wr.across_m, L - 0.5 * w, 1, sr);
  // Body: outer wall, layer lines, inner wall down to the fillet (or to z = 0 for the tube).
  b.line(V2(ro, zr), V2(ro, td), kSurfaceOuter, sb);
  for (int k = 1; k < wb.layers; ++k) b.line(V2(ri + k * wb.across_m, td), V2(ri + k * wb.across_m, zr), kSurfaceOther, sb);
  for (int k = 0; k < wb.layers; ++k) b.region(ri + (k + 0.5) * wb.across_m, 0.5 * (zr + td + rf), 0, sb);
  b.line(V2(ri, zr), V2(ri, td + rf), kSurfaceInner, sb);
  if (!cup) {
    b.line(V2(ri, 0), V2(ro, 0), kSurfaceClamped, sb);
  } else {
    // Fillet: quarter circle from the diaphragm's top face (ri - rf, td) to the inner wall (ri, td + rf).
    if (rf > 0) {
      ProfileSurface arc;
      arc.kind = ProfileSurface::Kind::Circle;
      arc.centre = V2(ri - rf, td + rf);
      arc.radius = rf;
      arc.marker = kSurfaceDiaphragm;
      const int n = std::max(2, static_cast<int>(std::ceil(0.5 * kPi * rf / sb)));
      for (int i = 0; i < n; ++i) {
        const double a0 = -0.5 * kPi + 0.5 * kPi * i / n, a1 = -0.5 * kPi + 0.5 * kPi * (i + 1) / n;
        b.add(arc.centre + rf * V2(std::cos(a0), std::sin(a0)), arc.centre + rf * V2(std::cos(a1), std::sin(a1)), arc, sb);
      }
    }
    // Diaphragm: top face, body/diaphragm interface, outer edge, bottom face, layer lines.
    b.line(V2(rb, td), V2(ri - rf, td), kSurfaceDiaphragm, sd);
    b.line(V2(ri - rf, td), V2(ro, td), kSurfaceOther, std::min(sb, sd));
    b.line(V2(ro, td), V2(ro, 0), kSurfaceOuter, std::min(sb, sd));
    b.line(V2(ro, 0), V2(rb, 0), kSurfaceDiaphragm, sd);
    for (int k = 1; k < wd.layers; ++k) b.line(V2(rb, k * wd.across_m), V2(ro, k * wd.across_m), kSurfaceOther, sd);
    for (int k = 0; k < wd.layers; ++k) b.region(0.5 * (rb + ri - rf), (k + 0.5) * wd.across_m, 2, sd);
    // Boss: interface with the diaphragm, clamped side, top and bottom.
    b.line(V2(rb, 0), V2(rb, td), kSurfaceOther, std::min(sd, sboss));
    b.line(V2(rb, td), V2(rb, hb), kSurfaceClamped, std::min(sd, sboss));
    b.line(V2(rb, hb), V2(0, hb), kSurfaceClamped, sboss);
    b.line(V2(0, 0), V2(rb, 0), kSurfaceClamped, sboss);
    b.line(V2(0, hb), V2(0, 0), kSurfaceOther, sboss);  // the axis: sweeps nothing
    b.region(0.5 * rb, 0.5 * hb, 3, sboss);
  }
  return mesh_revolved(b.p, mesh);
}

}  // namespace sw
