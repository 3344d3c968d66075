#pragma once
// VTK output: quadratic tetrahedra with nodal fields in an XML .vtu (binary appended, LZ4-compressed), and a .pvd
// collection of several load cases. Opens in ParaView; Warp By Vector on "displacement" shows the deformation.
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mesh/tet_mesh.hpp"

namespace sw {

/// A nodal field: n_nodes rows, 1, 3 or 6/9 components.
struct NodalField {
  std::string name;
  Eigen::MatrixXd values;  ///< n_nodes x components
};

/// Writes the mesh (VTK_QUADRATIC_TETRA cells, "region" cell data) and the nodal fields, atomically.
void write_vtu(const std::filesystem::path& path, const TetMesh& mesh, const std::vector<NodalField>& fields);

/// Writes a ParaView collection: one dataset per (name, file relative to the .pvd), as timesteps 0, 1, 2, ...
void write_pvd(const std::filesystem::path& path, const std::vector<std::pair<std::string, std::string>>& datasets);

}  // namespace sw
