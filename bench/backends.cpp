// bench_backends: the TET10 solve on CHOLMOD (1 process, 2 BLAS threads) beside PETSc under MPI (2 ranks, 1 thread
// each) with MUMPS Cholesky and with CG + GAMG, on one case at several meshes, through the command line as a user runs
// it (`strainwave fem`, `mpirun -np 2 strainwave fem --backend petsc ...`), read back from each result.json:
// time per phase, memory per rank, factor size and work, Krylov iterations and right-hand sides.
//
// Two variants of the case per mesh: the whole case (the generator's contact: some 35 right-hand sides; direct
// solvers only, unless --krylov-contact) and the torque case alone (no [wave_generator]: one right-hand side), where
// the Krylov method's set-up and one solve compare with a factorisation and one solve.
// Wall clock; the machine is shared: say so with the figures. The machine's DGEMM rate (2 threads) is measured first
// in the same run: the limit of a factor's GF/s, printed per run.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "bench_util.hpp"
#include "dgemm.hpp"

namespace {

namespace fs = std::filesystem;

std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The case's text with its [mesh] size and wall layers, its teeth, and without the generator (and what needs it)
/// if asked.
std::string variant(std::string t, double size_mm, int wall_layers, const std::string& teeth, bool generator) {
  auto set_line = [&](const std::string& key, const std::string& value) {
    const auto at = t.find("\n" + key + " =");
    if (at == std::string::npos) throw std::runtime_error("the case has no line '" + key + " = ...'");
    const auto end = t.find('\n', at + 1);
    t.replace(at + 1, end - at - 1, key + " = " + value);
  };
  set_line("size_mm", std::to_string(size_mm));
  set_line("wall_layers", std::to_string(wall_layers));
  if (!teeth.empty()) set_line("teeth", "\"" + teeth + "\"");
  if (!generator) {
    for (const std::string table : {"[wave_generator]", "[dynamics]", "[circular_spline]"}) {
      const auto from = t.find(table);
      if (from == std::string::npos) continue;
      const auto next = t.find("\n[", from + 1);
      t.erase(from, next == std::string::npos ? std::string::npos : next + 1 - from);
    }
  }
  return t;
}

struct Run {
  std::string label, launch, args;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_backends: CHOLMOD vs PETSc (MUMPS, CG + GAMG) under MPI, per phase"};
  std::string case_path = "cases/seed_190_192.toml", teeth = "ring";
  std::vector<std::string> meshes{"1.5:1", "1.5:2"};
  int ranks = 2;
  bool krylov_contact = false;
  app.add_option("case", case_path, "case file (TOML)");
  app.add_option("--meshes", meshes, "meshes as size_mm:wall_layers (the walls' layers set the cup's mesh more than "
                                    "size_mm does)")->delimiter(',');
  app.add_option("--teeth", teeth, "flexspline.teeth for every run (empty: the case's; explicit teeth of the seed cup "
                                  "are 8.4e5 equations even at size_mm 1.5, beyond 5 GB on MUMPS)");
  app.add_option("--ranks", ranks, "MPI ranks of the PETSc runs");
  app.add_flag("--krylov-contact", krylov_contact, "also run CG + GAMG on the whole case (slow: ~35 solves)");
  CLI11_PARSE(app, argc, argv);
  try {
    sw::bench::TempDir dir("sw_bench_backends_");
    const std::string base = read_text(case_path);
    const std::string mpi = std::string("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OPENBLAS_NUM_THREADS=1 ") +
                            SW_MPIEXEC + " -q --oversubscribe -np " + std::to_string(ranks) + " ";
    const std::vector<Run> direct{{"cholmod", "OPENBLAS_NUM_THREADS=2 ", ""},
                                  {"mumps", mpi, "--backend petsc"}};
    const Run krylov{"cg+gamg", mpi, "--backend petsc -ksp_type cg -pc_type gamg"};
    std::printf("DGEMM (n = 2000, this process's BLAS threads): %.1f GF/s\n", sw::bench::dgemm_gflops(2000, 3));
    std::printf("%-7s %-9s %-8s %5s %9s %6s %6s %6s %7s %6s %7s %8s %6s %8s %5s %6s %s\n", "mesh", "variant",
                "solver", "ranks", "equations", "mesh", "assem", "analy", "factor", "solve", "total", "GF", "GF/s",
                "nnz(L)", "rhs", "iters", "peak MB per rank");
    for (const std::string& m : meshes) {
      const auto colon = m.find(':');
      if (colon == std::string::npos) throw std::runtime_error("--meshes " + m + ": expected size_mm:wall_layers");
      const double size = std::stod(m.substr(0, colon));
      const int layers = std::stoi(m.substr(colon + 1));
      for (const bool generator : {true, false}) {
        const fs::path case_file = dir.path() / ("case_" + m + (generator ? "_whole" : "_torque") + ".toml");
        std::ofstream(case_file) << variant(base, size, layers, teeth, generator);
        std::vector<Run> runs = direct;
        if (!generator || krylov_contact) runs.push_back(krylov);
        for (const Run& r : runs) {
          const fs::path out = dir.path() / ("out_" + r.label);
          fs::remove_all(out);
          const std::string command = r.launch + SW_STRAINWAVE_BINARY + " fem --quiet --no-vtk " +
                                      case_file.string() + " --out " + out.string() + " " + r.args + " > " +
                                      (dir.path() / "log").string() + " 2>&1";
          if (std::system(command.c_str()) != 0) {
            std::printf("%-7s %-9s %-8s failed: %s\n", m.c_str(), generator ? "whole" : "torque", r.label.c_str(),
                        read_text(dir.path() / "log").c_str());
            continue;
          }
          const auto j = nlohmann::json::parse(read_text(out / "result.json"));
          const auto& s = j["solver"];
          const auto& t = j["timings_s"];
          std::string memory;
          if (s.contains("peak_rss_bytes_per_rank"))
            for (const auto& b : s["peak_rss_bytes_per_rank"]) memory += std::to_string(b.get<long>() / 1000000) + " ";
          else
            memory = std::to_string(j["peak_rss_bytes"].get<long>() / 1000000);
          const double factor_s = t["factor"].get<double>();
          std::printf("%-7s %-9s %-8s %5d %9lld %6.1f %6.1f %6.1f %7.1f %6.1f %7.1f %8.1f %6.1f %8.2e %5lld %6lld %s\n",
                      m.c_str(), generator ? "whole" : "torque", r.label.c_str(), s["ranks"].get<int>(),
                      s["equations"].get<long long>(), t["mesh"].get<double>(), t["assemble"].get<double>(),
                      t["analyse"].get<double>(), t["factor"].get<double>(), t["solve"].get<double>(),
                      t["total"].get<double>(), s["factor_gflop"].get<double>(),
                      factor_s > 0 ? s["factor_gflop"].get<double>() / factor_s : 0.0, s["factor_nnz"].get<double>(),
                      s.value("right_hand_sides", 0LL), s.value("iterations", 0LL), memory.c_str());
          std::fflush(stdout);
        }
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_backends: %s\n", e.what());
    return 1;
  }
  return 0;
}
