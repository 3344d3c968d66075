#pragma once
// Small helpers shared by the benchmark programs (bench/fem_scaling.cpp, bench/vs_calculix.cpp): the mesh of a case,
// a scratch directory that cleans up after itself, the process's current resident set.
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "common/error.hpp"
#include "common/params.hpp"
#include "mesh/flexspline.hpp"
#include "mesh/shapes.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw::bench {

/// The flexspline mesh of a case, as `strainwave fem` builds it.
inline TetMesh mesh_for_bench(const Case& c) { return mesh_flexspline(c.flexspline, c.gear, c.mesh); }

/// A fresh directory under the system temp dir (`prefix`XXXXXX), removed with its content on destruction unless
/// keep() was called.
class TempDir {
public:
  explicit TempDir(const std::string& prefix) {
    std::string tmpl = (std::filesystem::temp_directory_path() / (prefix + "XXXXXX")).string();
    if (!mkdtemp(tmpl.data())) throw InputError("cannot create a temporary directory " + tmpl);
    path_ = tmpl;
  }
  ~TempDir() {
    if (keep_) return;
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  void keep() { keep_ = true; }

private:
  std::filesystem::path path_;
  bool keep_ = false;
};

/// CPU time of this process on all its threads (s): on a shared machine, what a phase cost regardless of waiting.
inline double process_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Current resident set size of this process (bytes), from /proc/self/status (0 if unavailable).
inline long current_rss_bytes() {
  std::ifstream in("/proc/self/status");
  std::string key;
  while (in >> key) {
    if (key == "VmRSS:") {
      long kb = 0;
      in >> kb;
      return kb * 1024L;
    }
    in.ignore(4096, '\n');
  }
  return 0;
}

/// Memory held by the mesh arrays (bytes): coordinates, connectivity, regions, boundary faces.
inline double mesh_bytes(const TetMesh& m) {
  return static_cast<double>(m.n_nodes()) * 3 * sizeof(double) +
         static_cast<double>(m.tets.size()) * (sizeof(std::array<int, 10>) + sizeof(int)) +
         static_cast<double>(m.faces.size()) * sizeof(BoundaryFace);
}

}  // namespace sw::bench
