#include "fem/post.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

#include "common/error.hpp"
#include "fem/assembly.hpp"
#include "fem/elasticity.hpp"

namespace sw {

RowMatrixX6d nodal_stress(const TetMesh& mesh, const Material& material, const Eigen::VectorXd& u) {
  const std::size_t n = mesh.n_nodes();
  RowMatrixX6d s = RowMatrixX6d::Zero(n, 6);
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(n);
  const Matrix6d D = elasticity_matrix(material);
  const auto& X = tet10_node_coordinates();
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    const ElementCoords x = element_coordinates(mesh, e);
    Eigen::Matrix<double, 30, 1> ue;
    for (int a = 0; a < 10; ++a) ue.segment<3>(3 * a) = u.segment<3>(3 * mesh.tets[e][a]);
    const double vol = tet10_volume(x);
    for (int a = 0; a < 10; ++a) {
      const Eigen::Matrix<double, 6, 1> sigma = D * (tet10_strain_matrix(x, X.row(a).transpose()) * ue);
      s.row(mesh.tets[e][a]) += vol * sigma.transpose();
      weight[mesh.tets[e][a]] += vol;
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    if (weight[i] > 0) s.row(i) /= weight[i];
  return s;
}

Eigen::VectorXd von_mises(const RowMatrixX6d& s) {
  Eigen::VectorXd vm(s.rows());
  for (Eigen::Index i = 0; i < s.rows(); ++i) {
    const double a = s(i, 0) - s(i, 1), b = s(i, 1) - s(i, 2), c = s(i, 2) - s(i, 0);
    vm[i] = std::sqrt(0.5 * (a * a + b * b + c * c) + 3 * (s(i, 3) * s(i, 3) + s(i, 4) * s(i, 4) + s(i, 5) * s(i, 5)));
  }
  return vm;
}

CylindricalFields cylindrical_components(const TetMesh& mesh, const Eigen::VectorXd& u, const RowMatrixX6d& s) {
  const std::size_t n = mesh.n_nodes();
  CylindricalFields c;
  c.u_r.resize(n); c.u_theta.resize(n); c.s_rr.resize(n); c.s_thetatheta.resize(n); c.s_zz.resize(n);
  c.s_ztheta.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = mesh.nodes(i, 0), y = mesh.nodes(i, 1);
    const double r = std::hypot(x, y);
    const double cs = r > 0 ? x / r : 1.0, sn = r > 0 ? y / r : 0.0;
    c.u_r[i] = cs * u[3 * i] + sn * u[3 * i + 1];
    c.u_theta[i] = -sn * u[3 * i] + cs * u[3 * i + 1];
    const double sxx = s(i, 0), syy = s(i, 1), szz = s(i, 2), syz = s(i, 3), sxz = s(i, 4), sxy = s(i, 5);
    c.s_rr[i] = cs * cs * sxx + sn * sn * syy + 2 * cs * sn * sxy;
    c.s_thetatheta[i] = sn * sn * sxx + cs * cs * syy - 2 * cs * sn * sxy;
    c.s_zz[i] = szz;
    c.s_ztheta[i] = -sn * sxz + cs * syz;
  }
  return c;
}

double moment_about_z(const TetMesh& mesh, const Eigen::VectorXd& f, const std::vector<bool>& mask) {
  double m = 0;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (mask[i]) m += mesh.nodes(i, 0) * f[3 * i + 1] - mesh.nodes(i, 1) * f[3 * i];
  return m;
}

double rigid_rotation_z(const RowMatrixX3d& p, const RowMatrixX3d& d) {
  // Unknowns (t_x, t_y, θ): d_x ≈ t_x − θ·y, d_y ≈ t_y + θ·x. Normal equations 3 x 3.
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    const Eigen::Vector3d gx(1, 0, -p(i, 1)), gy(0, 1, p(i, 0));
    A += gx * gx.transpose() + gy * gy.transpose();
    b += gx * d(i, 0) + gy * d(i, 1);
  }
  return A.fullPivLu().solve(b)[2];
}

PointSampler::PointSampler(const TetMesh& mesh) : mesh_(mesh) {
  lo_ = mesh.nodes.colwise().minCoeff().transpose();
  const Eigen::Vector3d hi = mesh.nodes.colwise().maxCoeff().transpose();
  const double n_target = std::max<double>(1.0, mesh.tets.size() / 4.0);
  const Eigen::Vector3d ext = (hi - lo_).cwiseMax(1e-12);
  const double h = std::cbrt(ext.prod() / n_target);
  for (int k = 0; k < 3; ++k) {
    dims_[k] = std::clamp(static_cast<int>(ext[k] / h) + 1, 1, 512);
    cell_[k] = ext[k] / dims_[k] * (1 + 1e-9);
  }
  bins_.resize(static_cast<std::size_t>(dims_.prod()));
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    Eigen::Vector3d a = mesh.nodes.row(mesh.tets[e][0]).transpose(), b = a;
    for (int v : mesh.tets[e]) {
      a = a.cwiseMin(mesh.nodes.row(v).transpose());
      b = b.cwiseMax(mesh.nodes.row(v).transpose());
    }
    Eigen::Vector3i i0, i1;
    for (int k = 0; k < 3; ++k) {
      i0[k] = std::clamp(static_cast<int>((a[k] - lo_[k]) / cell_[k]), 0, dims_[k] - 1);
      i1[k] = std::clamp(static_cast<int>((b[k] - lo_[k]) / cell_[k]), 0, dims_[k] - 1);
    }
    for (int i = i0[0]; i <= i1[0]; ++i)
      for (int j = i0[1]; j <= i1[1]; ++j)
        for (int k = i0[2]; k <= i1[2]; ++k) bins_[(static_cast<std::size_t>(k) * dims_[1] + j) * dims_[0] + i].push_back(static_cast<int>(e));
  }
}

std::pair<long, Eigen::Vector3d> PointSampler::locate(const Eigen::Vector3d& x) const {
  Eigen::Vector3i c;
  for (int k = 0; k < 3; ++k) {
    c[k] = static_cast<int>(std::floor((x[k] - lo_[k]) / cell_[k]));
    if (c[k] < 0 || c[k] >= dims_[k]) return {-1, Eigen::Vector3d::Zero()};
  }
  constexpr double kInsideTol = 1e-9;
  long best = -1;
  double best_violation = 1e9;
  Eigen::Vector3d best_xi = Eigen::Vector3d::Zero();
  for (int e : bins_[(static_cast<std::size_t>(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0]]) {
    const ElementCoords X = element_coordinates(mesh_, static_cast<std::size_t>(e));
    // Start from the straight (corner) tetrahedron's barycentrics, then Newton on the isoparametric map.
    Eigen::Matrix3d J;
    for (int k = 0; k < 3; ++k) J.col(k) = (X.row(k + 1) - X.row(0)).transpose();
    Eigen::Vector3d xi = J.lu().solve(x - X.row(0).transpose());
    for (int it = 0; it < 8; ++it) {
      const Eigen::Vector3d r = X.transpose() * tet10_shape(xi) - x;
      const Eigen::Matrix3d Jc = X.transpose() * tet10_shape_gradient(xi);
      const Eigen::Vector3d dxi = Jc.lu().solve(r);
      xi -= dxi;
      if (dxi.norm() < 1e-13) break;
    }
    const double violation = std::max({-xi[0], -xi[1], -xi[2], xi.sum() - 1.0});
    if (violation < kInsideTol) return {e, xi};
    if (violation < best_violation) {
      best_violation = violation;
      best = e;
      best_xi = xi;
    }
  }
  // Points on a faceted boundary may fall a hair outside every element: accept a small overshoot.
  if (best_violation < 1e-3) return {best, best_xi};
  return {-1, Eigen::Vector3d::Zero()};
}

Eigen::VectorXd PointSampler::interpolate(const Eigen::Vector3d& x,
                                          const Eigen::Ref<const Eigen::MatrixXd>& field) const {
  const auto [e, xi] = locate(x);
  if (e < 0)
    throw InputError("sample point (" + std::to_string(x[0] * 1e3) + ", " + std::to_string(x[1] * 1e3) + ", " +
                     std::to_string(x[2] * 1e3) + ") mm lies outside the mesh");
  const auto N = tet10_shape(xi);
  Eigen::VectorXd v = Eigen::VectorXd::Zero(field.cols());
  for (int a = 0; a < 10; ++a) v += N[a] * field.row(mesh_.tets[e][a]).transpose();
  return v;
}

Eigen::Vector3d PointSampler::displacement(const Eigen::Vector3d& x, const Eigen::VectorXd& u) const {
  const auto [e, xi] = locate(x);
  if (e < 0)
    throw InputError("sample point (" + std::to_string(x[0] * 1e3) + ", " + std::to_string(x[1] * 1e3) + ", " +
                     std::to_string(x[2] * 1e3) + ") mm lies outside the mesh");
  const auto N = tet10_shape(xi);
  Eigen::Vector3d d = Eigen::Vector3d::Zero();
  for (int a = 0; a < 10; ++a) d += N[a] * u.segment<3>(3 * mesh_.tets[e][a]);
  return d;
}

}  // namespace sw
