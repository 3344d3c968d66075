#include "fem/elasticity.hpp"

#include <stdexcept>

#include <Eigen/LU>

namespace sw {
namespace {

// Degree-2 rule for the unit tetrahedron (4 points, weights 1/24): exact for the quadratic integrand B^T D B of a
// straight-sided TET10.
constexpr double kGaussA = 0.5854101966249685;
constexpr double kGaussB = 0.1381966011250105;
const std::array<Eigen::Vector3d, 4> kGaussPoints = {
    Eigen::Vector3d(kGaussB, kGaussB, kGaussB), Eigen::Vector3d(kGaussA, kGaussB, kGaussB),
    Eigen::Vector3d(kGaussB, kGaussA, kGaussB), Eigen::Vector3d(kGaussB, kGaussB, kGaussA)};
constexpr double kGaussWeight = 1.0 / 24.0;

// Edge (corner pairs) of each midside node 4..9, VTK order.
constexpr int kEdges[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};

}  // namespace

Matrix6d elasticity_matrix(const Material& m) {
  const double E = m.youngs_modulus_Pa, nu = m.poisson_ratio;
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  const double mu = E / (2 * (1 + nu));
  Matrix6d D = Matrix6d::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) D(i, j) = lambda;
    D(i, i) = lambda + 2 * mu;
    D(i + 3, i + 3) = mu;
  }
  return D;
}

Eigen::Matrix<double, 10, 1> tet10_shape(const Eigen::Vector3d& xi) {
  const double L[4] = {1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
  Eigen::Matrix<double, 10, 1> N;
  for (int i = 0; i < 4; ++i) N[i] = L[i] * (2 * L[i] - 1);
  for (int e = 0; e < 6; ++e) N[4 + e] = 4 * L[kEdges[e][0]] * L[kEdges[e][1]];
  return N;
}

Eigen::Matrix<double, 10, 3> tet10_shape_gradient(const Eigen::Vector3d& xi) {
  const double L[4] = {1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
  // dL/dξ for the four barycentric coordinates.
  static const double dL[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Eigen::Matrix<double, 10, 3> G;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) G(i, k) = (4 * L[i] - 1) * dL[i][k];
  for (int e = 0; e < 6; ++e) {
    const int a = kEdges[e][0], b = kEdges[e][1];
    for (int k = 0; k < 3; ++k) G(4 + e, k) = 4 * (dL[a][k] * L[b] + L[a] * dL[b][k]);
  }
  return G;
}

const Eigen::Matrix<double, 10, 3>& tet10_node_coordinates() {
  static const Eigen::Matrix<double, 10, 3> X = [] {
    Eigen::Matrix<double, 10, 3> c;
    c << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.5, 0, 0, 0.5, 0.5, 0, 0, 0.5, 0, 0, 0, 0.5, 0.5, 0, 0.5, 0, 0.5, 0.5;
    return c;
  }();
  return X;
}

Eigen::Matrix<double, 6, 30> tet10_strain_matrix(const ElementCoords& x, const Eigen::Vector3d& xi,
                                                 double* det_jacobian) {
  const Eigen::Matrix<double, 10, 3> dN = tet10_shape_gradient(xi);
  const Eigen::Matrix3d J = x.transpose() * dN;  // J(i,k) = dx_i/dξ_k
  const double det = J.determinant();
  if (!(det > 0)) throw std::runtime_error("inverted or degenerate TET10 element (det J <= 0)");
  if (det_jacobian) *det_jacobian = det;
  const Eigen::Matrix<double, 10, 3> dNdx = dN * J.inverse();  // dN/dx = dN/dξ · dξ/dx
  Eigen::Matrix<double, 6, 30> B = Eigen::Matrix<double, 6, 30>::Zero();
  for (int a = 0; a < 10; ++a) {
    const double gx = dNdx(a, 0), gy = dNdx(a, 1), gz = dNdx(a, 2);
    const int c = 3 * a;
    B(0, c) = gx;
    B(1, c + 1) = gy;
    B(2, c + 2) = gz;
    B(3, c + 1) = gz;
    B(3, c + 2) = gy;
    B(4, c) = gz;
    B(4, c + 2) = gx;
    B(5, c) = gy;
    B(5, c + 1) = gx;
  }
  return B;
}

Matrix30d tet10_stiffness(const ElementCoords& x, const Matrix6d& D) {
  Matrix30d K = Matrix30d::Zero();
  for (const auto& xi : kGaussPoints) {
    double det = 0;
    const Eigen::Matrix<double, 6, 30> B = tet10_strain_matrix(x, xi, &det);
    K.noalias() += (kGaussWeight * det) * (B.transpose() * (D * B));
  }
  return K;
}

double tet10_volume(const ElementCoords& x) {
  double v = 0;
  for (const auto& xi : kGaussPoints) {
    const Eigen::Matrix3d J = x.transpose() * tet10_shape_gradient(xi);
    v += kGaussWeight * J.determinant();
  }
  return v;
}

}  // namespace sw
