#include "fem/flexspline_system.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "common/constants.hpp"
#include "common/error.hpp"
#include "common/progress.hpp"
#include "generator/cam_profile.hpp"
#include "fem/loads.hpp"
#include "fem/petsc_solver.hpp"

namespace sw {
namespace {

constexpr int kSolveChunk = 24;  // right-hand sides per CHOLMOD solve (memory: n_eq × 24 doubles)

/// Radial outward patch loads on the inner wall, one per force, each of magnitude weight (N) as the integral of the
/// pressure over its patch.
Eigen::VectorXd generator_load(const FlexsplineModel& c, const TetMesh& mesh) {
  const auto& w = *c.wave_generator;
  const double z_wg = c.flexspline.length_m - w.axial_position_m;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.n_nodes());
  for (const auto& force : generator_forces(w)) {
    auto in_patch = [&](const Eigen::Vector3d& x) {
      return std::abs(wrap_pi(theta_of(x) - force.angle_rad)) <= kGeneratorPatchHalfAngle_rad &&
             std::abs(x[2] - z_wg) <= 0.5 * w.band_width_m;
    };
    const auto faces = select_faces(mesh, kSurfaceInner, in_patch);
    if (faces.empty())
      throw InputError("wave_generator: no inner-wall faces under the force at " +
                       std::to_string(force.angle_rad * 180 / kPi) + " deg, z = " + std::to_string(z_wg * 1e3) +
                       " mm; check wave_generator.axial_position_mm / band_width_mm or refine mesh.size_mm");
    const double area = faces_area(mesh, faces);
    f += traction_load(mesh, faces, [&](const Eigen::Vector3d& x, const Eigen::Vector3d&) -> Eigen::Vector3d {
      const double r = std::hypot(x[0], x[1]);
      return Eigen::Vector3d(x[0] / r, x[1] / r, 0.0) * (force.weight / area);
    });
  }
  return f;
}

}  // namespace

Eigen::MatrixXd FlexsplineSystem::solve(const Eigen::MatrixXd& loads) const {
  Eigen::MatrixXd B(dofs.n_equations, loads.cols());
  for (Eigen::Index j = 0; j < loads.cols(); ++j) B.col(j) = restrict_to_free(dofs, loads.col(j));
  const Eigen::MatrixXd X = factor->solve(B);
  const Eigen::VectorXd zeros = Eigen::VectorXd::Zero(loads.rows());
  Eigen::MatrixXd U(loads.rows(), loads.cols());
  for (Eigen::Index j = 0; j < loads.cols(); ++j) U.col(j) = expand_to_full(dofs, X.col(j), zeros);
  return U;
}

Eigen::MatrixXd FlexsplineSystem::influence(const Eigen::SparseMatrix<double>& loads) const {
  const Eigen::Index m = loads.cols();
  // Half solves on the patterns' paths (Yᵀ·Y with Y = L⁻¹·P·B) when Y fits in 2 GB; else full solves in chunks.
  if (static_cast<double>(m) * dofs.n_equations * 8 < 2e9) {
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(loads.nonZeros()));
    for (Eigen::Index j = 0; j < m; ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(loads, j); it; ++it)
        if (const std::int64_t q = dofs.equation[it.row()]; q >= 0) entries.emplace_back(q, j, it.value());
    Eigen::SparseMatrix<double> B(dofs.n_equations, m);
    B.setFromTriplets(entries.begin(), entries.end());
    if (auto C = factor->influence_matrix(B)) return *C;
  }
  Eigen::MatrixXd C(m, m);
  for (Eigen::Index j0 = 0; j0 < m; j0 += kSolveChunk) {
    const Eigen::Index k = std::min<Eigen::Index>(kSolveChunk, m - j0);
    const Eigen::MatrixXd U = solve(Eigen::MatrixXd(loads.middleCols(j0, k)));
    C.middleCols(j0, k) = loads.transpose() * U;
  }
  return 0.5 * (C + C.transpose());  // symmetric up to round-off; make it exactly so
}

std::vector<bool> clamped_nodes(const TetMesh& mesh) {
  std::vector<bool> fixed(mesh.n_nodes(), false);
  for (const auto& f : mesh.faces)
    if (f.marker == kSurfaceClamped)
      for (int v : f.nodes) fixed[v] = true;
  return fixed;
}

FlexsplineSystem assemble_and_factorise(const FlexsplineModel& c, const TetMesh& mesh) {
  FlexsplineSystem eq;
  eq.clamped = clamped_nodes(mesh);
  std::vector<bool> fixed(3 * mesh.n_nodes());
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) fixed[3 * i] = fixed[3 * i + 1] = fixed[3 * i + 2] = eq.clamped[i];
  eq.dofs = make_dof_map(fixed);
  Stopwatch clock;
  if (c.solver.backend == SolverBackend::Petsc) {
    progress("petsc: distributed assembly and set-up of " + std::to_string(eq.dofs.n_equations) + " equations");
    auto solver = std::make_unique<PetscSolver>(mesh, c.material, eq.dofs);
    eq.assemble_s = solver->assemble_s();
    eq.factor = std::move(solver);
  } else {
    if (parallel::ranks() > 1)
      throw InputError("solver.backend = \"cholmod\" runs in one process, but this run was launched on " +
                       std::to_string(parallel::ranks()) + " MPI ranks; use --backend petsc (or [solver] backend = "
                       "\"petsc\"), or run without mpirun");
    progress("assemble: " + std::to_string(eq.dofs.n_equations) + " equations");
    const SymmetricCsc K = assemble_stiffness(mesh, c.material, eq.dofs);
    eq.assemble_s = clock.lap();
    progress("factorise: nnz(K) = " + std::to_string(K.nnz()));
    eq.factor = std::make_unique<CholmodFactor>(K, equation_nodes(eq.dofs));
  }
  const FactorStats& st = eq.factor->stats();
  progress("factorised (" + st.algorithm + "): nnz(L) = " + std::to_string(static_cast<long long>(st.factor_nnz)) + ", " +
           std::to_string(st.factor_gflop) + " GF in " + std::to_string(st.factor_s) + " s");
  return eq;
}

double rollers_setout(const WaveGeneratorParams& w, double w_unit_m) {
  if (!(w_unit_m > 0))
    throw InputError("wave_generator: rollers at beta_deg = " + std::to_string(std::get<Rollers>(w.model).beta_rad * 180 / kPi) +
                     " do not push the major axis outward; use beta_deg < 45");
  return *w.radial_deformation_m / w_unit_m;
}

GeneratorStations generator_stations(const FlexsplineModel& c, const TetMesh& mesh) {
  const auto& w = *c.wave_generator;
  const auto& f = c.flexspline;
  const double z = f.length_m - w.axial_position_m, r = f.inner_radius_m;
  GeneratorStations g;
  const double spacing = station_spacing(c);
  const StationLayout layout = station_layout(w, r, spacing);
  g.unilateral = layout.unilateral;
  g.stations = band_stations(mesh, z, w.band_width_m, layout.angle_rad, spacing, layout.tilt);
  g.obstacle_m = layout.obstacle_m;
  if (!g.unilateral) g.force_load = generator_load(c, mesh);
  return g;
}

}  // namespace sw
