#pragma once
// Running the strainwave command line (or any shell command) from a test, as a user runs it: its exit code, stdout
// and stderr. The binary is the one of this build tree: its path is compiled in by the test target
// (SW_STRAINWAVE_BINARY="$<TARGET_FILE:strainwave>"), so a stale build elsewhere is never run.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

namespace sw::testing {

struct CommandRun {
  int exit_code = -1;    ///< exit status; -1 when the command did not exit normally (killed by a signal)
  std::string out, err;  ///< what it wrote to stdout and to stderr
  std::string output;    ///< stdout then stderr (under --quiet a one-line error message is the whole of it)
};

/// The whole text of a file ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A JSON file, parsed (throws nlohmann::json::parse_error when it is not JSON).
inline nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

/// Runs `command` with /bin/sh from the working directory, capturing stdout and stderr.
inline CommandRun run_shell(const std::string& command) {
  static int calls = 0;
  const std::filesystem::path base = std::filesystem::temp_directory_path() /
                                     ("sw_cli_" + std::to_string(::getpid()) + "_" + std::to_string(calls++));
  const std::filesystem::path out = base.string() + ".out", err = base.string() + ".err";
  const int status = std::system(("(" + command + ") > '" + out.string() + "' 2> '" + err.string() + "'").c_str());
  CommandRun r;
  r.exit_code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_text(out);
  r.err = read_text(err);
  r.output = r.out + r.err;
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

#ifdef SW_STRAINWAVE_BINARY
/// The strainwave binary of this build tree.
inline std::string strainwave_binary() { return SW_STRAINWAVE_BINARY; }

/// Runs `strainwave ARGS` (the arguments as one shell-quoted string).
inline CommandRun run_strainwave(const std::string& args) { return run_shell(strainwave_binary() + " " + args); }
#endif

}  // namespace sw::testing
