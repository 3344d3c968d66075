#pragma once
// CalculiX (ccx) for the benches that run it beside strainwave: find or install it, run it on a deck in a directory,
// read what its log says about the run.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/error.hpp"
#include "common/progress.hpp"

namespace sw::bench {

namespace fs = std::filesystem;

/// Path of `name` on PATH, empty if absent.
inline std::string which(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
    start = end + 1;
  }
  return {};
}

inline std::string ensure_ccx() {
  std::string ccx = which("ccx");
  if (!ccx.empty()) return ccx;
  std::fprintf(stderr, "ccx not on PATH; installing Debian's calculix-ccx\n");
  const std::string sudo = geteuid() == 0 ? "" : "sudo ";
  const std::string cmd = sudo + "env DEBIAN_FRONTEND=noninteractive apt-get install -y -q calculix-ccx";
  if (std::system(cmd.c_str()) != 0 || (ccx = which("ccx")).empty())
    throw InputError("could not install calculix-ccx (`" + cmd + "` failed); install it by hand");
  return ccx;
}

/// Writes the CalculiX deck: same nodes (1-based ids), C3D10 elements, clamped nodes, material, nodal loads.
/// Runs ccx in `dir` on job.inp, stdout/stderr to ccx.log; returns wall seconds.
inline double run_ccx(const std::string& ccx, const fs::path& dir, int threads) {
  std::fflush(stdout);
  std::fflush(stderr);
  Stopwatch clock;
  const pid_t pid = fork();
  if (pid < 0) throw InputError("fork() failed");
  if (pid == 0) {
    if (chdir(dir.c_str()) != 0) _exit(127);
    const std::string t = std::to_string(threads);
    setenv("OMP_NUM_THREADS", t.c_str(), 1);
    setenv("CCX_NPROC_EQUATION_SOLVER", t.c_str(), 1);
    std::FILE* log = std::freopen("ccx.log", "w", stdout);
    if (!log || dup2(fileno(stdout), STDERR_FILENO) < 0) _exit(127);
    execl(ccx.c_str(), "ccx", "-i", "job", static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  const double wall = clock.lap();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw InputError("ccx failed (status " + std::to_string(status) + "); see " + (dir / "ccx.log").string() +
                     " (run with --keep)");
  return wall;
}

/// What ccx.log says about its run: its equation count (-1 if absent) and the lines naming the solver, equations,
/// nonzeros and its own total time.
struct CcxLog {
  long long equations = -1;
  std::string summary;
};

inline CcxLog read_ccx_log(const fs::path& log) {
  std::ifstream in(log);
  std::string line;
  CcxLog out;
  auto trim = [](std::string t) {
    t.erase(0, t.find_first_not_of(' '));
    t.erase(t.find_last_not_of(" \r") + 1);
    return t;
  };
  while (std::getline(in, line)) {
    const std::string t = trim(line);
    if (t == "number of equations" || t == "number of nonzero lower triangular matrix elements") {
      std::string value;
      std::getline(in, value);
      out.summary += "  ccx: " + t + " " + trim(value) + "\n";
      if (t == "number of equations") out.equations = std::atoll(value.c_str());
    } else if (t.find("solver") != std::string::npos || t.rfind("Total CalculiX Time", 0) == 0) {
      out.summary += "  ccx: " + t + "\n";
    }
  }
  return out;
}

}  // namespace sw::bench
