#pragma once
// Explicit-tooth FEM of one loaded tooth: the slab of mesh/tooth_slab under plane strain (u_z = 0 at every node, so
// the 3-D TET10 model is exactly the 2-D plane-strain one), body held at the bore, a line load along the involute's
// normal at the contact radius spread over a small elliptic (Hertzian) strip. The deflection is read, along the load,
// at the tooth's centre line at the height of the contact point (Weber's convention: no local indentation).
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Dense>

#include "fem/assembly.hpp"
#include "fem/cholmod_factor.hpp"
#include "fem/elasticity.hpp"
#include "contact/loaded_contact.hpp"
#include "fem/loads.hpp"
#include "fem/post.hpp"
#include "gear/tooth_profile.hpp"
#include "mesh/tetgen_mesh.hpp"
#include "mesh/tooth_slab.hpp"

namespace sw::test {

/// Displacement (3) at point p by TET10 interpolation in the tet that contains it (straight-sided tets).
inline Eigen::Vector3d displacement_at(const TetMesh& mesh, const Eigen::VectorXd& u, const Eigen::Vector3d& p) {
  for (const auto& t : mesh.tets) {
    Eigen::Matrix3d J;
    const Eigen::Vector3d x0 = mesh.nodes.row(t[0]).transpose();
    for (int c = 0; c < 3; ++c) J.col(c) = mesh.nodes.row(t[c + 1]).transpose() - x0;
    const Eigen::Vector3d xi = J.partialPivLu().solve(p - x0);
    if (xi.minCoeff() < -1e-9 || xi.sum() > 1 + 1e-9) continue;
    const Eigen::Matrix<double, 10, 1> N = tet10_shape(xi);
    Eigen::Vector3d out = Eigen::Vector3d::Zero();
    for (int a = 0; a < 10; ++a) out += N[a] * u.segment<3>(3 * t[a]);
    return out;
  }
  throw std::runtime_error("point outside the slab mesh");
}

struct SlabResult {
  double compliance_m2_per_N = 0;  ///< centre-line deflection along the load per line load
  std::size_t nodes = 0;
};

/// FEM compliance of flexspline tooth 0 of `g` loaded on its ccw flank at `contact_radius_m`.
inline SlabResult slab_compliance(const GearParams& g, const Material& mat, const ToothSlabOptions& opt,
                                  double contact_radius_m, double strip_half_width_m) {
  const ToothSlab slab = mesh_tooth_slab(g, opt);
  const TetMesh& m = slab.mesh;
  std::vector<bool> fixed(3 * m.n_nodes(), false);
  for (std::size_t i = 0; i < m.n_nodes(); ++i) fixed[3 * i + 2] = true;  // plane strain
  for (const auto& f : m.faces)
    if (f.marker == kSurfaceClamped)
      for (int a : f.nodes) fixed[3 * a] = fixed[3 * a + 1] = true;
  const DofMap dofs = make_dof_map(fixed);

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
  const CholmodFactor factor(assemble_stiffness(m, mat, dofs), equation_nodes(dofs));
  const Eigen::VectorXd uf = factor.solve(restrict_to_free(dofs, f));
  const Eigen::VectorXd full = expand_to_full(dofs, uf, Eigen::VectorXd::Zero(3 * m.n_nodes()));
  const Eigen::Vector3d uc = displacement_at(m, full, Eigen::Vector3d(P.x(), 0.0, 0.5 * slab.depth_m));
  return {uc.dot(dir) / w, m.n_nodes()};
}

/// What the 3-D model's ring already holds of one flank's load: the same slab with the teeth smeared into the ring of
/// flexspline.teeth = "ring" (outer radius r_root + (r_tip − r_root)/2, as mesh/flexspline), same sector, bore, depth
/// and tet size, plane strain, held at the bore, loaded by contact/'s flank pattern (1 N along the contact normal at
/// `contact_radius_m`, a linear hat one pitch wide on the outer surface, its moment forced to the normal's moment arm)
/// and read work-conjugately (fᵀu), as the influence coefficients read it. Per unit line load (m²/N).
inline double ring_slab_compliance(const GearParams& g, const Material& mat, const ToothSlabOptions& opt,
                                   double contact_radius_m) {
  constexpr double kPi = 3.14159265358979323846;
  const GearRadii r = gear_radii(g);
  const double r_o = r.root_f + 0.5 * (r.tip_f - r.root_f);
  const double spacing = (r.tip_f - r.form_f) / (std::max(8, opt.points_per_flank) - 1);
  const double pitch = 2 * kPi / g.teeth_flexspline, a_end = (opt.teeth_each_side + 0.5) * pitch;
  std::vector<Eigen::Vector2d> pts;
  std::vector<int> marker;
  const int n_out = static_cast<int>(std::ceil(2 * a_end * r_o / spacing));
  for (int i = 0; i < n_out; ++i) {  // outer arc, −a_end to +a_end
    const double a = -a_end + 2 * a_end * i / n_out;
    pts.emplace_back(r_o * std::cos(a), r_o * std::sin(a));
    marker.push_back(kSurfaceRimOuter);
  }
  const double body = r_o - opt.bore_radius_m;
  const int n_side = std::max(2, static_cast<int>(std::ceil(body / (4 * spacing))));
  for (int i = 0; i < n_side; ++i) {
    const double rad = r_o - body * i / n_side;
    pts.emplace_back(rad * std::cos(a_end), rad * std::sin(a_end));
    marker.push_back(kSurfaceRimStep);
  }
  const int n_arc = std::max(4, static_cast<int>(std::ceil(2 * a_end * opt.bore_radius_m / (6 * spacing))));
  for (int i = 0; i < n_arc; ++i) {
    const double a = a_end - 2 * a_end * i / n_arc;
    pts.emplace_back(opt.bore_radius_m * std::cos(a), opt.bore_radius_m * std::sin(a));
    marker.push_back(kSurfaceClamped);
  }
  for (int i = 0; i < n_side; ++i) {
    const double rad = opt.bore_radius_m + body * i / n_side;
    pts.emplace_back(rad * std::cos(-a_end), rad * std::sin(-a_end));
    marker.push_back(kSurfaceRimStep);
  }
  const int n = static_cast<int>(pts.size());
  const double depth = opt.depth_over_spacing * spacing;
  Plc plc;
  for (double zz : {0.0, depth})
    for (const auto& p : pts) plc.points.emplace_back(p.x(), p.y(), zz);
  PlcFacet bottom, top;
  bottom.polygons.emplace_back();
  top.polygons.emplace_back();
  for (int i = 0; i < n; ++i) bottom.polygons[0].push_back(i), top.polygons[0].push_back(n + i);
  plc.facets.push_back(bottom);
  plc.facets.push_back(top);
  for (int i = 0; i < n; ++i) {
    PlcFacet quad;
    quad.polygons.push_back({i, (i + 1) % n, n + (i + 1) % n, n + i});
    quad.marker = marker[i];
    plc.facets.push_back(quad);
  }
  TetgenOptions t;
  t.max_radius_edge_ratio = 2.0;
  const double edge = opt.max_edge_over_spacing * spacing;
  t.max_volume_m3 = edge * edge * edge / (6 * std::sqrt(2.0));
  const TetMesh m = tetrahedralize_plc(plc, t);

  std::vector<bool> fixed(3 * m.n_nodes(), false);
  for (std::size_t i = 0; i < m.n_nodes(); ++i) fixed[3 * i + 2] = true;  // plane strain
  for (const auto& f : m.faces)
    if (f.marker == kSurfaceClamped)
      for (int a : f.nodes) fixed[3 * a] = fixed[3 * a + 1] = true;
  const DofMap dofs = make_dof_map(fixed);
  const Involute fl = flexspline_flank(g);
  const double u = roll_at_radius(fl.base_radius, contact_radius_m);
  const Eigen::Vector2d P = involute_point(fl, u);
  const double a = fl.epsilon - u;
  const Eigen::Vector2d dir(std::sin(a), -std::cos(a));  // as slab_compliance: into the tooth
  const double arm = P.x() * dir.y() - P.y() * dir.x();
  const Eigen::VectorXd f = FlankLoads(m, pitch).pattern({0.0}, dir, arm);
  const CholmodFactor factor(assemble_stiffness(m, mat, dofs), equation_nodes(dofs));
  const Eigen::VectorXd uf = factor.solve(restrict_to_free(dofs, f));
  const Eigen::VectorXd full = expand_to_full(dofs, uf, Eigen::VectorXd::Zero(3 * m.n_nodes()));
  return f.dot(full) * depth;  // 1 N over the depth: a line load of 1/depth N/m
}

}  // namespace sw::test
