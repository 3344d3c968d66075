#pragma once
// Quadratic tetrahedron (TET10) for isotropic linear elasticity. Node order is VTK's: corners 0..3 at natural
// coordinates (0,0,0), (1,0,0), (0,1,0), (0,0,1), then midsides of edges (0,1), (1,2), (0,2), (0,3), (1,3), (2,3).
// Strains and stresses in Voigt order (xx, yy, zz, yz, xz, xy), engineering shear strains.
#include <array>

#include <Eigen/Core>

#include "common/material.hpp"

namespace sw {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Matrix30d = Eigen::Matrix<double, 30, 30>;
using ElementCoords = Eigen::Matrix<double, 10, 3>;  ///< rows: the element's 10 node positions (m)

/// Isotropic elasticity matrix (Pa), Voigt order.
Matrix6d elasticity_matrix(const Material& material);

/// Shape function values N (10) at natural point (ξ, η, ζ).
Eigen::Matrix<double, 10, 1> tet10_shape(const Eigen::Vector3d& xi);

/// Shape function derivatives dN/dξ (10 x 3) at natural point (ξ, η, ζ).
Eigen::Matrix<double, 10, 3> tet10_shape_gradient(const Eigen::Vector3d& xi);

/// Natural coordinates of the 10 nodes (10 x 3).
const Eigen::Matrix<double, 10, 3>& tet10_node_coordinates();

/// Element stiffness (30 x 30, N/m), dof order node-major (u_x, u_y, u_z of node 0, then node 1, ...).
/// Integrated with the 4-point degree-2 Gauss rule, which is exact for straight-sided TET10 (B is linear, the
/// integrand quadratic); for elements with curved (projected) edges it is the usual isoparametric approximation.
/// Throws std::runtime_error if the element is inverted at a Gauss point.
Matrix30d tet10_stiffness(const ElementCoords& x, const Matrix6d& D);

/// Strain-displacement matrix B (6 x 30) at a natural point, and det J through `det_jacobian` if non-null.
Eigen::Matrix<double, 6, 30> tet10_strain_matrix(const ElementCoords& x, const Eigen::Vector3d& xi,
                                                 double* det_jacobian = nullptr);

/// Volume of the element (m³), integrated with the same rule.
double tet10_volume(const ElementCoords& x);

}  // namespace sw
