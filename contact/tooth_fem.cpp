#include "contact/tooth_fem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Dense>

#include "common/error.hpp"
#include "common/progress.hpp"
#include "contact/contact_body.hpp"
#include "contact/tet10_body.hpp"
#include "fem/assembly.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/loads.hpp"
#include "fem/post.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/tooth_slab.hpp"

namespace sw {
namespace {

DofMap bore_clamped(const TetMesh& m, bool plane_strain) {
  std::vector<bool> fixed(3 * m.n_nodes(), false);
  for (std::size_t i = 0; i < m.n_nodes() && plane_strain; ++i) fixed[3 * i + 2] = true;
  for (const auto& f : m.faces)
    if (f.marker == kSurfaceClamped)
      for (int a : f.nodes) fixed[3 * a] = fixed[3 * a + 1] = fixed[3 * a + 2] = true;
  return make_dof_map(fixed);
}

/// The flexspline flank's point at contact radius rc and the load's direction there: −e′(ε − u), into the tooth.
struct FlankPoint {
  Eigen::Vector2d P;
  Eigen::Vector3d dir;
};
FlankPoint flank_point(const Involute& fl, double rc) {
  const double u = roll_at_radius(fl.base_radius, rc), a = fl.epsilon - u;
  return {involute_point(fl, u), Eigen::Vector3d(std::sin(a), -std::cos(a), 0.0)};
}

/// The explicit slab's load: `force_N` along the flank point's direction, spread over the elliptic strip of half-width
/// `strip_m` about it on the loaded tooth's outline, on the faces whose centroids lie in z ∈ [z_lo, z_hi).
Eigen::VectorXd strip_load(const TetMesh& m, const FlankPoint& p, double strip_m, double force_N,
                           double z_lo = -std::numeric_limits<double>::infinity(),
                           double z_hi = std::numeric_limits<double>::infinity()) {
  auto dist = [&](const Eigen::Vector3d& x) { return std::hypot(x.x() - p.P.x(), x.y() - p.P.y()); };
  auto shape = [&](const Eigen::Vector3d& x) { const double s = dist(x) / strip_m; return s < 1 ? std::sqrt(1 - s * s) : 0.0; };
  const auto faces = select_faces(m, kSurfaceRimOuter, [&](const Eigen::Vector3d& c) {
    return c.y() > 0 && dist(c) < 3 * strip_m && c.z() >= z_lo && c.z() < z_hi;
  });
  const double area = faces.empty() ? 0.0 : faces_integral(m, faces, shape);
  if (!(area > 0)) throw InputError("tooth FEM: no flank surface under the load's strip");
  const double scale = force_N / area;
  return traction_load(m, faces, [&](const Eigen::Vector3d& x, const Eigen::Vector3d&) {
    return Eigen::Vector3d(scale * shape(x) * p.dir);
  });
}

}  // namespace

ClampedSlab::ClampedSlab(ToothSlab s, const Material& m, bool plane_strain)
    : slab_(std::move(s)), dofs_(bore_clamped(slab_.mesh, plane_strain)),
      factor_(assemble_stiffness(slab_.mesh, m, dofs_), equation_nodes(dofs_)) {}

Eigen::VectorXd ClampedSlab::solve(const Eigen::VectorXd& f) const {
  return expand_to_full(dofs_, factor_.solve(restrict_to_free(dofs_, f)), Eigen::VectorXd::Zero(f.size()));
}

double FlexsplineToothFem::operator()(double r) const {
  const auto n = radius_m.size();
  r = std::clamp(r, radius_m.front(), radius_m.back());
  std::size_t j = std::upper_bound(radius_m.begin(), radius_m.end(), r) - radius_m.begin();
  j = std::clamp<std::size_t>(j, 1, n - 1);
  const double a = (r - radius_m[j - 1]) / (radius_m[j] - radius_m[j - 1]);
  auto tooth = [&](std::size_t i) { return std::max(0.0, explicit_m2_per_N[i] - ring_m2_per_N[i]); };
  return (1 - a) * tooth(j - 1) + a * tooth(j);
}

FlexsplineToothFem flexspline_tooth_fem(const GearParams& g, const Material& mat, double bore_radius_m,
                                        double ring_outer_radius_m, int samples, int points_per_flank) {
  if (samples < 2) throw InputError("tooth FEM: need at least 2 contact radii");
  Stopwatch clock;
  const GearRadii r = gear_radii(g);
  ToothSlabOptions o;
  o.bore_radius_m = bore_radius_m;
  o.points_per_flank = points_per_flank;
  const double spacing = (r.tip_f - r.form_f) / (points_per_flank - 1);
  const double strip = 2 * spacing;  // the elliptic strip's half-width: two outline segments
  const ClampedSlab toothed(mesh_tooth_slab(g, o), mat), ring(mesh_ring_slab(g, o, ring_outer_radius_m), mat);
  const FlankLoads patterns(ring.slab().mesh, 2 * std::numbers::pi / g.teeth_flexspline);
  const PointSampler sampler(toothed.slab().mesh);
  const Involute fl = flexspline_flank(g);
  const double top = r.tip_f - 0.005 * (r.tip_f - r.form_f);
  FlexsplineToothFem out;
  for (int k = 0; k < samples; ++k) {
    const double rc = r.form_f + (top - r.form_f) * k / (samples - 1);
    const FlankPoint fp = flank_point(fl, rc);
    const Eigen::Vector2d& P = fp.P;
    const Eigen::Vector3d& dir = fp.dir;
    // explicit: w = 1 N/m over the strip (depth N over the slab), read at the centre line
    const Eigen::VectorXd f = strip_load(toothed.slab().mesh, fp, strip, toothed.slab().depth_m);
    const Eigen::Vector3d uc = sampler.displacement(Eigen::Vector3d(P.x(), 0.0, 0.5 * toothed.slab().depth_m), toothed.solve(f));
    // ring: contact/'s pattern of 1 N over the depth, read fᵀu
    const Eigen::Vector2d d2(dir.x(), dir.y());
    const Eigen::VectorXd fr = patterns.pattern({std::atan2(P.y(), P.x())}, d2, P.norm());
    out.radius_m.push_back(rc);
    out.explicit_m2_per_N.push_back(uc.dot(dir));
    out.ring_m2_per_N.push_back(fr.dot(ring.solve(fr)) * ring.slab().depth_m);
  }
  out.nodes = toothed.slab().mesh.n_nodes() + ring.slab().mesh.n_nodes();
  out.seconds = clock.lap();
  return out;
}

FaceCoupling face_coupling(const GearParams& g, const Material& mat, double bore_radius_m, double ring_outer_radius_m,
                           double face_m, int n, int points_per_flank) {
  if (n < 2) throw InputError("tooth face coupling: need at least 2 face sections, not " + std::to_string(n));
  Stopwatch clock;
  const GearRadii r = gear_radii(g);
  ToothSlabOptions o;
  o.teeth_each_side = 2;  // as flexspline_tooth_fem: its plane-strain tooth is this slab's interior (tests/gear)
  o.bore_radius_m = bore_radius_m;
  o.points_per_flank = points_per_flank;
  const double spacing = (r.tip_f - r.form_f) / (std::max(8, points_per_flank) - 1);
  o.depth_over_spacing = face_m / spacing;
  for (int j = 0; j + 1 < n; ++j) o.depth_cuts.push_back(face_slice(j, n).hi);  // each band its own whole faces
  const double strip = 2 * spacing;
  const ClampedSlab toothed(mesh_tooth_slab(g, o), mat, false), ring(mesh_ring_slab(g, o, ring_outer_radius_m), mat, false);
  const TetMesh& m = toothed.slab().mesh;
  const PointSampler sampler(m);
  const Involute fl = flexspline_flank(g);
  FaceCoupling out;
  out.radius_m = 0.5 * (r.form_f + r.tip_f);
  const FlankPoint fp = flank_point(fl, out.radius_m);
  const Eigen::Vector2d& P = fp.P;
  const Eigen::Vector3d& dir = fp.dir;
  const double depth = toothed.slab().depth_m;
  auto band = [&](int j) { const FaceSlice s = face_slice(j, n); return std::pair{depth * s.lo, depth * s.hi}; };
  std::vector<Eigen::VectorXd> u_explicit, f_ring, u_ring;
  for (int j = 0; j < n; ++j) {
    const auto [lo, hi] = band(j);
    u_explicit.push_back(toothed.solve(strip_load(m, fp, strip, 1.0, lo, hi)));  // 1 N over the band
    f_ring.push_back(FlankLoads(ring.slab().mesh, 2 * std::numbers::pi / g.teeth_flexspline, lo, hi)
                         .pattern({std::atan2(P.y(), P.x())}, Eigen::Vector2d(dir.x(), dir.y()), P.norm()));
    u_ring.push_back(ring.solve(f_ring.back()));
  }
  constexpr int kReads = 8;  // points along band i's centre line (midpoint rule)
  Eigen::MatrixXd C(n, n);
  for (int i = 0; i < n; ++i) {
    const auto [lo, hi] = band(i);
    for (int j = 0; j < n; ++j) {
      double e = 0;
      for (int k = 0; k < kReads; ++k)
        e += sampler.displacement(Eigen::Vector3d(P.x(), 0.0, lo + (hi - lo) * (k + 0.5) / kReads), u_explicit[j])
                 .dot(dir) / kReads;
      C(i, j) = e - f_ring[i].dot(u_ring[j]);
    }
  }
  C = (0.5 * (C + C.transpose())).eval();
  Eigen::VectorXd w(n);
  for (int j = 0; j < n; ++j) w[j] = face_slice(j, n).width();
  out.uniform_m2_per_N = face_m * w.dot(C * w);
  out.interior_m2_per_N = face_m * C.row(n / 2).dot(w);  // band n/2 under F_j = w_j·b·(1 N/m)
  out.shape = C * face_m / out.uniform_m2_per_N;
  if (!(out.uniform_m2_per_N > 0) || !(C.diagonal().array() > 0).all())
    throw InputError("tooth face coupling: a band's own compliance or the uniform load's is not positive");
  out.nodes = m.n_nodes() + ring.slab().mesh.n_nodes();
  out.seconds = clock.lap();
  return out;
}

}  // namespace sw
