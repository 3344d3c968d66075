// A run stopped by SIGINT or SIGTERM leaves its output folder with the complete earlier set or the complete new set,
// never a mix, and no temporaries: `strainwave fem` on the torsion tube (coarsened to a few seconds) is interrupted
// at points found from its progress lines (meshing, factorising) and at fractions of the time from its "output:" line
// to the new set's appearance, measured by a first run uninterrupted.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/cli.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using namespace sw::testing;
using Clock = std::chrono::steady_clock;

/// The working folder: the coarse tube's case and the output folder `case` beside it.
fs::path work_root() {
  static const fs::path root = [] {
    const fs::path d = fs::temp_directory_path() / ("sw_interrupt_" + std::to_string(::getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    std::string text = read_text("cases/tube_torsion.toml");
    text.replace(text.find("size_mm = 1.5"), 13, "size_mm = 3.0");
    text.replace(text.find("wall_layers = 2"), 15, "wall_layers = 1");
    std::ofstream(d / "tube.toml") << text;
    return d;
  }();
  return root;
}

const std::string kEarlier = "earlier run\n", kOther = "another command's\n";

/// The folder as an earlier fem run (with a generator case the new run does not have) and another command left it.
void lay_earlier_set(const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (const char* f : {"result.json", "flexspline.pvd", "flexspline_torque.vtu", "flexspline_generator.vtu"})
    std::ofstream(dir / f) << kEarlier;
  std::ofstream(dir / "backlash.json") << kOther;
}

std::set<std::string> names_in(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(folder)) names.insert(e.path().filename().string());
  return names;
}

bool is_earlier_set(const fs::path& dir) {
  if (names_in(dir) != std::set<std::string>{"backlash.json", "flexspline.pvd", "flexspline_generator.vtu",
                                             "flexspline_torque.vtu", "result.json"})
    return false;
  for (const char* f : {"result.json", "flexspline.pvd", "flexspline_torque.vtu", "flexspline_generator.vtu"})
    if (read_text(dir / f) != kEarlier) return false;
  return read_text(dir / "backlash.json") == kOther;
}

/// The tube's whole fem set (its one load case), every file complete, the other command's file kept.
bool is_new_set(const fs::path& dir) {
  if (names_in(dir) != std::set<std::string>{"backlash.json", "flexspline.pvd", "flexspline_torque.vtu", "result.json",
                                             "resolved_case.toml"})
    return false;
  const auto ends_with = [](const std::string& text, const std::string& tail) {
    return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
  };
  const std::string vtu = read_text(dir / "flexspline_torque.vtu"), pvd = read_text(dir / "flexspline.pvd");
  if (!ends_with(vtu, "</VTKFile>\n") || !ends_with(pvd, "</VTKFile>\n")) return false;
  try {
    return read_json(dir / "result.json").contains("phi0_rad") && read_text(dir / "backlash.json") == kOther;
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

/// Names under the working folder that a run's temporaries carry (staging folders, temporary files).
std::vector<std::string> temporaries_left() {
  std::vector<std::string> left;
  for (const auto& e : fs::recursive_directory_iterator(work_root())) {
    const std::string name = e.path().filename().string();
    if (name.find(".staging-") != std::string::npos || name.find(".tmp") != std::string::npos) left.push_back(name);
  }
  return left;
}

/// `strainwave fem` on the tube into `case`, its stderr (the progress lines) on a pipe, SIGINT and SIGTERM at their
/// default action whatever the test runner's are.
struct FemChild {
  pid_t pid = -1;
  int progress_fd = -1;
  std::string progress;  ///< read so far

  FemChild() {
    int fds[2];
    if (::pipe(fds) != 0) throw std::runtime_error("pipe");
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_adddup2(&actions, fds[1], 2);
    posix_spawn_file_actions_addclose(&actions, fds[0]);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t defaults;
    sigemptyset(&defaults);
    sigaddset(&defaults, SIGINT);
    sigaddset(&defaults, SIGTERM);
    posix_spawnattr_setsigdefault(&attributes, &defaults);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
    // On TET10: its phases (meshing, factorising, output) each take long enough to be interrupted in.
    std::vector<std::string> args = {strainwave_binary(), "fem", (work_root() / "tube.toml").string(), "--solver",
                                     "tet10", "--out", (work_root() / "case").string()};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const int rc = posix_spawn(&pid, argv[0], &actions, &attributes, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    posix_spawnattr_destroy(&attributes);
    ::close(fds[1]);
    progress_fd = fds[0];
    if (rc != 0) throw std::runtime_error("cannot start " + args[0]);
  }

  /// Reads progress until a line holds `text` (true) or the run has closed its stderr (false).
  bool wait_for(const std::string& text) {
    char buffer[4096];
    while (progress.find(text) == std::string::npos) {
      const ssize_t n = ::read(progress_fd, buffer, sizeof buffer);
      if (n <= 0) return false;
      progress.append(buffer, static_cast<std::size_t>(n));
    }
    return true;
  }

  /// Drains the progress (the run must never block on a full pipe) and returns the wait status.
  int finish() {
    wait_for("\x01");  // to the end
    ::close(progress_fd);
    int status = 0;
    ::waitpid(pid, &status, 0);
    return status;
  }
};

struct Interruption {
  int signal;
  std::string after;  ///< progress text to wait for
  double delay_s;     ///< then this long
};

/// How long a run uninterrupted takes from its "output:" line until the new set is in the folder (watched every
/// 0.2 ms), and that it is the whole new set.
double output_seconds() {
  const fs::path dir = work_root() / "case";
  lay_earlier_set(dir);
  FemChild run;
  EXPECT_TRUE(run.wait_for("output:")) << run.progress;
  const auto from = Clock::now();
  while (read_text(dir / "result.json") == kEarlier && Clock::now() - from < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  const double seconds = std::chrono::duration<double>(Clock::now() - from).count();
  const int status = run.finish();
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << run.progress;
  EXPECT_TRUE(is_new_set(dir));
  return seconds;
}

TEST(Interrupt, LeavesTheEarlierSetOrTheNewOneAndNoTemporaries) {
  const double writing_s = output_seconds();
  std::printf("the outputs take %.1f ms from the \"output:\" line to the new set\n", writing_s * 1e3);
  std::vector<Interruption> plan = {{SIGINT, "mesh:", 0}, {SIGTERM, "factorise:", 0}};
  for (double f : {0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 4.0}) plan.push_back({SIGINT, "output:", f * writing_s});
  for (double f : {0.3, 0.7}) plan.push_back({SIGTERM, "output:", f * writing_s});
  int kept_earlier = 0, brought_in = 0;
  for (const Interruption& i : plan) {
    const std::string where = std::string(i.signal == SIGINT ? "SIGINT" : "SIGTERM") + " " +
                              std::to_string(i.delay_s) + " s after '" + i.after + "'";
    lay_earlier_set(work_root() / "case");
    FemChild run;
    ASSERT_TRUE(run.wait_for(i.after)) << where << "\n" << run.progress;
    std::this_thread::sleep_for(std::chrono::duration<double>(i.delay_s));
    ::kill(run.pid, i.signal);
    const int status = run.finish();
    const bool earlier = is_earlier_set(work_root() / "case"), fresh = is_new_set(work_root() / "case");
    EXPECT_TRUE(earlier || fresh) << where << ": the folder holds a mix";
    EXPECT_EQ(temporaries_left(), std::vector<std::string>{}) << where;
    if (WIFEXITED(status)) {  // it finished before the signal came
      EXPECT_EQ(WEXITSTATUS(status), 0) << where << "\n" << run.progress;
      EXPECT_TRUE(fresh) << where;
    } else {
      EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == i.signal) << where << "\n" << run.progress;
    }
    kept_earlier += earlier;
    brought_in += fresh;
    std::printf("%s: %s set, %s\n", where.c_str(), earlier ? "earlier" : fresh ? "new" : "mixed",
                WIFEXITED(status) ? "the run had ended" : "the run stopped");
  }
  EXPECT_GE(kept_earlier, 2) << "the interruptions before the output keep the earlier set";
  EXPECT_GE(brought_in, 1) << "four times the output's time after its start, the new set is in";
  fs::remove_all(work_root());
}

}  // namespace
