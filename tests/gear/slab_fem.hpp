#pragma once
// Explicit-tooth FEM of one loaded tooth: the slab of mesh/tooth_slab under plane strain, body held at the bore
// (contact/tooth_fem.hpp's ClampedSlab), a line load along the involute's
// normal at the contact radius spread over a small elliptic (Hertzian) strip. The deflection is read, along the load,
// at the tooth's centre line at the height of the contact point (Weber's convention: no local indentation).
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "fem/elasticity.hpp"
#include "contact/loaded_contact.hpp"
#include "contact/tooth_fem.hpp"
#include "fem/loads.hpp"
#include "fem/post.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/tooth_slab.hpp"

namespace sw::test {

struct SlabResult {
  double compliance_m2_per_N = 0;  ///< centre-line deflection along the load per line load
  std::size_t nodes = 0;
};

/// FEM compliance of flexspline tooth 0 of `g` loaded on its ccw flank at `contact_radius_m`.
inline SlabResult slab_compliance(const GearParams& g, const Material& mat, const ToothSlabOptions& opt,
                                  double contact_radius_m, double strip_half_width_m) {
  const ClampedSlab model(mesh_tooth_slab(g, opt), mat);
  const ToothSlab& slab = model.slab();
  const TetMesh& m = slab.mesh;

  const Involute fl = flexspline_flank(g);
  const double u = roll_at_radius(fl.base_radius, contact_radius_m);
  const Eigen::Vector2d P2 = involute_point(fl, u);
  const Eigen::Vector3d P(P2.x(), P2.y(), 0.0);
  const double a = fl.epsilon - u;
  const Eigen::Vector3d dir(std::sin(a), -std::cos(a), 0.0);  // −e′(ε − u): into the tooth
  const double b = strip_half_width_m;
  auto dist = [&](const Eigen::Vector3d& x) { return std::hypot(x.x() - P.x(), x.y() - P.y()); };
  const auto faces = select_faces(m, kSurfaceRimOuter, [&](const Eigen::Vector3d& c) { return c.y() > 0 && dist(c) < 3 * b; });
  auto shape = [&](const Eigen::Vector3d& x) { const double s = dist(x) / b; return s < 1 ? std::sqrt(1 - s * s) : 0.0; };
  const double w = 1e3;  // N/m (linear problem: any value)
  const double scale = w * slab.depth_m / faces_integral(m, faces, shape);
  const Eigen::VectorXd f = traction_load(m, faces, [&](const Eigen::Vector3d& x, const Eigen::Vector3d&) {
    return Eigen::Vector3d(scale * shape(x) * dir);
  });
  const Eigen::Vector3d uc = PointSampler(m).displacement(Eigen::Vector3d(P.x(), 0.0, 0.5 * slab.depth_m), model.solve(f));
  return {uc.dot(dir) / w, m.n_nodes()};
}

/// What the 3-D model's ring already holds of one flank's load: mesh/tooth_slab's ring slab (the teeth smeared into
/// the ring of flexspline.teeth = "ring", outer radius r_root + (r_tip − r_root)/2), plane strain, held at the bore, loaded by contact/'s flank pattern (1 N along the contact normal at
/// `contact_radius_m` carried down a rigid tooth: hats of force and foot moment on the outer surface)
/// and read work-conjugately (fᵀu), as the influence coefficients read it. Per unit line load (m²/N).
inline double ring_slab_compliance(const GearParams& g, const Material& mat, const ToothSlabOptions& opt,
                                   double contact_radius_m) {
  const GearRadii radii = gear_radii(g);
  const ClampedSlab model(mesh_ring_slab(g, opt, radii.root_f + 0.5 * (radii.tip_f - radii.root_f)), mat);
  const TetMesh& m = model.slab().mesh;
  const double depth = model.slab().depth_m, pitch = 2 * 3.14159265358979323846 / g.teeth_flexspline;
  const Involute fl = flexspline_flank(g);
  const double u = roll_at_radius(fl.base_radius, contact_radius_m);
  const Eigen::Vector2d P = involute_point(fl, u);
  const double a = fl.epsilon - u;
  const Eigen::Vector2d dir(std::sin(a), -std::cos(a));  // as slab_compliance: into the tooth
  const Eigen::VectorXd f = FlankLoads(m, pitch).pattern({std::atan2(P.y(), P.x())}, dir, P.norm());
  return f.dot(model.solve(f)) * depth;  // 1 N over the depth: a line load of 1/depth N/m
}

}  // namespace sw::test
