#pragma once
// Post-processing of a displacement field: recovered nodal stresses, von Mises, cylindrical components, reactions,
// rigid rotation of a ring of points, and displacement sampled at arbitrary points.
#include <vector>

#include <Eigen/Core>

#include "common/material.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

using RowMatrixX3d = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
using RowMatrixX6d = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;

/// Nodal stresses (n_nodes x 6, Pa, Voigt xx yy zz yz xz xy): each element's stress evaluated at its own nodes
/// (exact for the element's field, not Gauss values) and averaged over the elements sharing the node, weighted by
/// element volume.
RowMatrixX6d nodal_stress(const TetMesh& mesh, const Material& material, const Eigen::VectorXd& u);

/// Von Mises stress (Pa) of each row of a Voigt stress table.
Eigen::VectorXd von_mises(const RowMatrixX6d& stress);

/// Cylindrical components about the z axis at every node.
struct CylindricalFields {
  Eigen::VectorXd u_r, u_theta;                               ///< m
  Eigen::VectorXd s_rr, s_thetatheta, s_zz, s_ztheta;         ///< Pa
};
CylindricalFields cylindrical_components(const TetMesh& mesh, const Eigen::VectorXd& u, const RowMatrixX6d& stress);

/// Reaction moment about the z axis (N·m) of a nodal force vector (3·n_nodes) restricted to the nodes in `mask`
/// (size n_nodes; true = include).
double moment_about_z(const TetMesh& mesh, const Eigen::VectorXd& f, const std::vector<bool>& mask);

/// Least-squares rigid in-plane motion (t_x, t_y, rotation about z) of points p (n x 3) with displacements d (n x 3):
/// returns the rotation (rad).
double rigid_rotation_z(const RowMatrixX3d& points, const RowMatrixX3d& displacements);

/// Locates points in the mesh and interpolates a nodal field there with the TET10 shape functions.
class PointSampler {
public:
  explicit PointSampler(const TetMesh& mesh);
  /// Displacement (3) at x of the full dof vector u; throws InputError if x lies outside the mesh.
  Eigen::Vector3d displacement(const Eigen::Vector3d& x, const Eigen::VectorXd& u) const;
  /// Nodal field (n_nodes x k) interpolated at x; throws InputError if x lies outside the mesh.
  Eigen::VectorXd interpolate(const Eigen::Vector3d& x, const Eigen::Ref<const Eigen::MatrixXd>& field) const;
  /// Element and natural coordinates of x (element −1 if outside).
  std::pair<long, Eigen::Vector3d> locate(const Eigen::Vector3d& x) const;

private:
  const TetMesh& mesh_;
  Eigen::Vector3d lo_, cell_;
  Eigen::Vector3i dims_;
  std::vector<std::vector<int>> bins_;
};

}  // namespace sw
