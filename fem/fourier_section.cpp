#include "fem/fourier_section.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <numbers>

#include <Eigen/LU>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/interpolate.hpp"
#include "fem/rib_cell.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/flexspline.hpp"
#include "mesh/shapes.hpp"

namespace sw {
namespace {

constexpr int kInterior = -1;  // a block side that is not on the boundary (or lies on the axis)
// The tooth layer: at least this many cells from the rim to the tip (the solidity falls from 1 at the root to the
// tip land's over about the tooth's height), and its solidity tabulated at this many intervals (the layer's steel
// then holds the teeth's area within 1.5e-4, tests/fem FourierToothLayer).
constexpr int kMinToothLayerCells = 3;
constexpr int kToothLayerSamples = 64;
// The rib cell's rows and cells across the tooth (fem/rib_cell.hpp). The rows converge fast (the default tooth's κ at
// 16 across: 0.27933 / 0.27907 / 0.27902 at 128 / 256 / 512 rows); across, the root's corners set the rate (at 128 rows
// 0.27933 / 0.27701 / 0.27618 at 16 / 32 / 64, order 1.5, extrapolated 0.2757): 128 × 32 is within 0.5 % of it
// (tests/fem/test_tooth_layer.cpp).
constexpr int kRibCellSamples = 128;
constexpr int kRibCellAcross = 32;

using V2 = Eigen::Vector2d;

/// A structured block: a map of the unit square (u, v) onto the section, nu × nv cells, the region of its
/// triangles and the Surface marker of each side (bottom v = 0, right u = 1, top v = 1, left u = 0).
struct Block {
  std::function<V2(double u, double v)> map;
  int nu = 1, nv = 1;
  int region = 0;
  std::array<int, 4> marker{kInterior, kInterior, kInterior, kInterior};
  std::vector<double> us, vs;  ///< cell corners in u and v (nu + 1, nv + 1 values from 0 to 1); empty: uniform
};

/// Cell corners 0..1 of `n` uniform cells whose first (`at_start`) and/or last (`at_end`) cell is split geometrically
/// into `levels` + 1 cells, each half the next: a graded (geometric) refinement toward a singular corner.
std::vector<double> graded(int n, int levels, bool at_start, bool at_end) {
  std::vector<double> x;
  const double h = 1.0 / n;
  x.push_back(0.0);
  if (at_start)
    for (int j = levels; j >= 1; --j) x.push_back(h * std::ldexp(1.0, -j));
  for (int k = 1; k < n; ++k) x.push_back(k * h);
  if (at_end)
    for (int j = 1; j <= levels; ++j) x.push_back(1.0 - h * std::ldexp(1.0, -j));
  x.push_back(1.0);
  std::sort(x.begin(), x.end());
  x.erase(std::unique(x.begin(), x.end(), [](double a, double b) { return std::abs(a - b) < 1e-12; }), x.end());
  return x;
}

/// Adds blocks to a section, merging the nodes that blocks share (equal up to round-off).
class SectionBuilder {
public:
  void add(const Block& b) {
    const int ni = 2 * b.nu + 1, nj = 2 * b.nv + 1;
    // Node parameters: cell corners (graded or uniform), midside nodes halfway between them.
    auto param = [](const std::vector<double>& corners, int n, int i) {
      auto corner = [&](int k) { return corners.empty() ? double(k) / n : corners[static_cast<std::size_t>(k)]; };
      return i % 2 == 0 ? corner(i / 2) : 0.5 * (corner(i / 2) + corner(i / 2 + 1));
    };
    std::vector<int> g(static_cast<std::size_t>(ni * nj));
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < ni; ++i) g[j * ni + i] = node(b.map(param(b.us, b.nu, i), param(b.vs, b.nv, j)));
    auto at = [&](int i, int j) { return g[j * ni + i]; };
    for (int cj = 0; cj < b.nv; ++cj)
      for (int ci = 0; ci < b.nu; ++ci) {
        const int i = 2 * ci, j = 2 * cj;
        const int a = at(i, j), bb = at(i + 2, j), c = at(i + 2, j + 2), d = at(i, j + 2);
        const int ab = at(i + 1, j), bc = at(i + 2, j + 1), cd = at(i + 1, j + 2), da = at(i, j + 1),
                  mid = at(i + 1, j + 1);
        triangle({a, bb, c, ab, bc, mid}, b.region);
        triangle({a, c, d, mid, cd, da}, b.region);
      }
    auto side = [&](int s, int k) -> std::array<int, 3> {  // k-th edge of side s
      switch (s) {
        case 0: return {at(2 * k, 0), at(2 * k + 2, 0), at(2 * k + 1, 0)};
        case 1: return {at(ni - 1, 2 * k), at(ni - 1, 2 * k + 2), at(ni - 1, 2 * k + 1)};
        case 2: return {at(2 * k, nj - 1), at(2 * k + 2, nj - 1), at(2 * k + 1, nj - 1)};
        default: return {at(0, 2 * k), at(0, 2 * k + 2), at(0, 2 * k + 1)};
      }
    };
    for (int s = 0; s < 4; ++s) {
      if (b.marker[s] == kInterior) continue;
      const int n = (s % 2 == 0) ? b.nu : b.nv;
      for (int k = 0; k < n; ++k) mesh_.edges.push_back({side(s, k), b.marker[s]});
    }
  }

  SectionMesh finish() {
    mesh_.nodes.resize(static_cast<Eigen::Index>(points_.size()), 2);
    for (std::size_t i = 0; i < points_.size(); ++i) mesh_.nodes.row(static_cast<Eigen::Index>(i)) = points_[i];
    return std::move(mesh_);
  }

private:
  static constexpr double kQuantum = 1e-9;  // m: nodes of different blocks closer than this are one node
  int node(const V2& p) {
    const long long kr = std::llround(p.x() / kQuantum), kz = std::llround(p.y() / kQuantum);
    for (long long dr = -1; dr <= 1; ++dr)
      for (long long dz = -1; dz <= 1; ++dz) {
        const auto it = index_.find({kr + dr, kz + dz});
        if (it != index_.end() && (points_[it->second] - p).norm() < kQuantum) return it->second;
      }
    points_.push_back(p);
    const int id = static_cast<int>(points_.size()) - 1;
    index_[{kr, kz}] = id;
    return id;
  }
  void triangle(std::array<int, 6> t, int region) {
    const V2 a = points_[t[0]], b = points_[t[1]], c = points_[t[2]];
    const double area2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    if (area2 < 0) t = {t[0], t[2], t[1], t[5], t[4], t[3]};
    mesh_.triangles.push_back(t);
    mesh_.region.push_back(region);
  }
  std::vector<V2> points_;
  std::map<std::pair<long long, long long>, int> index_;
  SectionMesh mesh_;
};

Block rectangle(double r0, double r1, double z0, double z1, int nu, int nv, int region, std::array<int, 4> marker) {
  Block b;
  b.map = [=](double u, double v) { return V2(r0 + u * (r1 - r0), z0 + v * (z1 - z0)); };
  b.nu = std::max(1, nu);
  b.nv = std::max(1, nv);
  b.region = region;
  b.marker = marker;
  return b;
}

int cells(double length, double size) { return std::max(1, static_cast<int>(std::ceil(length / size - 1e-9))); }

/// A block whose u (v) cell corners are `us` (`vs`).
Block graded_block(Block b, std::vector<double> us, std::vector<double> vs) {
  if (!us.empty()) b.nu = static_cast<int>(us.size()) - 1, b.us = std::move(us);
  if (!vs.empty()) b.nv = static_cast<int>(vs.size()) - 1, b.vs = std::move(vs);
  return b;
}

/// The section's dimensions (m) and its cells: r_i, wall t_w, r_o, L, the rim's start z_r (L without a rim) and outer
/// radius r_rim (r_o without a rim), the diaphragm t_d and fillet r_f (0 for a tube), boss r_b and h_b = 2 t_d; the
/// layer count shared by every wall, the cell length along the wall and the diaphragm, the rim's extra layers beyond
/// r_o, the grading levels toward the boss corners and the graded layer corners.
struct SectionSizes {
  bool cup = false, rim = false;
  double ri, tw, ro, L, zr, rr, td, rf, rb, hb;
  int layers;
  double along_wall, along_diaphragm;
  int extra, levels;
  std::vector<double> lay;
  double rt = 0;         ///< teeth = "layer": the tooth layer's outer radius (the tip circle); 0 without a layer
  int layer_cells = 0;   ///< its cells from the rim's outer radius to the tip
};

SectionSizes section_sizes(const FlexsplineParams& f, const std::optional<GearParams>& gear, const MeshParams& mesh) {
  SectionSizes s;
  s.cup = f.shape == FlexsplineShape::Cup;
  s.rim = s.cup || f.teeth != TeethModel::None;
  s.ri = f.inner_radius_m;
  s.tw = f.wall_thickness_m;
  s.ro = s.ri + s.tw;
  s.L = f.length_m;
  s.zr = s.rim ? s.L - f.rim_width_m : s.L;
  s.rr = s.rim ? rim_outer_radius(f, gear) : s.ro;
  s.td = s.cup ? f.diaphragm_thickness_m : 0.0;
  s.rf = s.cup ? f.fillet_radius_m : 0.0;
  s.rb = f.boss_radius_m;
  s.hb = 2.0 * s.td;
  // Layers: the same count through every wall, so the blocks meet node to node.
  s.layers = wall_size(s.tw, mesh).layers;
  if (s.cup) s.layers = std::max(s.layers, wall_size(s.td, mesh).layers);
  s.along_wall = std::min(mesh.size_m, kMaxLayerAspect * s.tw / s.layers);
  s.along_diaphragm = s.cup ? std::min(mesh.size_m, kMaxLayerAspect * s.td / s.layers) : s.along_wall;
  const double across = s.tw / s.layers;
  s.extra = s.rr - s.ro > 1e-9 ? std::max(1, static_cast<int>(std::lround((s.rr - s.ro) / across))) : 0;
  // The cup's boss/diaphragm junction is singular: at r = r_boss the clamped boss meets the free diaphragm faces, at
  // z = 0 on a straight line (clamped → free) and at z = t_d in a 270° corner (φ₀ converges as h^0.6 on uniform
  // sections). The cells at the junction are split geometrically (halving) toward it, in r in the diaphragm and the
  // boss, in z through every wall's layers (the layers are shared by all walls, so their outermost layers are thin
  // everywhere) and in the boss above the diaphragm. Levels: mesh.corner_levels, the TET10 size field's key
  // (mesh/flexspline_sizes.hpp corner_levels: the rule's kDerivedCornerLevels + log2 of the diaphragm's layers unless
  // the case gives it, so the corner cell shrinks about as h²).
  s.levels = corner_levels(f, mesh);
  s.lay = graded(s.layers, s.levels, true, true);
  if (f.teeth == TeethModel::Layer) {
    s.rt = gear_radii(*gear).tip_f;
    s.layer_cells = std::max(kMinToothLayerCells, static_cast<int>(std::lround((s.rt - s.rr) / across)));
  }
  return s;
}

/// The axial break lines of the body wall and rim: the body's start, the rim's shoulder, the generator band's edges
/// (when inside the wall) and the open end, sorted and without repeats.
std::vector<double> axial_breaks(const SectionSizes& s, std::optional<std::pair<double, double>> band) {
  const double z_start = s.cup ? s.td + s.rf : 0.0;
  std::vector<double> breaks = {z_start, s.L};
  if (s.rim) breaks.push_back(s.zr);
  if (band)
    for (const double z : {band->first - 0.5 * band->second, band->first + 0.5 * band->second})
      if (z > z_start + 1e-9 && z < s.L - 1e-9) breaks.push_back(z);
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end(), [](double a, double c) { return std::abs(a - c) < 1e-9; }),
               breaks.end());
  return breaks;
}

/// Body wall and rim: a block through the wall per axial segment between the break lines, and in the rim a block
/// from r_o out to the rim's outer radius.
void add_wall_blocks(SectionBuilder& b, const SectionSizes& s, const std::vector<double>& breaks) {
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double z0 = breaks[k], z1 = breaks[k + 1];
    const bool in_rim = s.rim && z0 >= s.zr - 1e-12;
    const int n = cells(z1 - z0, s.along_wall);
    const int bottom = (!s.cup && k == 0) ? kSurfaceClamped : kInterior;
    const int top = k + 2 == breaks.size() ? kSurfaceOpenEnd : kInterior;
    const int right = !in_rim ? kSurfaceOuter : s.extra > 0 ? kInterior : kSurfaceRimOuter;
    b.add(graded_block(rectangle(s.ri, s.ro, z0, z1, s.layers, n, in_rim ? 1 : 0, {bottom, right, top, kSurfaceInner}),
                       s.lay, {}));
    const int shoulder = std::abs(z0 - s.zr) < 1e-12 ? kSurfaceRimStep : kInterior;
    if (in_rim && s.extra > 0)
      b.add(rectangle(s.ro, s.rr, z0, z1, s.extra, n, 1, {shoulder, kSurfaceRimOuter, top, kInterior}));
    // The tooth layer outside the rim's outer surface, which stays marked: the contact's loads and readings sit on it
    // (the teeth carry a flank's load down to the rim in series, contact/tooth_fem.hpp).
    if (in_rim && s.layer_cells > 0)
      b.add(rectangle(s.rr, s.rt, z0, z1, s.layer_cells, n, kToothLayerRegion, {shoulder, kSurfaceOther, top, kInterior}));
  }
}

/// The layer's solidity at kToothLayerSamples radii from the rim's outer radius to the tip, and its shear factor from
/// one pitch of the rim (bore to root) and a tooth on it, sampled at kRibCellSamples heights: the tooth's width at each
/// radius, φ·2πr/z_f, within the root's pitch (the cell is plane: s = r_root·θ at the root). At the root circle itself
/// the solidity jumps (1 below, the teeth's share above the spaces' floor); both read it from above, so a rim whose
/// outer radius is the root circle to the last digit is not a tooth as wide as the pitch in one case and not in the
/// next.
ToothLayer tooth_layer(const SectionSizes& s, const GearParams& g) {
  const double above_root = 1e-6 * (s.rt - s.rr);
  const auto solidity = [&](double r) { return flexspline_solidity(g, std::max(r, s.rr + above_root)); };
  ToothLayer t;
  for (int k = 0; k <= kToothLayerSamples; ++k) {
    const double r = s.rr + (s.rt - s.rr) * k / kToothLayerSamples;
    t.radius_m.push_back(r);
    t.solidity.push_back(solidity(r));
  }
  RibCell cell;
  cell.pitch_m = 2 * kPi * s.rr / g.teeth_flexspline;
  cell.rim_thickness_m = s.rr - s.ri;
  cell.cells_across = kRibCellAcross;
  for (int k = 0; k <= kRibCellSamples; ++k) {
    const double r = s.rr + (s.rt - s.rr) * k / kRibCellSamples;
    cell.height_m.push_back(r - s.rr);
    cell.width_m.push_back(std::min(cell.pitch_m, solidity(r) * 2 * kPi * r / g.teeth_flexspline));
  }
  cell.width_m.back() = std::max(cell.width_m.back(), 1e-3 * cell.pitch_m);  // the tip's corner, not a point
  t.shear_factor = rib_shear_factor(cell);
  return t;
}

/// The fillet's centre (r_i - r_f, t_d + r_f).
V2 fillet_centre(const SectionSizes& s) { return V2(s.ri - s.rf, s.td + s.rf); }

/// One block of the fillet's elbow: rays from the fillet's centre O at angles a0..a1 (u), from the arc out to the
/// diaphragm's bottom z = 0 (`to_bottom`) or to the body's outer wall r = r_o (v).
Block elbow_block(const SectionSizes& s, double a0, double a1, bool to_bottom) {
  const V2 O = fillet_centre(s);
  const double ro = s.ro, rf = s.rf;
  Block e;
  e.map = [=](double u, double v) {
    const double a = a0 + u * (a1 - a0);
    const V2 dir(std::cos(a), std::sin(a));
    const double t = to_bottom ? O.y() / -dir.y() : (ro - O.x()) / dir.x();
    const V2 inner = O + rf * dir, outer = O + t * dir;
    return V2(inner + v * (outer - inner));
  };
  const double outer_len = (e.map(1, 1) - e.map(0, 1)).norm(), arc_len = rf * std::abs(a1 - a0);
  e.nu = cells(std::max(outer_len, arc_len), std::min(s.along_wall, s.along_diaphragm));
  e.nv = s.layers;
  e.region = to_bottom ? 2 : 0;
  e.marker = {kSurfaceDiaphragm, kInterior, to_bottom ? kSurfaceDiaphragm : kSurfaceOuter, kInterior};
  return e;
}

/// The cup's diaphragm/wall elbow. With a fillet, two blocks of rays from its centre: the first ends on the
/// diaphragm's bottom, the second on the body's outer wall; they meet at the ray through the outer corner (r_o, 0).
/// Without, a square corner block.
void add_elbow_blocks(SectionBuilder& b, const SectionSizes& s) {
  if (s.rf > 0) {
    const V2 O = fillet_centre(s);
    const double alpha_k = std::atan2(-O.y(), s.ro - O.x());
    b.add(graded_block(elbow_block(s, -0.5 * kPi, alpha_k, true), {}, s.lay));
    b.add(graded_block(elbow_block(s, alpha_k, 0.0, false), {}, s.lay));
  } else {
    b.add(graded_block(
        rectangle(s.ri, s.ro, 0.0, s.td, s.layers, s.layers, 2, {kSurfaceDiaphragm, kSurfaceOuter, kInterior, kInterior}),
        s.lay, s.lay));
  }
}

/// The cup's diaphragm from the boss to the elbow and the boss below and above the diaphragm's top, graded toward
/// the boss/diaphragm junction.
void add_diaphragm_and_boss_blocks(SectionBuilder& b, const SectionSizes& s, const MeshParams& mesh) {
  const double rb = s.rb, td = s.td, hb = s.hb, r_dia = s.ri - s.rf;
  b.add(graded_block(rectangle(rb, r_dia, 0.0, td, 1, 1, 2, {kSurfaceDiaphragm, kInterior, kSurfaceDiaphragm, kInterior}),
                     graded(cells(r_dia - rb, s.along_diaphragm), s.levels, true, false), s.lay));
  const double s_boss = kBossSizeFactor * mesh.size_m;
  const std::vector<double> boss_r = graded(cells(rb, s_boss), s.levels, false, true);
  b.add(graded_block(rectangle(0.0, rb, 0.0, td, 1, 1, 3, {kSurfaceClamped, kInterior, kInterior, kInterior}), boss_r,
                     s.lay));
  b.add(graded_block(rectangle(0.0, rb, td, hb, 1, 1, 3, {kInterior, kSurfaceClamped, kSurfaceClamped, kInterior}), boss_r,
                     graded(cells(hb - td, s_boss), s.levels, true, false)));
}

}  // namespace

SectionMesh mesh_annulus_section(double r_inner_m, double r_outer_m, double length_m, int layers, int cells_along) {
  SectionBuilder b;
  b.add(rectangle(r_inner_m, r_outer_m, 0.0, length_m, layers, cells_along, 0,
                  {kSurfaceClamped, kSurfaceOuter, kSurfaceOpenEnd, kSurfaceInner}));
  return b.finish();
}

SectionMesh mesh_annulus_section(const std::vector<double>& r_m, const std::vector<double>& z_m) {
  const auto unit = [](const std::vector<double>& x) {
    std::vector<double> u;
    for (const double v : x) u.push_back((v - x.front()) / (x.back() - x.front()));
    return u;
  };
  SectionBuilder b;
  b.add(graded_block(rectangle(r_m.front(), r_m.back(), z_m.front(), z_m.back(), 1, 1, 0,
                               {kSurfaceClamped, kSurfaceOuter, kSurfaceOpenEnd, kSurfaceInner}),
                     unit(r_m), unit(z_m)));
  return b.finish();
}

SectionMesh mesh_flexspline_section(const FlexsplineParams& f, const std::optional<GearParams>& gear,
                                    const MeshParams& mesh, std::optional<std::pair<double, double>> band) {
  validate_flexspline(f, mesh);
  check_teeth_on_rim(f, gear);
  if (f.teeth == TeethModel::Explicit)
    throw InputError("flexspline.teeth = \"explicit\": the toothed rim is not a body of revolution; the harmonic "
                     "solver takes teeth = \"ring\" or \"none\" (solver.method = \"tet10\" takes explicit teeth)");
  const SectionSizes s = section_sizes(f, gear, mesh);
  SectionBuilder b;
  add_wall_blocks(b, s, axial_breaks(s, band));
  if (s.cup) {
    add_elbow_blocks(b, s);
    add_diaphragm_and_boss_blocks(b, s, mesh);
  }
  SectionMesh out = b.finish();
  if (s.layer_cells > 0) out.tooth_layer = tooth_layer(s, *gear);
  return out;
}

double ToothLayer::at(double r_m) const { return interpolate_clamped(radius_m, solidity, r_m); }

Eigen::Matrix<double, 6, 1> t6_shape(double xi, double eta) {
  const double l1 = 1 - xi - eta, l2 = xi, l3 = eta;
  Eigen::Matrix<double, 6, 1> N;
  N << l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), l3 * (2 * l3 - 1), 4 * l1 * l2, 4 * l2 * l3, 4 * l3 * l1;
  return N;
}

Eigen::Matrix<double, 2, 6> t6_shape_derivatives(double xi, double eta) {
  const double l1 = 1 - xi - eta, l2 = xi, l3 = eta;
  Eigen::Matrix<double, 2, 6> d;
  // d/dξ: dL1 = −1, dL2 = 1, dL3 = 0; d/dη: dL1 = −1, dL2 = 0, dL3 = 1.
  d.row(0) << -(4 * l1 - 1), 4 * l2 - 1, 0, 4 * (l1 - l2), 4 * l3, -4 * l3;
  d.row(1) << -(4 * l1 - 1), 0, 4 * l3 - 1, -4 * l2, 4 * l2, 4 * (l1 - l3);
  return d;
}

std::pair<long, Eigen::Vector2d> locate_in_section(const SectionMesh& s, const Eigen::Vector2d& rz) {
  constexpr double kTol = 1e-9;
  for (std::size_t e = 0; e < s.triangles.size(); ++e) {
    const auto& t = s.triangles[e];
    Eigen::Matrix<double, 6, 2> X;
    for (int a = 0; a < 6; ++a) X.row(a) = s.nodes.row(t[a]);
    const Eigen::Vector2d lo = X.colwise().minCoeff().transpose(), hi = X.colwise().maxCoeff().transpose();
    const double pad = 0.25 * (hi - lo).maxCoeff();
    if ((rz.array() < lo.array() - pad).any() || (rz.array() > hi.array() + pad).any()) continue;
    // Newton on the isoparametric map from the straight triangle's natural coordinates.
    Eigen::Matrix2d A;
    A.col(0) = (X.row(1) - X.row(0)).transpose();
    A.col(1) = (X.row(2) - X.row(0)).transpose();
    Eigen::Vector2d q = A.inverse() * (rz - X.row(0).transpose());
    for (int it = 0; it < 20; ++it) {
      const Eigen::Vector2d x = X.transpose() * t6_shape(q[0], q[1]);
      const Eigen::Matrix2d J = (t6_shape_derivatives(q[0], q[1]) * X).transpose();  // dx/dq
      const Eigen::Vector2d dq = J.inverse() * (rz - x);
      q += dq;
      if (dq.norm() < 1e-14) break;
    }
    if (q[0] >= -kTol && q[1] >= -kTol && q[0] + q[1] <= 1 + kTol &&
        (X.transpose() * t6_shape(q[0], q[1]) - rz).norm() < 1e-9 * (hi - lo).maxCoeff() + 1e-15)
      return {static_cast<long>(e), q};
  }
  return {-1, Eigen::Vector2d::Zero()};
}

}  // namespace sw
