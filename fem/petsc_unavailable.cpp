// The petsc backend in a build without PETSc: refused in one line (fem/petsc_solver.hpp).
#include <stdexcept>

#include "common/error.hpp"
#include "fem/petsc_solver.hpp"

namespace sw {
namespace {
const char* const kRebuild = "this strainwave was built without PETSc; install libpetsc-real-dev (scripts/setup.sh) and "
                             "rebuild with cmake -DSW_WITH_PETSC=ON";
}

namespace parallel {
bool petsc_available() { return false; }
void start(const std::vector<std::string>& petsc_options) {
  if (!petsc_options.empty())
    throw InputError("PETSc option " + petsc_options.front() + " given, but " + kRebuild);
}
int rank() { return 0; }
int ranks() { return 1; }
int nodes() { return 1; }
int serve() { return 0; }
void stop(bool) {}
}  // namespace parallel

struct PetscSolver::Impl {};

PetscSolver::PetscSolver(const TetMesh&, const Material&, const DofMap&) {
  throw InputError(std::string("solver.backend = \"petsc\": ") + kRebuild);
}
PetscSolver::~PetscSolver() = default;
Eigen::MatrixXd PetscSolver::solve(const Eigen::MatrixXd&) const { throw std::logic_error("no PETSc"); }
const FactorStats& PetscSolver::stats() const { throw std::logic_error("no PETSc"); }
double PetscSolver::assemble_s() const { return 0; }

}  // namespace sw
