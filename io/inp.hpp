#pragma once
// The Abaqus/CalculiX input deck of a solve (nodes, C3D10 elements, clamped nodes, material, nodal loads; SI units)
// and, beside its writer, the reader of what CalculiX returns: the displacements of its ASCII .frd result file.
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "io/case.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw {

/// Writes the deck atomically: *NODE, *ELEMENT TYPE=C3D10 (the TET10 node order of VTK and CalculiX agree), the
/// clamped nodes fixed in x, y, z, the case's elastic material, one *STATIC step with the nodal loads `load`
/// (3·n_nodes, N; none on fixed nodes) and *NODE FILE U. `origin` names the writer in the deck's first comment.
/// Numbers in %.13e: ccx reads at most 20 characters per number.
void write_inp_deck(const std::filesystem::path& path, const Case& c, const TetMesh& mesh,
                    const std::vector<bool>& fixed_node, const Eigen::VectorXd& load, const std::string& origin);

/// Displacements (3·n_nodes) from the last DISP block of a CalculiX ASCII .frd. Throws InputError naming the file for
/// a missing block, a node out of range or a node without a value.
Eigen::VectorXd read_frd_displacements(const std::filesystem::path& path, std::size_t n_nodes);

}  // namespace sw
