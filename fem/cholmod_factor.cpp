#include "fem/cholmod_factor.hpp"

#include <cholmod.h>
#include <dlfcn.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <optional>
#include <vector>

#include "common/error.hpp"

namespace sw {

BlasInfo detect_blas() {
  BlasInfo info;
  std::string where = "unknown library";
  Dl_info dl{};
  void* dgemm = dlsym(RTLD_DEFAULT, "dgemm_");  // CHOLMOD pulls BLAS in; look up whose dgemm_ it got
  if (dgemm && dladdr(dgemm, &dl) && dl.dli_fname) {
    std::error_code ec;
    const auto real = std::filesystem::canonical(dl.dli_fname, ec);
    where = ec ? std::string(dl.dli_fname) : real.string();
  }
  using ConfigFn = char* (*)();
  using ThreadsFn = int (*)();
  auto config = reinterpret_cast<ConfigFn>(dlsym(RTLD_DEFAULT, "openblas_get_config"));
  auto threads = reinterpret_cast<ThreadsFn>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  if (config) {
    info.description = std::string(config()) + (threads ? ", " + std::to_string(threads()) + " threads" : "") +
                       " from " + where;
  } else {
    info.is_reference = where.find("openblas") == std::string::npos && where.find("mkl") == std::string::npos &&
                        where.find("blis") == std::string::npos;
    info.description = (info.is_reference ? "reference BLAS from " : "BLAS from ") + where;
  }
  return info;
}

struct CholmodFactor::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  FactorStats stats;
  ~Impl() {
    if (factor) cholmod_l_free_factor(&factor, &common);
    cholmod_l_finish(&common);
  }
};

namespace {

std::string status_sentence(const cholmod_common& c, std::int64_t n) {
  switch (c.status) {
    case CHOLMOD_OUT_OF_MEMORY:
      return "CHOLMOD ran out of memory factorising " + std::to_string(n) +
             " equations; use a coarser mesh (larger mesh.size_mm or fewer mesh.wall_layers)";
    case CHOLMOD_TOO_LARGE:
      return "CHOLMOD: the problem is too large for integer indexing; use a coarser mesh";
    case CHOLMOD_INVALID:
      return "CHOLMOD rejected the matrix as invalid (an internal error: please report it)";
    case CHOLMOD_NOT_POSDEF:
      return "the stiffness matrix is not positive definite: rigid-body modes unconstrained? check the boundary "
             "conditions";
    default:
      return "CHOLMOD failed with status " + std::to_string(c.status);
  }
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The smallest ratio of pivots we accept: cholmod_rcond's estimate, min/max of the diagonal of L squared for LL' (the
// pivots of LDL'). A free rigid-body mode usually stops the factorisation (not positive definite); where round-off
// leaves it a positive pivot, that pivot is at round-off level relative to the largest, 1e-16…1e-13. A constrained
// model's ratio falls with the mesh as (h/L)²: 3e-2 on a small box, 2.6e-6 on size 17's section at the case's mesh,
// 3.2e-7 at a 0.05 mm section (measured), far above it.
constexpr double kMinPivotRatio = 1e-13;

}  // namespace

namespace {

/// A cholmod_sparse view of K's upper triangle (no copy; CHOLMOD only reads it).
cholmod_sparse csc_view(const SymmetricCsc& K) {
  cholmod_sparse A{};
  A.nrow = A.ncol = static_cast<size_t>(K.n);
  A.nzmax = K.nnz();
  A.p = const_cast<std::int64_t*>(K.column_start.data());
  A.i = const_cast<std::int64_t*>(K.row.data());
  A.x = const_cast<double*>(K.value.data());
  A.stype = 1;  // upper triangle stored
  A.itype = CHOLMOD_LONG;
  A.xtype = CHOLMOD_REAL;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  return A;
}

/// Fill-reducing permutation of K's equations from METIS on the graph of its blocks (nodes).
std::vector<std::int64_t> block_ordering(const SymmetricCsc& K, const std::vector<std::int64_t>& block,
                                         cholmod_common& c) {
  // Renumber the blocks that have equations 0..nb-1 in order of first appearance (equations are block-contiguous).
  std::vector<std::int64_t> compact(K.n), first_equation;
  std::int64_t nb = 0;
  for (std::int64_t j = 0; j < K.n; ++j) {
    if (j == 0 || block[j] != block[j - 1]) first_equation.push_back(j), ++nb;
    compact[j] = nb - 1;
  }
  first_equation.push_back(K.n);
  // Upper pattern of the block graph, column by column, deduplicated with a marker.
  std::vector<std::int64_t> colptr(nb + 1, 0), rows, mark(nb, -1);
  for (std::int64_t b = 0; b < nb; ++b) {
    for (std::int64_t j = first_equation[b]; j < first_equation[b + 1]; ++j)
      for (std::int64_t k = K.column_start[j]; k < K.column_start[j + 1]; ++k) {
        const std::int64_t a = compact[K.row[k]];
        if (mark[a] != b) {
          mark[a] = b;
          rows.push_back(a);
        }
      }
    std::sort(rows.begin() + colptr[b], rows.end());
    colptr[b + 1] = static_cast<std::int64_t>(rows.size());
  }
  cholmod_sparse G{};
  G.nrow = G.ncol = static_cast<size_t>(nb);
  G.nzmax = rows.size();
  G.p = colptr.data();
  G.i = rows.data();
  G.stype = 1;
  G.itype = CHOLMOD_LONG;
  G.xtype = CHOLMOD_PATTERN;
  G.dtype = CHOLMOD_DOUBLE;
  G.sorted = 1;
  G.packed = 1;
  std::vector<std::int64_t> block_perm(nb);
  if (!cholmod_l_metis(&G, nullptr, 0, 1, block_perm.data(), &c)) return {};
  std::vector<std::int64_t> perm;
  perm.reserve(K.n);
  for (std::int64_t b : block_perm)
    for (std::int64_t j = first_equation[b]; j < first_equation[b + 1]; ++j) perm.push_back(j);
  return perm;
}

}  // namespace

CholmodFactor::CholmodFactor(const SymmetricCsc& K, const std::vector<std::int64_t>& block_of_equation)
    : impl_(std::make_unique<Impl>()) {
  cholmod_common& c = impl_->common;
  cholmod_l_start(&c);
  c.supernodal = CHOLMOD_SUPERNODAL;
  // Nested dissection by METIS only: on 3-D TET10 meshes it always gave the least fill, and letting CHOLMOD also try
  // AMD (its default) made the analysis cost as much as the factorisation itself (bench/fem_scaling).
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_METIS;
  c.postorder = 1;
  c.print = 0;
  c.error_handler = nullptr;
  if (K.n == 0) throw InputError("no free degrees of freedom: every node is fixed");

  cholmod_sparse A = csc_view(K);

  auto t0 = std::chrono::steady_clock::now();
  std::vector<std::int64_t> perm;
  if (!block_of_equation.empty()) perm = block_ordering(K, block_of_equation, c);
  if (!perm.empty()) {
    c.method[0].ordering = CHOLMOD_GIVEN;
    impl_->factor = cholmod_l_analyze_p(&A, perm.data(), nullptr, 0, &c);
  } else {
    impl_->factor = cholmod_l_analyze(&A, &c);
  }
  if (!impl_->factor || c.status < CHOLMOD_OK) throw InputError(status_sentence(c, K.n));
  impl_->stats.analyse_s = seconds_since(t0);
  impl_->stats.factor_gflop = c.fl * 1e-9;
  impl_->stats.factor_nnz = c.lnz;
  static const char* kOrderings[] = {"natural", "given", "AMD", "METIS", "NESDIS", "COLAMD", "postordered"};
  const int ord = impl_->factor->ordering;
  impl_->stats.ordering = !perm.empty() ? "METIS on the node graph" : ord >= 0 && ord < 7 ? kOrderings[ord] : "other";

  impl_->stats.equations = K.n;
  impl_->stats.supernodal = impl_->factor->is_super;
  impl_->stats.algorithm = impl_->factor->is_super ? "supernodal Cholesky" : "simplicial Cholesky";
  refactorise(K);
}

void CholmodFactor::refactorise(const SymmetricCsc& K) {
  if (K.n != static_cast<std::int64_t>(impl_->factor->n))
    throw std::logic_error("refactorise: the matrix is not of the analysed size");
  cholmod_common& c = impl_->common;
  cholmod_sparse A = csc_view(K);
  const auto t0 = std::chrono::steady_clock::now();
  const int ok = cholmod_l_factorize(&A, impl_->factor, &c);
  impl_->stats.factor_s = seconds_since(t0);
  if (!ok || c.status != CHOLMOD_OK) throw InputError(status_sentence(c, K.n));
  impl_->stats.matrix_nnz = static_cast<std::int64_t>(K.nnz());

  // Unconstrained rigid modes need not give a negative pivot in floating point: check the pivot spread too.
  const double rcond = cholmod_l_rcond(impl_->factor, &c);
  if (!(rcond > kMinPivotRatio)) {
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.2g", rcond);
    throw InputError(std::string("the stiffness matrix is singular to working precision (pivot ratio ") + ratio +
                     "): rigid-body modes unconstrained? check the boundary conditions");
  }
}

CholmodFactor::~CholmodFactor() = default;

namespace {
/// A cholmod_dense view of an Eigen matrix (no copy; CHOLMOD only reads it).
cholmod_dense dense_view(const Eigen::MatrixXd& B) {
  cholmod_dense b{};
  b.nrow = static_cast<size_t>(B.rows());
  b.ncol = static_cast<size_t>(B.cols());
  b.nzmax = b.nrow * b.ncol;
  b.d = b.nrow;
  b.x = const_cast<double*>(B.data());
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  return b;
}
}  // namespace

Eigen::MatrixXd CholmodFactor::solve(const Eigen::MatrixXd& B) const {
  cholmod_common& c = impl_->common;
  cholmod_dense b = dense_view(B);
  cholmod_dense* x = cholmod_l_solve(CHOLMOD_A, impl_->factor, &b, &c);
  if (!x) throw InputError(status_sentence(c, impl_->stats.equations));
  Eigen::MatrixXd X = Eigen::Map<Eigen::MatrixXd>(static_cast<double*>(x->x), B.rows(), B.cols());
  cholmod_l_free_dense(&x, &c);
  return X;
}

namespace {
extern "C" {
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb, std::size_t, std::size_t,
            std::size_t, std::size_t);
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc, std::size_t, std::size_t);
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc, std::size_t, std::size_t);
}
}  // namespace


// Written here rather than taken from CHOLMOD: its dense solve runs every supernode for every column, and its
// sparse-set solve (cholmod_solve2 with Bset) is for one column. Load patterns for influence coefficients are local
// (a tooth's flank, a generator station), so each column's forward substitution only reaches the supernodes on the
// path from its rows to the root of the supernodal elimination tree (Gilbert and Peierls's reachability); grouping the
// columns that share a supernode keeps each step a BLAS-3 triangular solve and product.
std::optional<Eigen::MatrixXd> CholmodFactor::forward_solve(const Eigen::SparseMatrix<double>& B) const {
  return forward(B, nullptr);
}

std::optional<Eigen::MatrixXd> CholmodFactor::influence_matrix(const Eigen::SparseMatrix<double>& B) const {
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(B.cols(), B.cols());
  if (!forward(B, &C)) return std::nullopt;
  C.triangularView<Eigen::StrictlyUpper>() = C.transpose();
  return C;
}

std::optional<Eigen::MatrixXd> CholmodFactor::forward(const Eigen::SparseMatrix<double>& B, Eigen::MatrixXd* gram) const {
  const cholmod_factor* L = impl_->factor;
  if (!L->is_ll || !L->is_super || L->itype != CHOLMOD_LONG) return std::nullopt;
  const auto n = static_cast<std::int64_t>(L->n);
  if (B.rows() != n) throw std::logic_error("forward_solve: right-hand side has the wrong number of rows");
  const auto* perm = static_cast<const std::int64_t*>(L->Perm);
  const auto* super = static_cast<const std::int64_t*>(L->super);
  const auto* pi = static_cast<const std::int64_t*>(L->pi);
  const auto* px = static_cast<const std::int64_t*>(L->px);
  const auto* srow = static_cast<const std::int64_t*>(L->s);
  const auto* lx = static_cast<const double*>(L->x);
  const auto nsuper = static_cast<std::int64_t>(L->nsuper);

  std::vector<std::int64_t> position(n), supernode_of(n), parent(nsuper, -1);
  for (std::int64_t k = 0; k < n; ++k) position[perm ? perm[k] : k] = k;
  for (std::int64_t sn = 0; sn < nsuper; ++sn)
    for (std::int64_t k = super[sn]; k < super[sn + 1]; ++k) supernode_of[k] = sn;
  for (std::int64_t sn = 0; sn < nsuper; ++sn) {
    const std::int64_t ncol = super[sn + 1] - super[sn], nrow = pi[sn + 1] - pi[sn];
    if (nrow > ncol) parent[sn] = supernode_of[srow[pi[sn] + ncol]];  // the first row below the diagonal block
  }
  // P·B scattered into Y; each column marks the supernodes on its paths (a parent is numbered after its children).
  const Eigen::Index m = B.cols();
  Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(n, m);
  std::vector<std::vector<int>> columns(nsuper);
  std::vector<Eigen::Index> mark(nsuper, -1);
  for (Eigen::Index j = 0; j < m; ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(B, j); it; ++it) {
      const std::int64_t k = position[it.row()];
      Y(k, j) = it.value();
      for (std::int64_t sn = supernode_of[k]; sn >= 0 && mark[sn] != j; sn = parent[sn]) {
        mark[sn] = j;
        columns[sn].push_back(static_cast<int>(j));
      }
    }
  std::vector<double> X, W, G;
  const double one = 1, zero = 0;
  for (std::int64_t sn = 0; sn < nsuper; ++sn) {
    const auto& cols = columns[sn];
    if (cols.empty()) continue;
    const int ncol = static_cast<int>(super[sn + 1] - super[sn]), nrow = static_cast<int>(pi[sn + 1] - pi[sn]);
    const int nrhs = static_cast<int>(cols.size()), nbelow = nrow - ncol;
    const double* Ls = lx + px[sn];
    const std::int64_t* rows = srow + pi[sn];
    X.resize(static_cast<std::size_t>(ncol) * nrhs);
    for (int c = 0; c < nrhs; ++c)
      for (int i = 0; i < ncol; ++i) X[static_cast<std::size_t>(c) * ncol + i] = Y(super[sn] + i, cols[c]);
    dtrsm_("L", "L", "N", "N", &ncol, &nrhs, &one, Ls, &nrow, X.data(), &ncol, 1, 1, 1, 1);
    for (int c = 0; c < nrhs; ++c)
      for (int i = 0; i < ncol; ++i) Y(super[sn] + i, cols[c]) = X[static_cast<std::size_t>(c) * ncol + i];
    if (gram) {  // these rows of Y are final: their share of Yᵀ·Y (lower triangle, in the columns' order)
      G.resize(static_cast<std::size_t>(nrhs) * nrhs);
      dsyrk_("L", "T", &nrhs, &ncol, &one, X.data(), &ncol, &zero, G.data(), &nrhs, 1, 1);
      for (int b = 0; b < nrhs; ++b)
        for (int a = b; a < nrhs; ++a) (*gram)(cols[a], cols[b]) += G[static_cast<std::size_t>(b) * nrhs + a];
    }
    if (nbelow == 0) continue;
    W.resize(static_cast<std::size_t>(nbelow) * nrhs);
    dgemm_("N", "N", &nbelow, &nrhs, &ncol, &one, Ls + ncol, &nrow, X.data(), &ncol, &zero, W.data(), &nbelow, 1, 1);
    for (int c = 0; c < nrhs; ++c)
      for (int i = 0; i < nbelow; ++i) Y(rows[ncol + i], cols[c]) -= W[static_cast<std::size_t>(c) * nbelow + i];
  }
  return Y;
}

const FactorStats& CholmodFactor::stats() const { return impl_->stats; }

}  // namespace sw
