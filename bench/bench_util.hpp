#pragma once
// Small helpers shared by the benchmark programs (bench/fem_scaling.cpp, bench/vs_calculix.cpp): the mesh of a case,
// a scratch directory that cleans up after itself, the process's current resident set.
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "common/error.hpp"
#include "io/case.hpp"
#include "mesh/flexspline.hpp"
#include "mesh/shapes.hpp"
#include "mesh/tet_mesh.hpp"

namespace sw::bench {

/// The flexspline mesh of a case, as `strainwave fem` builds it.
inline TetMesh mesh_for_bench(const Case& c) { return mesh_flexspline(c.flexspline, c.gear, c.mesh); }

/// A tet10 mesh on a bench's command line: SIZE_MM/LAYERS[/CORNER_LEVELS] (mesh.size_mm, mesh.wall_layers,
/// mesh.corner_levels; −1: the case's).
struct MeshSpec {
  double size_mm = 1.0;
  int layers = 2;
  int corner_levels = -1;
};

/// The comma-separated meshes of `option`, read before any work so a typo costs nothing; a third part only when
/// `with_levels`. Throws InputError naming the item (size > 0, layers >= 1, levels >= 0, nothing after it).
inline std::vector<MeshSpec> parse_mesh_specs(const std::string& text, const std::string& option, bool with_levels) {
  std::vector<MeshSpec> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    MeshSpec m;
    char slash = 0, extra = 0;
    std::stringstream is(item);
    bool ok = (is >> m.size_mm >> slash >> m.layers) && slash == '/';
    if (ok && (is >> extra)) ok = with_levels && extra == '/' && (is >> m.corner_levels) && m.corner_levels >= 0 && !(is >> extra);
    if (!ok || !(m.size_mm > 0) || m.layers < 1)
      throw InputError(option + ": \"" + item + "\"; expected SIZE_MM/LAYERS" +
                       (with_levels ? std::string(" or SIZE_MM/LAYERS/CORNER_LEVELS") : std::string()) +
                       " (size > 0, layers >= 1" + (with_levels ? ", levels >= 0" : "") + ", nothing after)");
    out.push_back(m);
  }
  return out;
}

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
