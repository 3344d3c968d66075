// The explicit-tooth slab and the ring slab (mesh/tooth_slab) of every flexspline `strainwave design` writes at sizes
// 14, 17, 20 and ratios 30, 50, 80, 100, 160 (design_cup, so no case file is needed): each meshes, its volume is the
// section's area times the depth, and its bore and sides carry their markers over their whole extent. Plus the ring
// slab of the size-14 ratio-50 case exactly as the case file gives it (TetGen 1.5 asserts or stalls on it with the
// section's sides drawn as chains of points; it meshes on the retry with single-segment sides) and the input errors.
//
// The areas, written out (a_end = (K + 1/2)·2π/z_f is the sector's half angle, r_b the bore, r_o the ring's outside):
//   ring slab:   A = a_end·(r_o² − r_b²)                          (annular sector)
//   tooth slab:  A = (2K + 1)/z_f · A_gear − a_end·r_b²            (the outline is periodic with the pitch 2π/z_f, so
//                any sector of 2K + 1 pitches holds (2K + 1)/z_f of the area A_gear inside flexspline_outline, which
//                is the shoelace sum over its dense polygon)
// The slab's section is a polygon on these curves, so its area differs by the chord segments: an arc of radius R cut
// into chords of angle θ loses R²·θ²/6 of area per radian of arc (sector minus triangle, θ³/12·R² per chord); on the
// bore the chords are at most 6 outline spacings s long (θ ≤ 6s/r_b; the bore is concave, the polygon gains it), on
// the ring's outside at most s. On the tooth outline, resampled at even arc lengths (s on the loaded tooth, 2s on its
// neighbours), a tip corner falls between samples and is cut by at most a triangle of legs s_k/2, s_k/2: s_k²/8 each,
// two corners per tooth: 2·s²/8 + 4·2·(2s)²/8 = 4.25·s² with K = 2. These are the tolerances, with a factor 1.5 on the
// chord terms for the shorter chords at the arcs' ends.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <numbers>
#include <string>

#include "common/error.hpp"
#include "design/proportions.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/flexspline.hpp"
#include "mesh/tetgen_mesh.hpp"
#include "mesh/tooth_slab.hpp"

namespace sw {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kPointsPerFlank = 24;  // what contact/tooth_fem.hpp's flexspline_tooth_fem passes by default
// Round-off of the TET10 volume and of the side areas (sums of some thousand terms of size 1e-13 m³ in doubles).
constexpr double kRoundOffRelative = 1e-9;
// The area bounds above are bounds; the chord count rounds up, so the arcs' chords are never longer than assumed.
constexpr double kChordMargin = 1.5;

struct Design {
  int size, ratio;
};

std::string name_of(const testing::TestParamInfo<Design>& info) {
  return "size" + std::to_string(info.param.size) + "_ratio" + std::to_string(info.param.ratio);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double shoelace_area(const std::vector<Eigen::Vector2d>& p) {
  double twice = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& a = p[i];
    const auto& b = p[(i + 1) % p.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

/// Loss of area of an arc of radius r over angle `angle` cut into chords of angle at most theta (R²θ²/6 per radian).
double chord_area(double r, double angle, double theta) { return kChordMargin * r * r * theta * theta / 6 * angle; }

bool has_marker(const TetMesh& m, int marker) {
  for (const auto& f : m.faces)
    if (f.marker == marker) return true;
  return false;
}

class ToothSlabOfDesign : public testing::TestWithParam<Design> {};

TEST_P(ToothSlabOfDesign, MeshesWithTheSectionsAreaTimesItsDepthAndItsSidesAndBoreMarked) {
  const CupDesign d = design_cup(GetParam().size, GetParam().ratio);
  const GearParams& g = d.gear;
  const GearRadii r = gear_radii(g);
  ToothSlabOptions o;
  o.bore_radius_m = d.flexspline.inner_radius_m;
  o.points_per_flank = kPointsPerFlank;
  const double r_b = o.bore_radius_m, r_o = rim_outer_radius(d.flexspline, d.gear);
  const int K = o.teeth_each_side, z = g.teeth_flexspline;
  const double a_end = (K + 0.5) * 2 * kPi / z;
  const double s = (r.tip_f - r.form_f) / (kPointsPerFlank - 1);
  const double bore_chords = chord_area(r_b, 2 * a_end, 6 * s / r_b);

  auto t0 = std::chrono::steady_clock::now();
  const ToothSlab tooth = mesh_tooth_slab(g, o);
  const double t_tooth = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const ToothSlab ring = mesh_ring_slab(g, o, r_o);
  const double t_ring = seconds_since(t0);
  std::printf("size %d ratio %d: tooth slab %ld nodes %.3f s, ring slab %ld nodes %.3f s\n", GetParam().size,
              GetParam().ratio, static_cast<long>(tooth.mesh.nodes.rows()), t_tooth,
              static_cast<long>(ring.mesh.nodes.rows()), t_ring);
  RecordProperty("tooth_slab_seconds", std::to_string(t_tooth));
  RecordProperty("ring_slab_seconds", std::to_string(t_ring));

  for (const ToothSlab* slab : {&tooth, &ring}) {
    ASSERT_GT(slab->mesh.nodes.rows(), 0);
    ASSERT_FALSE(slab->mesh.tets.empty());
    EXPECT_TRUE(has_marker(slab->mesh, kSurfaceRimOuter));
    EXPECT_TRUE(has_marker(slab->mesh, kSurfaceOther));  // the z faces
    // the bore: the chords of the arc 2·a_end·r_b, shorter than it by θ²/24 at most
    const double bore_area = 2 * a_end * r_b * slab->depth_m;
    EXPECT_NEAR(boundary_area(slab->mesh, kSurfaceClamped), bore_area, bore_area * (6 * s / r_b) * (6 * s / r_b) / 24 +
                                                                          kRoundOffRelative * bore_area);
  }
  // the two radial sides, from the bore up to the root circle (tooth slab: the outline starts and ends at mid-root) or
  // the ring's outside: rectangles, exact
  EXPECT_NEAR(boundary_area(tooth.mesh, kSurfaceRimStep), 2 * (r.root_f - r_b) * tooth.depth_m,
              kRoundOffRelative * r.root_f * tooth.depth_m);
  EXPECT_NEAR(boundary_area(ring.mesh, kSurfaceRimStep), 2 * (r_o - r_b) * ring.depth_m,
              kRoundOffRelative * r_o * ring.depth_m);

  const double ring_area = a_end * (r_o * r_o - r_b * r_b);
  const double ring_tol = bore_chords + chord_area(r_o, 2 * a_end, s / r_o) + kRoundOffRelative * ring_area;
  EXPECT_NEAR(mesh_volume(ring.mesh) / ring.depth_m, ring_area, ring_tol);

  const double tooth_area = (2 * K + 1) * shoelace_area(flexspline_outline(g, 400)) / z - a_end * r_b * r_b;
  const double tooth_tol = bore_chords + 4.25 * s * s + kRoundOffRelative * tooth_area;
  EXPECT_NEAR(mesh_volume(tooth.mesh) / tooth.depth_m, tooth_area, tooth_tol);
}

INSTANTIATE_TEST_SUITE_P(DesignedFlexsplines, ToothSlabOfDesign,
                         testing::Values(Design{14, 30}, Design{14, 50}, Design{14, 80}, Design{14, 100},
                                         Design{14, 160}, Design{17, 30}, Design{17, 50}, Design{17, 80},
                                         Design{17, 100}, Design{17, 160}, Design{20, 30}, Design{20, 50},
                                         Design{20, 80}, Design{20, 100}, Design{20, 160}),
                         name_of);

// The [gear] and [flexspline] tables of `strainwave design --size 14 --ratio 50` as the case loader reads them
// (millimetres times 1e-3). TetGen 1.5 asserted in its segment recovery on this ring slab and stalled on the retries.
GearParams case_14_50_gear() {
  GearParams g;
  g.module_m = 0.3556 * 1e-3;
  g.teeth_flexspline = 100;
  g.teeth_circular = 102;
  g.pressure_angle_rad = 20 * kPi / 180;
  g.profile_shift_flexspline = 1.52;
  g.profile_shift_circular = 1.5334591;
  g.cutter_teeth = 80;
  g.addendum_coefficient_flexspline = g.addendum_coefficient_circular = 0.7;
  g.dedendum_coefficient_flexspline = g.dedendum_coefficient_circular = 0.95;
  return g;
}

TEST(ToothSlab, MeshesTheRingSlabOfTheSize14Ratio50CaseThatTetGenRejectedBefore) {
  const GearParams g = case_14_50_gear();
  ToothSlabOptions o;
  o.bore_radius_m = 17.4556104 * 1e-3;
  o.points_per_flank = kPointsPerFlank;
  const double r_o = o.bore_radius_m + 0.49784 * 1e-3;  // rim_outer_radius of teeth = "none": bore + rim thickness
  const auto t0 = std::chrono::steady_clock::now();
  const ToothSlab ring = mesh_ring_slab(g, o, r_o);
  const double seconds = seconds_since(t0);
  std::printf("size 14 ratio 50 case: ring slab %ld nodes %.3f s\n", static_cast<long>(ring.mesh.nodes.rows()), seconds);
  const double a_end = 2.5 * 2 * kPi / 100;
  const double area = a_end * (r_o * r_o - o.bore_radius_m * o.bore_radius_m);
  const GearRadii r = gear_radii(g);
  const double s = (r.tip_f - r.form_f) / (kPointsPerFlank - 1);
  EXPECT_NEAR(mesh_volume(ring.mesh) / ring.depth_m, area,
              chord_area(o.bore_radius_m, 2 * a_end, 6 * s / o.bore_radius_m) + chord_area(r_o, 2 * a_end, s / r_o));
  // the first attempt (chains) stalls to its 10 s budget at most, the retry with straight sides meshes in well under a
  // second: under 12 s, where the old retries (more points on the chains) spent four budgets and failed
  EXPECT_LT(seconds, 12.0);
}

TEST(ToothSlab, RefusesABoreOutsideTheRootCircleNamingIt) {
  const GearParams g = case_14_50_gear();
  ToothSlabOptions o;
  o.bore_radius_m = gear_radii(g).root_f;  // must be strictly inside
  try {
    mesh_tooth_slab(g, o);
    FAIL() << "a bore on the root circle was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bore radius"), std::string::npos) << e.what();
  }
  o.bore_radius_m = 17e-3;
  o.teeth_each_side = -1;
  EXPECT_THROW(mesh_tooth_slab(g, o), InputError);
}

TEST(ToothSlab, RefusesARingWhoseOutsideIsNotBeyondTheBore) {
  const GearParams g = case_14_50_gear();
  ToothSlabOptions o;
  o.bore_radius_m = 17e-3;
  EXPECT_THROW(mesh_ring_slab(g, o, 17e-3), InputError);
  EXPECT_THROW(mesh_ring_slab(g, o, 16e-3), InputError);
}

// Depth cuts (a slab as deep as the face, cut at its sections' band ends): no tet crosses a cut plane, the volume is
// the uncut slab's section times the depth, and a cut outside (0, 1) or out of order is refused naming it.
TEST(ToothSlab, DepthCutsAreFacesNoTetCrossesAndBadCutsAreRefused) {
  const GearParams g = case_14_50_gear();
  ToothSlabOptions o;
  o.bore_radius_m = 17.4556104 * 1e-3;
  o.points_per_flank = 8;
  o.teeth_each_side = 1;
  o.depth_over_spacing = 40;
  const double r_o = o.bore_radius_m + 0.49784 * 1e-3;
  const ToothSlab plain = mesh_ring_slab(g, o, r_o);
  o.depth_cuts = {0.125, 0.375, 0.625, 0.875};
  const ToothSlab cut = mesh_ring_slab(g, o, r_o);
  EXPECT_NEAR(mesh_volume(cut.mesh) / mesh_volume(plain.mesh), 1.0, 1e-3);  // the chords: the same outline
  const double tol = 1e-9 * cut.depth_m;
  int crossing = 0;
  for (const auto& t : cut.mesh.tets)
    for (const double c : o.depth_cuts) {
      double lo = cut.depth_m, hi = 0;
      for (int k = 0; k < 4; ++k) lo = std::min(lo, cut.mesh.nodes(t[k], 2)), hi = std::max(hi, cut.mesh.nodes(t[k], 2));
      if (lo < c * cut.depth_m - tol && hi > c * cut.depth_m + tol) ++crossing;
    }
  EXPECT_EQ(crossing, 0);
  for (const std::vector<double>& bad : {std::vector<double>{0.5, 0.25}, {0.0}, {1.0}}) {
    o.depth_cuts = bad;
    try {
      mesh_tooth_slab(g, o);
      FAIL() << "accepted a bad cut";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("depth cut"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace sw
