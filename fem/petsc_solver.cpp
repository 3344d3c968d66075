#include "fem/petsc_solver.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <map>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <petscksp.h>

#include "common/error.hpp"
#include "common/progress.hpp"
#include "common/resources.hpp"
#include "fem/elasticity.hpp"

namespace sw {
namespace {

// ---- errors: PETSc's error codes as exceptions carrying PETSc's own first sentence -------------------------------

std::string& last_petsc_message() {
  static std::string message;
  return message;
}

/// PETSc calls this on an error instead of printing a traceback: it keeps the first (most specific) message.
PetscErrorCode record_error(MPI_Comm, int, const char*, const char*, PetscErrorCode n, PetscErrorType p,
                            const char* message, void*) {
  if (p == PETSC_ERROR_INITIAL) last_petsc_message() = message ? message : "";
  return n;
}

struct PetscFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void check(PetscErrorCode code) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  std::string message = last_petsc_message();
  last_petsc_message().clear();
  if (message.empty()) message = text ? text : "error " + std::to_string(static_cast<int>(code));
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  std::replace(message.begin(), message.end(), '\n', ' ');
  throw PetscFailure(message);
}

// ---- the session: MPI and PETSc for the process, and rank 0's requests to the others ---------------------------

struct Session {
  std::vector<std::string> options;  ///< PETSc options from the command line
  std::vector<std::string> argv_text;
  std::vector<char*> argv;
  bool started = false, stopped = false, used = false;
  int rank = 0, size = 1, nodes = 1;
  std::int64_t next_id = 1;
};

Session& session() {
  static Session s;
  return s;
}

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})  // OpenMPI; MPICH, srun --mpi=pmi2; PMIx
    if (std::getenv(v)) return true;
  return false;
}

void initialise_petsc() {
  Session& s = session();
  if (s.started) return;
  s.argv_text = {"strainwave"};
  s.argv_text.insert(s.argv_text.end(), s.options.begin(), s.options.end());
  s.argv_text.push_back("-options_left");  // unused options are refused by the first solve, in one line
  s.argv_text.push_back("no");
  for (auto& a : s.argv_text) s.argv.push_back(a.data());
  s.argv.push_back(nullptr);
  int argc = static_cast<int>(s.argv_text.size());
  char** argv = s.argv.data();
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0)
    throw InputError("MPI/PETSc failed to start (PetscInitialize); check the MPI installation (openmpi-bin) and the "
                     "launch (mpirun -np N strainwave ...)");
  PetscPushErrorHandler(record_error, nullptr);
  MPI_Comm_rank(PETSC_COMM_WORLD, &s.rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &s.size);
  MPI_Comm node;  // the ranks on this machine; the node count is the number of their first ranks
  MPI_Comm_split_type(PETSC_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int node_rank = 0;
  MPI_Comm_rank(node, &node_rank);
  MPI_Comm_free(&node);
  s.nodes = node_rank == 0 ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &s.nodes, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  s.started = true;
}

enum Command : std::int64_t { kSetup = 1, kSolve = 2, kRelease = 3, kStop = 4 };
struct Header {
  std::int64_t command = 0, id = 0, count = 0, spare = 0;
};

/// Rank 0 → all: the next request. Non-blocking on both sides, so the serving ranks can sleep between requests
/// instead of spinning in a blocking broadcast (the cores stay free for rank 0's work).
Header broadcast_header(Header h) {
  MPI_Request request;
  MPI_Ibcast(&h, 4, MPI_INT64_T, 0, PETSC_COMM_WORLD, &request);
  if (session().rank == 0) {
    MPI_Wait(&request, MPI_STATUS_IGNORE);
  } else {
    int done = 0;
    while (MPI_Test(&request, &done, MPI_STATUS_IGNORE), !done) {
      const timespec pause{0, 500000};  // 0.5 ms
      nanosleep(&pause, nullptr);
    }
  }
  return h;
}

template <class T>
void broadcast(std::vector<T>& v) {
  std::int64_t n = static_cast<std::int64_t>(v.size());
  MPI_Bcast(&n, 1, MPI_INT64_T, 0, PETSC_COMM_WORLD);
  v.resize(static_cast<std::size_t>(n));
  const std::size_t bytes = v.size() * sizeof(T);
  constexpr std::size_t kChunk = std::size_t{1} << 30;  // MPI counts are int
  auto* p = reinterpret_cast<char*>(v.data());
  for (std::size_t at = 0; at < bytes; at += kChunk)
    MPI_Bcast(p + at, static_cast<int>(std::min(kChunk, bytes - at)), MPI_BYTE, 0, PETSC_COMM_WORLD);
}

/// The end of every collective request: whether some rank failed (then the first failing rank's message, for rank 0
/// to report), and each rank's peak memory, gathered on rank 0.
struct Outcome {
  std::optional<std::string> error;
  std::vector<long> peak_rss_bytes_per_rank;
};
Outcome finish_request(const std::optional<std::string>& my_error) {
  const Session& s = session();
  Outcome o;
  int failed = my_error ? s.rank : s.size;
  MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  if (failed < s.size) {
    std::string message = my_error.value_or("");
    std::int64_t n = static_cast<std::int64_t>(message.size());
    MPI_Bcast(&n, 1, MPI_INT64_T, failed, PETSC_COMM_WORLD);
    message.resize(static_cast<std::size_t>(n));
    MPI_Bcast(message.data(), static_cast<int>(n), MPI_CHAR, failed, PETSC_COMM_WORLD);
    o.error = failed > 0 ? "rank " + std::to_string(failed) + ": " + message : message;
  }
  long mine = peak_rss_bytes();
  o.peak_rss_bytes_per_rank.resize(static_cast<std::size_t>(s.size));
  MPI_Gather(&mine, 1, MPI_LONG, o.peak_rss_bytes_per_rank.data(), 1, MPI_LONG, 0, PETSC_COMM_WORLD);
  return o;
}

/// Runs `work`, turning what it throws into a message (out of memory said as such).
template <class F>
std::optional<std::string> attempt(F&& work) {
  try {
    work();
    return std::nullopt;
  } catch (const std::bad_alloc&) {
    return "out of memory (" + std::to_string(peak_rss_bytes() / 1000000) + " MB resident); use more ranks or nodes";
  } catch (const std::exception& e) {
    return std::string(e.what());
  }
}

// ---- the distributed system --------------------------------------------------------------------------------------

/// Neighbour lists of the rows [lo, hi) of a node numbering (`number`, −1 for fixed nodes) over the mesh's elements:
/// the numbers of the other free nodes each row's node shares an element with, sorted (compressed rows).
struct NodeGraph {
  std::vector<PetscInt> start, neighbour;
};
NodeGraph node_graph(const TetMesh& mesh, const std::vector<PetscInt>& number, PetscInt lo, PetscInt hi) {
  const auto mine = [&](int v) { return number[v] >= lo && number[v] < hi; };
  std::vector<PetscInt> count(static_cast<std::size_t>(hi - lo) + 1, 0);
  for (const auto& t : mesh.tets)
    for (int v : t)
      if (mine(v)) ++count[number[v] - lo + 1];
  for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
  std::vector<std::int64_t> elements(static_cast<std::size_t>(count.back()));
  std::vector<PetscInt> next(count.begin(), count.end() - 1);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e)
    for (int v : mesh.tets[e])
      if (mine(v)) elements[next[number[v] - lo]++] = static_cast<std::int64_t>(e);
  NodeGraph g;
  g.start.reserve(static_cast<std::size_t>(hi - lo) + 1);
  g.start.push_back(0);
  std::vector<PetscInt> row;
  for (PetscInt r = 0; r < hi - lo; ++r) {
    row.clear();
    for (PetscInt k = count[r]; k < count[r + 1]; ++k)
      for (int v : mesh.tets[elements[k]])
        if (number[v] >= 0 && number[v] != lo + r) row.push_back(number[v]);
    std::sort(row.begin(), row.end());
    row.erase(std::unique(row.begin(), row.end()), row.end());
    g.neighbour.insert(g.neighbour.end(), row.begin(), row.end());
    g.start.push_back(static_cast<PetscInt>(g.neighbour.size()));
  }
  return g;
}

/// New numbers of the free nodes (index: free node in node order) after partitioning their graph over the ranks,
/// and the first new number of each rank (size ranks + 1): rank r owns [first[r], first[r + 1]).
struct Partition {
  std::vector<PetscInt> new_number, first;
};
Partition partition_nodes(const TetMesh& mesh, const std::vector<PetscInt>& free_number, PetscInt n_free) {
  const Session& s = session();
  Partition p;
  p.first.resize(static_cast<std::size_t>(s.size) + 1);
  if (s.size == 1) {
    p.new_number.resize(static_cast<std::size_t>(n_free));
    for (PetscInt k = 0; k < n_free; ++k) p.new_number[k] = k;
    p.first = {0, n_free};
    return p;
  }
  // The graph's rows start in blocks of the node order; PT-Scotch moves them so each rank's block is compact.
  const PetscInt lo = n_free * s.rank / s.size, hi = n_free * (s.rank + 1) / s.size;
  NodeGraph g = node_graph(mesh, free_number, lo, hi);
  PetscInt *ia = nullptr, *ja = nullptr;
  check(PetscMalloc1(g.start.size(), &ia));
  check(PetscMalloc1(std::max<std::size_t>(g.neighbour.size(), 1), &ja));
  std::copy(g.start.begin(), g.start.end(), ia);
  std::copy(g.neighbour.begin(), g.neighbour.end(), ja);
  g = {};
  Mat adjacency = nullptr;
  MatPartitioning part = nullptr;
  IS owner = nullptr, numbering = nullptr, all = nullptr;
  check(MatCreateMPIAdj(PETSC_COMM_WORLD, hi - lo, n_free, ia, ja, nullptr, &adjacency));  // takes ia, ja
  check(MatPartitioningCreate(PETSC_COMM_WORLD, &part));
  check(MatPartitioningSetAdjacency(part, adjacency));
  check(MatPartitioningSetType(part, MATPARTITIONINGPTSCOTCH));
  check(MatPartitioningSetFromOptions(part));
  check(MatPartitioningApply(part, &owner));
  check(ISPartitioningToNumbering(owner, &numbering));
  std::vector<PetscInt> counts(static_cast<std::size_t>(s.size));
  check(ISPartitioningCount(owner, s.size, counts.data()));
  check(ISAllGather(numbering, &all));
  const PetscInt* idx = nullptr;
  check(ISGetIndices(all, &idx));
  p.new_number.assign(idx, idx + n_free);
  check(ISRestoreIndices(all, &idx));
  p.first[0] = 0;
  for (int r = 0; r < s.size; ++r) p.first[r + 1] = p.first[r] + counts[r];
  ISDestroy(&all);
  ISDestroy(&numbering);
  ISDestroy(&owner);
  MatPartitioningDestroy(&part);
  MatDestroy(&adjacency);
  return p;
}

constexpr PetscInt kDirectBlock = 32;  // right-hand sides per MatMatSolve (memory: rows × 32 doubles, twice)

}  // namespace

// Outside the anonymous namespace: PetscSolver::Impl (a member of a class with linkage) holds one.
namespace petsc_detail {

struct Distributed {
  Mat A = nullptr;
  KSP ksp = nullptr;
  Vec x = nullptr, b = nullptr, on_zero = nullptr;
  VecScatter to_zero = nullptr;
  PetscInt rows = 0, local_rows = 0;
  bool direct = false, options_checked = false;
  std::vector<PetscInt> row_of_equation;  ///< rank 0: PETSc row of each equation of the DofMap
  FactorStats stats;
  double assemble_s = 0;

  Distributed() = default;
  Distributed(const Distributed&) = delete;
  Distributed& operator=(const Distributed&) = delete;
  ~Distributed() {
    PetscBool finalised = PETSC_FALSE;
    PetscFinalized(&finalised);
    if (finalised) return;
    VecScatterDestroy(&to_zero);
    VecDestroy(&on_zero);
    VecDestroy(&b);
    VecDestroy(&x);
    KSPDestroy(&ksp);
    MatDestroy(&A);
  }
};

}  // namespace petsc_detail

namespace {

using petsc_detail::Distributed;

std::string mumps_ordering(PetscInt code) {
  switch (code) {
    case 0: return "AMD";
    case 2: return "AMF";
    case 3: return "SCOTCH";
    case 4: return "PORD";
    case 5: return "METIS";
    case 6: return "QAMD";
    default: return "MUMPS ordering " + std::to_string(code);
  }
}

/// The PETSc numbering of the nodes: per node its block row (−1 for a fixed node), the number of free nodes and this
/// rank's block rows [lo, hi).
struct NodeRows {
  std::vector<PetscInt> number;
  PetscInt n_free = 0, lo = 0, hi = 0;
};

/// Collective: numbers the free nodes and partitions them over the ranks (partition_nodes).
NodeRows number_node_rows(const TetMesh& mesh, const std::vector<char>& free_node) {
  const Session& s = session();
  std::vector<PetscInt> free_number(mesh.n_nodes(), -1);
  NodeRows rows;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (free_node[i]) free_number[i] = rows.n_free++;
  const Partition part = partition_nodes(mesh, free_number, rows.n_free);
  rows.number.assign(mesh.n_nodes(), -1);
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (free_number[i] >= 0) rows.number[i] = part.new_number[free_number[i]];
  rows.lo = part.first[s.rank];
  rows.hi = part.first[s.rank + 1];
  return rows;
}

/// Collective: creates d.A, a block-size-3 MATAIJ (or the -mat_type asked for) preallocated from the node graph of
/// this rank's rows: exact, so assembly never reallocates.
void create_matrix(Distributed& d, const TetMesh& mesh, const NodeRows& rows) {
  const PetscInt lo = rows.lo, hi = rows.hi;
  std::vector<PetscInt> d_nnz(static_cast<std::size_t>(hi - lo)), o_nnz(static_cast<std::size_t>(hi - lo));
  {
    const NodeGraph g = node_graph(mesh, rows.number, lo, hi);
    for (PetscInt r = 0; r < hi - lo; ++r) {
      PetscInt inside = 1;  // the node itself
      for (PetscInt k = g.start[r]; k < g.start[r + 1]; ++k) inside += g.neighbour[k] >= lo && g.neighbour[k] < hi;
      d_nnz[r] = inside;
      o_nnz[r] = g.start[r + 1] - g.start[r] + 1 - inside;
    }
  }
  check(MatCreate(PETSC_COMM_WORLD, &d.A));
  check(MatSetSizes(d.A, d.local_rows, d.local_rows, d.rows, d.rows));
  check(MatSetBlockSize(d.A, 3));
  check(MatSetType(d.A, MATAIJ));
  check(MatSetFromOptions(d.A));  // -mat_type baij / sbaij if wanted
  check(MatXAIJSetPreallocation(d.A, 3, d_nnz.data(), o_nnz.data(), nullptr, nullptr));
  check(MatSetOption(d.A, MAT_ROW_ORIENTED, PETSC_FALSE));  // Eigen's column-major element matrices
  PetscBool sbaij = PETSC_FALSE;
  check(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(d.A), &sbaij, MATSBAIJ, MATSEQSBAIJ, MATMPISBAIJ, ""));
  if (sbaij) check(MatSetOption(d.A, MAT_IGNORE_LOWER_TRIANGULAR, PETSC_TRUE));
}

/// Collective: assembles the stiffness into d.A. Each element is assembled once, by the rank that owns its
/// lowest-numbered free node; entries of rows another rank owns travel to it at MatAssemblyEnd.
void assemble_matrix(Distributed& d, const TetMesh& mesh, const NodeRows& rows, const Material& material) {
  const Matrix6d D = elasticity_matrix(material);
  for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
    PetscInt idx[10], lowest = -1;
    for (int a = 0; a < 10; ++a) {
      idx[a] = rows.number[mesh.tets[e][a]];
      if (idx[a] >= 0 && (lowest < 0 || idx[a] < lowest)) lowest = idx[a];
    }
    if (lowest < rows.lo || lowest >= rows.hi) continue;
    const Matrix30d Ke = tet10_stiffness(element_coordinates(mesh, e), D);
    check(MatSetValuesBlocked(d.A, 10, idx, 10, idx, Ke.data(), ADD_VALUES));
  }
  check(MatAssemblyBegin(d.A, MAT_FINAL_ASSEMBLY));
  check(MatAssemblyEnd(d.A, MAT_FINAL_ASSEMBLY));
  check(MatSetOption(d.A, MAT_SPD, PETSC_TRUE));
}

/// Collective: the six rigid-body modes of the free nodes' coordinates as d.A's near-null space, for algebraic
/// multigrid. Needs d.x.
void set_rigid_body_modes(Distributed& d, const TetMesh& mesh, const NodeRows& rows) {
  Vec coordinates = nullptr;
  check(VecDuplicate(d.x, &coordinates));
  PetscScalar* c = nullptr;
  check(VecGetArray(coordinates, &c));
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (rows.number[i] >= rows.lo && rows.number[i] < rows.hi)
      for (int k = 0; k < 3; ++k) c[3 * (rows.number[i] - rows.lo) + k] = mesh.nodes(static_cast<Eigen::Index>(i), k);
  check(VecRestoreArray(coordinates, &c));
  MatNullSpace rigid = nullptr;
  check(MatNullSpaceCreateRigidBody(coordinates, &rigid));
  check(MatSetNearNullSpace(d.A, rigid));
  MatNullSpaceDestroy(&rigid);
  VecDestroy(&coordinates);
}

/// Collective: creates and sets up d.ksp on d.A, MUMPS Cholesky unless the options say otherwise (for a direct
/// solver, the numeric factorisation). Returns its preconditioner. InputError when the preconditioner fails.
PC set_up_solver(Distributed& d) {
  check(KSPCreate(PETSC_COMM_WORLD, &d.ksp));
  check(KSPSetOperators(d.ksp, d.A, d.A));
  check(KSPSetType(d.ksp, KSPPREONLY));
  PC pc = nullptr;
  check(KSPGetPC(d.ksp, &pc));
  check(PCSetType(pc, PCCHOLESKY));
  check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  check(KSPSetTolerances(d.ksp, 1e-10, PETSC_DEFAULT, PETSC_DEFAULT, 100000));
  check(KSPSetFromOptions(d.ksp));
  check(KSPSetUp(d.ksp));
  PCFailedReason failed = PC_NOERROR;
  check(PCGetFailedReason(pc, &failed));
  if (failed != PC_NOERROR)
    throw InputError(std::string("setting up the preconditioner failed (") + PCFailedReasons[failed] +
                     "); a zero pivot means the supports leave a rigid-body motion free: check the boundary conditions");
  return pc;
}

/// The solver's figures in d.stats: the KSP and PC types (d.direct for KSPPREONLY), the factor's package and, for
/// MUMPS, its entries, flops and ordering; the matrix's size and entries.
void record_solver_stats(Distributed& d, PC pc) {
  KSPType ksp_type = nullptr;
  PCType pc_type = nullptr;
  check(KSPGetType(d.ksp, &ksp_type));
  check(PCGetType(pc, &pc_type));
  d.direct = std::string(ksp_type) == KSPPREONLY;
  d.stats.algorithm = std::string(ksp_type) + " + " + pc_type;
  PetscBool factor = PETSC_FALSE;
  check(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &factor, PCCHOLESKY, PCLU, ""));
  d.stats.factor_nnz = 0;
  d.stats.factor_gflop = 0;
  d.stats.ordering = "none";
  if (factor) {
    MatSolverType package = nullptr;
    check(PCFactorGetMatSolverType(pc, &package));
    d.stats.algorithm += std::string(" (") + (package ? package : "petsc") + ")";
    if (package && std::string(package) == MATSOLVERMUMPS) {
      Mat F = nullptr;
      check(PCFactorGetMatrix(pc, &F));
      PetscInt entries = 0, ordering = 0, parallel_ordering = 0;
      PetscReal flops = 0;
      check(MatMumpsGetInfog(F, 29, &entries));  // entries in the factors; negative: millions
      check(MatMumpsGetInfog(F, 7, &ordering));
      check(MatMumpsGetIcntl(F, 28, &parallel_ordering));
      check(MatMumpsGetRinfog(F, 3, &flops));
      d.stats.factor_nnz = entries >= 0 ? static_cast<double>(entries) : -1e6 * static_cast<double>(entries);
      d.stats.factor_gflop = flops / 1e9;
      d.stats.ordering = parallel_ordering == 2 ? "parallel (ICNTL(28) = 2)" : mumps_ordering(ordering);
    }
  }
  MatInfo info;
  check(MatGetInfo(d.A, MAT_GLOBAL_SUM, &info));
  d.stats.backend = "petsc";
  d.stats.ranks = session().size;
  d.stats.equations = d.rows;
  d.stats.matrix_nnz = static_cast<std::int64_t>(info.nz_used);
  d.stats.supernodal = false;
}

/// Rank 0: the PETSc row of each equation of `dofs`.
std::vector<PetscInt> rows_of_equations(const TetMesh& mesh, const DofMap& dofs, const NodeRows& rows) {
  std::vector<PetscInt> row(static_cast<std::size_t>(dofs.n_equations), -1);
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    for (int k = 0; k < 3; ++k)
      if (const std::int64_t q = dofs.equation[3 * i + k]; q >= 0) row[q] = 3 * rows.number[i] + k;
  return row;
}

/// Collective: partitions, assembles and sets up the solver. `free_node`: per node, 1 where its dofs are free.
/// `dofs`: rank 0 only, for the map from its equations to PETSc's rows.
void set_up(Distributed& d, const TetMesh& mesh, const std::vector<char>& free_node, const Material& material,
            const DofMap* dofs) {
  Stopwatch clock;
  const NodeRows rows = number_node_rows(mesh, free_node);
  d.rows = 3 * rows.n_free;
  d.local_rows = 3 * (rows.hi - rows.lo);
  create_matrix(d, mesh, rows);
  d.stats.analyse_s = clock.lap();
  assemble_matrix(d, mesh, rows, material);
  check(MatCreateVecs(d.A, &d.x, &d.b));
  set_rigid_body_modes(d, mesh, rows);
  d.assemble_s = clock.lap();
  const PC pc = set_up_solver(d);
  d.stats.factor_s = clock.lap();
  record_solver_stats(d, pc);
  check(VecScatterCreateToZero(d.x, &d.to_zero, &d.on_zero));
  if (dofs) d.row_of_equation = rows_of_equations(mesh, *dofs, rows);
}

/// Refuses options nobody read once the first solve has queried everything (-ksp_view etc. are read by KSPSolve).
void refuse_unused_options() {
  PetscInt n = 0;
  char **names = nullptr, **values = nullptr;
  check(PetscOptionsLeftGet(nullptr, &n, &names, &values));
  std::string unused;
  for (PetscInt i = 0; i < n; ++i)
    if (std::string(names[i]) != "options_left")  // ours, read by PetscFinalize
      unused += std::string(unused.empty() ? "-" : ", -") + names[i];
  check(PetscOptionsLeftRestore(nullptr, &n, &names, &values));
  if (!unused.empty())
    throw InputError("option " + unused + " was not used by the solver (misspelt, or not one for this " +
                     "-ksp_type / -pc_type; -help lists them)");
}

/// Collective: X = K⁻¹·B. B (n_equations × k) and the result on rank 0; other ranks pass nullptr and get nothing.
Eigen::MatrixXd solve_columns(Distributed& d, const Eigen::MatrixXd* B, PetscInt k) {
  const bool root = session().rank == 0;
  Eigen::MatrixXd X;
  if (root) X.resize(B->rows(), B->cols());
  auto to_ranks = [&](PetscInt column, Vec target) {
    if (root) {
      PetscScalar* z = nullptr;
      check(VecGetArray(d.on_zero, &z));
      for (Eigen::Index q = 0; q < B->rows(); ++q) z[d.row_of_equation[q]] = (*B)(q, column);
      check(VecRestoreArray(d.on_zero, &z));
    }
    check(VecScatterBegin(d.to_zero, d.on_zero, target, INSERT_VALUES, SCATTER_REVERSE));
    check(VecScatterEnd(d.to_zero, d.on_zero, target, INSERT_VALUES, SCATTER_REVERSE));
  };
  auto to_root = [&](Vec source, PetscInt column) {
    check(VecScatterBegin(d.to_zero, source, d.on_zero, INSERT_VALUES, SCATTER_FORWARD));
    check(VecScatterEnd(d.to_zero, source, d.on_zero, INSERT_VALUES, SCATTER_FORWARD));
    if (root) {
      const PetscScalar* z = nullptr;
      check(VecGetArrayRead(d.on_zero, &z));
      for (Eigen::Index q = 0; q < X.rows(); ++q) X(q, column) = z[d.row_of_equation[q]];
      check(VecRestoreArrayRead(d.on_zero, &z));
    }
  };
  if (d.direct) {
    for (PetscInt j0 = 0; j0 < k; j0 += kDirectBlock) {
      const PetscInt m = std::min(kDirectBlock, k - j0);
      Mat Bm = nullptr, Xm = nullptr;
      check(MatCreateDense(PETSC_COMM_WORLD, d.local_rows, PETSC_DECIDE, d.rows, m, nullptr, &Bm));
      check(MatCreateDense(PETSC_COMM_WORLD, d.local_rows, PETSC_DECIDE, d.rows, m, nullptr, &Xm));
      for (PetscInt j = 0; j < m; ++j) {
        Vec column = nullptr;
        check(MatDenseGetColumnVecWrite(Bm, j, &column));
        to_ranks(j0 + j, column);
        check(MatDenseRestoreColumnVecWrite(Bm, j, &column));
      }
      check(KSPMatSolve(d.ksp, Bm, Xm));
      for (PetscInt j = 0; j < m; ++j) {
        Vec column = nullptr;
        check(MatDenseGetColumnVecRead(Xm, j, &column));
        to_root(column, j0 + j);
        check(MatDenseRestoreColumnVecRead(Xm, j, &column));
      }
      MatDestroy(&Bm);
      MatDestroy(&Xm);
    }
  } else {
    for (PetscInt j = 0; j < k; ++j) {
      to_ranks(j, d.b);
      check(KSPSolve(d.ksp, d.b, d.x));
      KSPConvergedReason reason;
      PetscInt iterations = 0;
      check(KSPGetConvergedReason(d.ksp, &reason));
      check(KSPGetIterationNumber(d.ksp, &iterations));
      if (reason < 0)
        throw InputError(std::string("the Krylov solver did not converge (") + KSPConvergedReasons[reason] +
                         ") after " + std::to_string(iterations) +
                         " iterations; raise -ksp_max_it, choose another -pc_type, or use the default direct solver");
      d.stats.iterations += iterations;
      to_root(d.x, j);
    }
  }
  d.stats.right_hand_sides += k;
  if (!d.options_checked) {
    d.options_checked = true;
    refuse_unused_options();
  }
  return X;
}

struct MeshMessage {
  TetMesh mesh;
  std::vector<char> free_node;
  Material material;
};

/// Rank 0 sends, the others receive: what the assembly needs of the mesh (nodes, elements, free nodes, material).
void broadcast_mesh(const TetMesh* mesh, MeshMessage& m) {
  std::vector<double> nodes, elastic{m.material.youngs_modulus_Pa, m.material.poisson_ratio};
  std::vector<std::array<int, 10>> tets;
  if (mesh) {
    nodes.assign(mesh->nodes.data(), mesh->nodes.data() + mesh->nodes.size());
    tets = mesh->tets;
  }
  broadcast(nodes);
  broadcast(tets);
  broadcast(m.free_node);
  broadcast(elastic);
  if (!mesh) {
    m.mesh.nodes = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(
        nodes.data(), static_cast<Eigen::Index>(nodes.size() / 3), 3);
    m.mesh.tets = std::move(tets);
    m.material.youngs_modulus_Pa = elastic[0];
    m.material.poisson_ratio = elastic[1];
  }
}

}  // namespace

// ---- parallel:: ----------------------------------------------------------------------------------------------------

namespace parallel {

bool petsc_available() { return true; }

void start(const std::vector<std::string>& petsc_options) {
  session().options = petsc_options;
  if (launched_by_mpi()) initialise_petsc();
}

int rank() { return session().rank; }
int ranks() { return session().size; }
int nodes() { return session().nodes; }

int serve() {
  std::map<std::int64_t, std::unique_ptr<Distributed>> systems;
  for (;;) {
    const Header h = broadcast_header({});
    switch (h.command) {
      case kSetup: {
        MeshMessage m;
        broadcast_mesh(nullptr, m);
        auto d = std::make_unique<Distributed>();
        const auto error = attempt([&] { set_up(*d, m.mesh, m.free_node, m.material, nullptr); });
        m = {};
        if (!finish_request(error).error) systems[h.id] = std::move(d);
        break;
      }
      case kSolve: {
        Distributed& d = *systems.at(h.id);
        finish_request(attempt([&] { solve_columns(d, nullptr, static_cast<PetscInt>(h.count)); }));
        break;
      }
      case kRelease:
        systems.erase(h.id);
        break;
      case kStop:
        systems.clear();
        PetscFinalize();
        return 0;
      default:
        std::fprintf(stderr, "strainwave: internal error: rank %d got request %lld\n", session().rank,
                     static_cast<long long>(h.command));
        return 3;
    }
  }
}

void stop(bool succeeded) {
  Session& s = session();
  if (s.stopped) return;
  s.stopped = true;
  if (succeeded && !s.used && !s.options.empty())
    std::fprintf(stderr, "strainwave: warning: PETSc options (%s ...) ignored: this run did not use the petsc backend\n",
                 s.options.front().c_str());
  if (!s.started) return;
  if (s.rank == 0 && s.size > 1) broadcast_header({kStop, 0, 0, 0});
  PetscFinalize();
}

}  // namespace parallel

// ---- PetscSolver (rank 0) -----------------------------------------------------------------------------------------

struct PetscSolver::Impl {
  std::int64_t id = 0;
  Distributed d;
};

PetscSolver::PetscSolver(const TetMesh& mesh, const Material& material, const DofMap& dofs)
    : impl_(std::make_unique<Impl>()) {
  initialise_petsc();
  Session& s = session();
  if (s.rank != 0) throw std::logic_error("PetscSolver is constructed on rank 0; the other ranks serve");
  s.used = true;
  impl_->id = s.next_id++;
  MeshMessage m;  // checked before the request goes out: once it has, every rank must see the request through
  m.material = material;
  m.free_node.resize(mesh.n_nodes());
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
    const bool free = dofs.equation[3 * i] >= 0;
    if (free != (dofs.equation[3 * i + 1] >= 0) || free != (dofs.equation[3 * i + 2] >= 0))
      throw std::logic_error("PetscSolver: a node with some dofs fixed and some free (whole nodes are fixed here)");
    m.free_node[i] = free;
  }
  if (s.size > 1) {
    broadcast_header({kSetup, impl_->id, 0, 0});
    broadcast_mesh(&mesh, m);
  }
  const Outcome o = finish_request(attempt([&] { set_up(impl_->d, mesh, m.free_node, material, &dofs); }));
  impl_->d.stats.peak_rss_bytes_per_rank = o.peak_rss_bytes_per_rank;
  if (o.error) throw InputError("PETSc: " + *o.error);
}

PetscSolver::~PetscSolver() {
  const Session& s = session();
  if (s.started && !s.stopped && s.size > 1) broadcast_header({kRelease, impl_->id, 0, 0});
}

Eigen::MatrixXd PetscSolver::solve(const Eigen::MatrixXd& B) const {
  const Session& s = session();
  if (B.rows() != static_cast<Eigen::Index>(impl_->d.row_of_equation.size()))
    throw std::logic_error("PetscSolver::solve: right-hand sides of the wrong size");
  if (s.size > 1) broadcast_header({kSolve, impl_->id, B.cols(), 0});
  Eigen::MatrixXd X;
  const Outcome o =
      finish_request(attempt([&] { X = solve_columns(impl_->d, &B, static_cast<PetscInt>(B.cols())); }));
  impl_->d.stats.peak_rss_bytes_per_rank = o.peak_rss_bytes_per_rank;
  if (o.error) throw InputError("PETSc: " + *o.error);
  return X;
}

const FactorStats& PetscSolver::stats() const { return impl_->d.stats; }
double PetscSolver::assemble_s() const { return impl_->d.assemble_s; }

}  // namespace sw
