#pragma once
// The machine's dense reference rate: DGEMM of the loaded BLAS (the libblas.so.3 CHOLMOD uses), for the benches that
// state a factorisation's efficiency against it. Link BLAS::BLAS.
#include <algorithm>
#include <random>
#include <vector>

#include "common/progress.hpp"

extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
                       const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
                       const double* beta, double* c, const int* ldc, std::size_t, std::size_t);

namespace sw::bench {

/// Best-of-`repeats` DGEMM rate (GF/s) of the loaded BLAS on n×n matrices.
inline double dgemm_gflops(int n, int repeats) {
  std::vector<double> a(static_cast<std::size_t>(n) * n), b(a.size()), c(a.size(), 0.0);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& x : a) x = u(rng);
  for (auto& x : b) x = u(rng);
  const double one = 1.0, zero = 0.0;
  dgemm_("N", "N", &n, &n, &n, &one, a.data(), &n, b.data(), &n, &zero, c.data(), &n, 1, 1);  // warm-up
  double best = 0;
  for (int r = 0; r < repeats; ++r) {
    Stopwatch clock;
    dgemm_("N", "N", &n, &n, &n, &one, a.data(), &n, b.data(), &n, &zero, c.data(), &n, 1, 1);
    best = std::max(best, 2.0 * n * n * static_cast<double>(n) / clock.lap() / 1e9);
  }
  return best;
}

}  // namespace sw::bench
