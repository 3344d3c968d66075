#pragma once
// Sparse assembly of the TET10 stiffness straight into the compressed-column upper triangle that CHOLMOD takes.
// Dirichlet conditions are applied by elimination: fixed degrees of freedom get no equation.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "common/material.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Equation number of every degree of freedom (3 per node, node-major), −1 where the dof is fixed.
/// Free dofs are numbered in node order, which keeps each column's row indices sorted.
struct DofMap {
  std::vector<std::int64_t> equation;  ///< size 3·n_nodes
  std::int64_t n_equations = 0;
};

/// Node of every equation (size n_equations): lets the solver order the node graph instead of the dof graph.
std::vector<std::int64_t> equation_nodes(const DofMap& dofs);

/// Numbers the free dofs. `fixed` has size 3·n_nodes (true = eliminated).
DofMap make_dof_map(const std::vector<bool>& fixed);

/// Symmetric matrix stored as its upper triangle in compressed columns (row indices sorted within each column).
struct SymmetricCsc {
  std::int64_t n = 0;
  std::vector<std::int64_t> column_start;  ///< n + 1
  std::vector<std::int64_t> row;           ///< nnz
  std::vector<double> value;               ///< nnz
  std::size_t nnz() const { return value.size(); }
};

/// Local bases at some nodes, so a condition can fix a non-Cartesian component (the radial displacement under a
/// cam): where a node has a frame R (columns = local axes in global coordinates), its three dofs are the components
/// along those axes, u_global = R·u_local. Nodes without a frame keep x, y, z.
struct NodeFrames {
  std::vector<int> frame_of_node;          ///< size n_nodes (or empty = no frames), −1 = global axes
  std::vector<Eigen::Matrix3d> rotations;  ///< orthonormal, one per frame
  bool empty() const { return rotations.empty(); }
};

/// Global stiffness (N/m) over the free dofs of `dofs`: pattern from the node graph, then element scatter.
/// Memory: the pattern and values only (no triplets, no dense blocks beyond one 30x30 element matrix).
/// With `frames`, the dofs of framed nodes are local components (K' = Tᵀ·K·T element by element).
SymmetricCsc assemble_stiffness(const TetMesh& mesh, const Material& material, const DofMap& dofs,
                                const NodeFrames& frames = {});

/// Right-hand-side contribution −K_fc·u_c of prescribed (nonzero) values on fixed dofs, over the free equations.
/// `prescribed` has size 3·n_nodes (values on free dofs are ignored; local components at framed nodes).
Eigen::VectorXd dirichlet_lift(const TetMesh& mesh, const Material& material, const DofMap& dofs,
                               const Eigen::VectorXd& prescribed, const NodeFrames& frames = {});

/// Converts a full dof vector between global components and the frames' local ones (loads: to_local; solutions:
/// to_global).
Eigen::VectorXd to_local(const NodeFrames& frames, const Eigen::VectorXd& global);
Eigen::VectorXd to_global(const NodeFrames& frames, const Eigen::VectorXd& local);

/// Internal forces K·u (N) at every dof (3·n_nodes) by element loop; at fixed dofs minus applied loads this is the
/// reaction.
Eigen::VectorXd internal_forces(const TetMesh& mesh, const Material& material, const Eigen::VectorXd& u);

/// Strain energy ½ u_eᵀK_e u_e of a displacement u (3·n_nodes) summed per region of the mesh (J, indexed by
/// TetMesh::region: 0 body wall, 1 rim, 2 diaphragm, 3 boss); the regions add to ½ uᵀK u.
std::vector<double> strain_energy_by_region_J(const TetMesh& mesh, const Material& material, const Eigen::VectorXd& u);

/// Gathers the element's node coordinates (10 x 3).
Eigen::Matrix<double, 10, 3> element_coordinates(const TetMesh& mesh, std::size_t element);

/// Free-dof vector (n_equations) from a full dof vector (3·n_nodes), and back (fixed dofs take `fixed_values`).
Eigen::VectorXd restrict_to_free(const DofMap& dofs, const Eigen::VectorXd& full);
Eigen::VectorXd expand_to_full(const DofMap& dofs, const Eigen::VectorXd& free, const Eigen::VectorXd& fixed_values);

}  // namespace sw
