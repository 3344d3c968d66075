#pragma once
// The fem job shared by `strainwave fem` and `strainwave run`.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/commands.hpp"
#include "io/atomic_file.hpp"
#include "io/case.hpp"
#include "fem/flexspline_analysis.hpp"
#include "fem/fourier_solver.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw::app {

/// The files the fem job writes in its output folder (the VTK ones unless --no-vtk; neutral_curve.csv with a
/// generator): a command that runs it owns them (OutputSet).
inline const std::vector<std::string> kFemJobFiles = {"result.json", "neutral_curve.csv", "flexspline.pvd",
                                                      "flexspline_*.vtu"};

struct FemJobResult {
  FlexsplineSolution solution;
  std::filesystem::path result_json_path;  ///< where result.json appears (read it through the set's read_path)
  /// The TET10 mesh and its factorised system, kept for the stages that solve on it again (the tooth contact);
  /// null on the harmonic solver.
  std::shared_ptr<const TetMesh> mesh;
  std::shared_ptr<const FlexsplineSystem> system;
  /// The harmonic solution (its bands' responses for the loaded contact); null on TET10.
  std::shared_ptr<const FourierSolution> harmonic;
};


/// The fem job's command-line options, shared by `fem` and `run` (one place, one spelling).
struct FemJobOptions {
  bool write_vtk = true;                            ///< --no-vtk leaves out flexspline.pvd and the .vtu files
  std::optional<std::filesystem::path> export_inp;  ///< --export-inp FILE: CalculiX/Abaqus deck of the torque case
  double max_memory_gb = 0;                         ///< --max-memory GB; 0: the machine's available memory
};

/// Registers --no-vtk, --export-inp and --max-memory on a subcommand.
void add_fem_job_options(CLI::App* cmd, FemJobOptions& options);

/// The mesh of the case's flexspline, refused in one line before meshing when the model's estimated peak memory
/// exceeds max_memory_gb (0: the machine's available memory), per machine the petsc backend's ranks run on.
TetMesh mesh_for_case(const Case& c, double max_memory_gb = 0);

/// Meshes, solves, writes every fem output into the set `out` (owning kFemJobFiles), prints the summary (by the
/// case's solver.method).
FemJobResult run_fem_job(const Case& c, OutputSet& out, const FemJobOptions& options = {});

/// The case's harmonic solution (with the bands the loaded contact reads, when it can take the case), refused from its
/// section before assembly when its estimate exceeds max_memory_gb (0: the machine's available memory). `section_s`:
/// the section's meshing time.
FourierSolution solve_fourier_model(const Case& c, double max_memory_gb, double& section_s);

/// The same on the harmonic solver (solver.method = "fourier"; app/fem_fourier_job.cpp); VTU output optional. A model
/// whose estimate exceeds max_memory_gb (0: the machine's available memory) is refused before it is assembled.
FemJobResult run_fourier_fem_job(const Case& c, OutputSet& out, bool write_vtk = true, double max_memory_gb = 0);

/// Applies the `--solver` ("tet10" | "fourier") and `--backend` ("cholmod" | "petsc") command-line choices (empty:
/// the case's) to the case.
void apply_solver_option(Case& c, const std::string& solver, const std::string& backend = "");

/// Registers --backend cholmod | petsc on a subcommand.
void add_backend_option(CLI::App* cmd, std::string& backend);

/// --solver tet10 | fourier and --backend, overriding the case's [solver] keys.
void add_solver_options(CLI::App* cmd, std::string& solver, std::string& backend);

/// "auto" takes the TET10 model where a command needs it: a case that leaves solver.method to "auto" gets "tet10", with
/// `why` as the method's origin; a case that names a method keeps it (the caller refuses a fourier one where it cannot
/// serve, before any work).
void take_tet10_under_auto(Case& c, const std::string& why);

/// The case at `path` with the command line's solver and backend applied, its headline shown as progress.
/// `tet10_needed_for`: what of the command needs the TET10 model, if anything (take_tet10_under_auto, unless --solver
/// is given).
Case load_case_with_solver(const std::string& path, const std::string& solver, const std::string& backend,
                           const std::string& tet10_needed_for = "");

}  // namespace sw::app
