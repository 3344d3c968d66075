#pragma once
// The fem job shared by `strainwave fem` and `strainwave run`.
#include <filesystem>
#include <string>

#include "common/params.hpp"
#include "fem/flexspline_analysis.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw::app {

struct FemJobResult {
  FlexsplineSolution solution;
  std::filesystem::path result_json_path;
};

/// out/<case stem>/
std::filesystem::path default_out_dir(const Case& c);

/// The mesh of the case's flexspline.
TetMesh mesh_for_case(const Case& c);

/// Meshes, solves, writes every fem output under out_dir, prints the summary (by the case's solver.method);
/// write_vtk = false leaves out the .vtu/.pvd files (sweeps).
FemJobResult run_fem_job(const Case& c, const std::filesystem::path& out_dir, bool write_vtk = true);

/// The same on the harmonic solver (solver.method = "fourier"; app/fem_fourier_job.cpp); VTU output optional.
FemJobResult run_fourier_fem_job(const Case& c, const std::filesystem::path& out_dir, bool write_vtk = true);

/// Applies a `--solver` command-line choice ("tet10" | "fourier"; empty: the case's) to the case.
void apply_solver_option(Case& c, const std::string& solver);

}  // namespace sw::app
