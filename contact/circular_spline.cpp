#include "contact/circular_spline.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "contact/hat_patterns.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {
namespace {

// The ring's section. Radially: cells a quarter module deep at the inner surface (a pitch-wide hat's harmonics up to
// n ≈ z_c decay over r/n ≈ m/2), growing by 0.4 of their distance from it up to 0.15 of the ring's depth. Bolted on a
// face: cells one module wide at the held annulus's edges (where the face's support ends and the stress is singular),
// growing alike, radially and toward the free face. Axially at most one pitch and a quarter of the width. Measured on
// the size-17 ring against a section about four times finer each way: the block within 0.05 % held outside, within
// 0.5 % on its diagonal and 1.5 % off it bolted on its face (the singular edges converge slowly).
constexpr double kFirstCellPerModule = 0.25, kCellGrowth = 0.4, kLargestCellPerDepth = 0.15;
constexpr double kEdgeCellPerModule = 1.0, kAxialCellsPerWidth = 4;

std::string mm(double m) {
  std::ostringstream s;
  s << m * 1e3;
  return s.str();
}

/// Cell corners from a to b (both included) for a cell size s(x) > 0: ⌈∫ dx/s⌉ cells, equal in ∫ dx/s.
template <class Size>
std::vector<double> corners(double a, double b, const Size& s) {
  constexpr int kSamples = 400;
  std::vector<double> x(kSamples + 1), t(kSamples + 1, 0.0);
  for (int i = 0; i <= kSamples; ++i) x[i] = a + (b - a) * i / kSamples;
  for (int i = 1; i <= kSamples; ++i) t[i] = t[i - 1] + (x[i] - x[i - 1]) * 0.5 * (1 / s(x[i - 1]) + 1 / s(x[i]));
  const int n = std::max(1, static_cast<int>(std::ceil(t.back() - 1e-9)));
  std::vector<double> out{a};
  for (int k = 1; k < n; ++k) {
    const double target = t.back() * k / n;
    const auto it = std::lower_bound(t.begin(), t.end(), target);
    const std::size_t i = static_cast<std::size_t>(it - t.begin());
    out.push_back(x[i - 1] + (x[i] - x[i - 1]) * (target - t[i - 1]) / (t[i] - t[i - 1]));
  }
  out.push_back(b);
  return out;
}

/// Corners through every break (sorted here; the first and last are the ends), cells of size s(x) between them.
template <class Size>
std::vector<double> corners_through(std::vector<double> breaks, const Size& s) {
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  std::vector<double> out{breaks.front()};
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const std::vector<double> piece = corners(breaks[k], breaks[k + 1], s);
    out.insert(out.end(), piece.begin() + 1, piece.end());
  }
  return out;
}

/// The ring's meridian section: radial node lines through the bolt circles, axial ones through the slices' bands' ends.
SectionMesh ring_section(const CircularSplineParams& c, double root_m, double module_m, int z_c, int slices) {
  const double depth = c.outer_radius_m - root_m, edge = kEdgeCellPerModule * module_m;
  const bool bolted = c.mounting == CircularSplineMounting::BoltedFace;
  const std::vector<double> bolts = {c.bolt_circle_inner_m, c.bolt_circle_outer_m};
  const auto radial = [&](double r) {
    double s = std::min(kFirstCellPerModule * module_m + kCellGrowth * (r - root_m), kLargestCellPerDepth * depth);
    for (const double b : bolts) s = bolted ? std::min(s, edge + kCellGrowth * std::abs(r - b)) : s;
    return s;
  };
  const double axial_max = std::min(2 * kPi * root_m / z_c, c.width_m / kAxialCellsPerWidth);
  const auto axial = [&](double z) {
    return bolted ? std::min(axial_max, edge + kCellGrowth * (c.width_m - z)) : axial_max;
  };
  std::vector<double> r_breaks{root_m, c.outer_radius_m}, z_breaks;
  if (bolted) r_breaks.insert(r_breaks.end(), bolts.begin(), bolts.end());
  z_breaks.push_back(0);
  for (int j = 0; j < slices; ++j) z_breaks.push_back(c.width_m * face_slice(j, slices).hi);
  return mesh_annulus_section(corners_through(r_breaks, radial), corners_through(z_breaks, axial));
}

/// The nodes the mounting holds: the outside cylinder, or the annulus between the bolt circles on the end face z =
/// width.
std::vector<bool> held_nodes(const SectionMesh& s, const CircularSplineParams& c) {
  const double tol = 1e-9 * c.outer_radius_m;
  std::vector<bool> held(s.n_nodes(), false);
  for (std::size_t i = 0; i < s.n_nodes(); ++i) {
    const double r = s.nodes(static_cast<Eigen::Index>(i), 0), z = s.nodes(static_cast<Eigen::Index>(i), 1);
    held[i] = c.mounting == CircularSplineMounting::Outer
                  ? r >= c.outer_radius_m - tol
                  : z >= c.width_m - tol && r >= c.bolt_circle_inner_m - tol && r <= c.bolt_circle_outer_m + tol;
  }
  return held;
}

/// The bands of the inner surface: the whole width, then each slice when more than one.
std::vector<SurfaceBand> inner_bands(const CircularSplineParams& c, int slices) {
  std::vector<SurfaceBand> b{{kSurfaceInner}};
  for (int j = 0; slices > 1 && j < slices; ++j)
    b.push_back({kSurfaceInner, c.width_m * face_slice(j, slices).lo, c.width_m * face_slice(j, slices).hi});
  return b;
}

}  // namespace

std::string to_string(CircularSplineMounting m) {
  return m == CircularSplineMounting::Outer ? "outer" : "bolted_face";
}

CircularSplineParams default_circular_spline(const GearParams& gear, double face_width_m) {
  const double pitch_diameter = gear.module_m * gear.teeth_circular;
  CircularSplineParams c;
  c.outer_radius_m = 0.5 * kCircularSplineOuterDiameterPerPitchDiameter * pitch_diameter;
  c.width_m = face_width_m;
  std::tie(c.bolt_circle_inner_m, c.bolt_circle_outer_m) = default_bolt_circles_m(gear_radii(gear).root_c,
                                                                                  c.outer_radius_m);
  return c;
}

std::pair<double, double> default_bolt_circles_m(double root_radius_m, double outer_radius_m) {
  const double depth = outer_radius_m - root_radius_m;
  return {root_radius_m + kBoltCircleInnerFraction * depth, root_radius_m + kBoltCircleOuterFraction * depth};
}

const std::vector<CaseKey<CircularSplineParams>>& circular_spline_keys() {
  using C = CircularSplineParams;
  const auto bolted = [](const C& c) { return c.mounting == CircularSplineMounting::BoltedFace; };
  static const std::vector<CaseKey<C>> keys = {
      number_key<C>("outer_radius_mm", &C::outer_radius_m, 1e-3, "mm", any_value(),
                    "the ring's outer radius, > its root radius")
          .with_default("0.7 x the pitch diameter z_c m (design rule)"),
      number_key<C>("width_mm", &C::width_m, 1e-3, "mm", any_value(), "the ring's axial width, > 0")
          .with_default("flexspline.rim_width_mm (the toothed face)"),
      choice_key<C>("mounting", &C::mounting,
                    {{to_string(CircularSplineMounting::Outer), CircularSplineMounting::Outer},
                     {to_string(CircularSplineMounting::BoltedFace), CircularSplineMounting::BoltedFace}},
                    "held on its outside cylinder, or bolted by its end face (as catalog drives are)"),
      number_key<C>("bolt_circle_inner_mm", &C::bolt_circle_inner_m, 1e-3, "mm", any_value(),
                    "inner edge of the held annulus on the end face, >= the root radius")
          .with_default("0.4 of the way from the root circle to the outer radius (the bolt heads' footprint)")
          .only_when(bolted, "mounting = \"bolted_face\""),
      number_key<C>("bolt_circle_outer_mm", &C::bolt_circle_outer_m, 1e-3, "mm", any_value(),
                    "outer edge of the held annulus, in (bolt_circle_inner_mm, outer_radius_mm]")
          .with_default("0.8 of the way from the root circle to the outer radius")
          .only_when(bolted, "mounting = \"bolted_face\""),
  };
  return keys;
}

void validate_circular_spline(const CircularSplineParams& c, double root_radius_m, const std::string& file) {
  const std::string at = file.empty() ? "" : file + ": ";
  if (!(c.width_m > 0)) throw InputError(at + "circular_spline.width_mm = " + mm(c.width_m) + "; must be > 0");
  if (!(c.outer_radius_m > root_radius_m))
    throw InputError(at + "circular_spline.outer_radius_mm = " + mm(c.outer_radius_m) +
                     "; must be > the circular spline's root radius " + mm(root_radius_m) + " mm (from [gear])");
  if (c.mounting != CircularSplineMounting::BoltedFace) return;
  if (!(c.bolt_circle_inner_m >= root_radius_m))
    throw InputError(at + "circular_spline.bolt_circle_inner_mm = " + mm(c.bolt_circle_inner_m) +
                     "; must be >= the circular spline's root radius " + mm(root_radius_m) + " mm (from [gear])");
  if (!(c.bolt_circle_outer_m <= c.outer_radius_m))
    throw InputError(at + "circular_spline.bolt_circle_outer_mm = " + mm(c.bolt_circle_outer_m) +
                     "; must be <= circular_spline.outer_radius_mm = " + mm(c.outer_radius_m));
  if (!(c.bolt_circle_inner_m < c.bolt_circle_outer_m))
    throw InputError(at + "circular_spline.bolt_circle_inner_mm = " + mm(c.bolt_circle_inner_m) +
                     "; must be < circular_spline.bolt_circle_outer_mm = " + mm(c.bolt_circle_outer_m));
}

CircularSplineRing circular_spline_ring(const CircularSplineParams& c, const GearParams& g, const Material& m,
                                        int slices, int harmonics) {
  const double root = gear_radii(g).root_c;
  validate_circular_spline(c, root);
  Stopwatch clock;
  CircularSplineRing ring;
  ring.slices = std::max(1, slices);
  ring.section = ring_section(c, root, g.module_m, g.teeth_circular, ring.slices);
  ring.held = held_nodes(ring.section, c);
  ring.material = m;
  ring.pitch_rad = 2 * kPi / g.teeth_circular;
  ring.harmonics = harmonics > 0 ? harmonics : kCircularSplineHarmonicsPerTooth * g.teeth_circular;
  std::vector<bool> fixed(3 * ring.section.n_nodes());
  for (std::size_t i = 0; i < ring.held.size(); ++i) fixed[3 * i] = fixed[3 * i + 1] = fixed[3 * i + 2] = ring.held[i];
  ring.bands = band_responses(ring.section, m, fixed, inner_bands(c, ring.slices), ring.harmonics,
                              g.teeth_flexspline % 2 != 0);
  progress("contact: the circular spline's ring (" + to_string(c.mounting) + ", " +
           std::to_string(ring.section.n_nodes()) + " section nodes, harmonics 0.." + std::to_string(ring.harmonics) +
           ") in " + std::to_string(clock.lap()) + " s");
  return ring;
}

CircularSplineBlock circular_spline_block(const CircularSplineRing& ring, const std::vector<FlankPattern>& patterns) {
  std::vector<const BandResponse*> r;
  for (const BandResponse& b : ring.bands) r.push_back(&b);
  for (const FlankPattern& p : patterns)
    if (ring.slices > 1 && p.slice >= ring.slices)
      throw std::logic_error("the circular spline's ring has no slice " + std::to_string(p.slice));
  const Eigen::Index np = static_cast<Eigen::Index>(patterns.size()), B = static_cast<Eigen::Index>(r.size());
  const Eigen::VectorXd& radius = ring.section.nodes.col(0);
  auto m = std::make_shared<Moments>();
  m->sym.assign(ring.harmonics + 1, Eigen::MatrixXd::Zero(np, 2 * B));
  m->anti = m->sym;
  add_flanks(*m, patterns, ring.slices, r, radius, ring.pitch_rad);
  CircularSplineBlock out;
  out.A = influence_of(*m, r);
  // The loads' moment about z: −Σ r_i·F_θ,i of their harmonic-0 antisymmetric generalised forces
  // (fem/fourier_solver.cpp moment_z), F_θ = Φa₀(·, θ)·S per band.
  out.moment_m = Eigen::VectorXd::Zero(np);
  for (Eigen::Index b = 0; b < B; ++b) out.moment_m -= m->anti[0].col(2 * b + 1) * radius.dot(r[b]->S);
  out.mounting_torque_Nm = [&ring, m, r](const Eigen::VectorXd& x) {
    return -clamp_reaction_moment(ring.section, ring.material, ring.held, field_of(*m, r, x), anti0_loads(*m, r, x));
  };
  return out;
}

}  // namespace sw
