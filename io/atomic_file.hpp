#pragma once
// Outputs appear whole or not at all. A file is written under a temporary name beside it and renamed; the files of a
// command (OutputSet) are written into a staging folder beside their output folder, which takes the folder's place in
// one rename when the command completes, so a reader sees the earlier set or the new one, never a mix. SIGINT, SIGTERM
// and SIGHUP remove the process's temporaries (temporary files, staging folders) and end it with the signal's status;
// a signal that arrives while a set is brought in waits until it is in. Directories are created as needed. Throws
// InputError when a path cannot be written.
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <string>
#include <vector>

namespace sw {

class TemporaryEntry;  // an entry in the process's list of temporaries (io/atomic_file.cpp)

/// Writes `content` to `path` atomically (temp file + rename).
void write_file_atomic(const std::filesystem::path& path, const std::string& content);

/// Calls `write(tmp_path)` to produce the file under a temporary name, then renames it to `path`
/// (for writers that insist on a file name, like VTK's).
void write_via_temp(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write);

/// The files one command writes into its output folder, brought in as one set. The command writes them under
/// staging() (and reads back what it wrote there through read_path); commit() makes the folder hold them, every file
/// of the folder's earlier contents that the command does not own (other commands' files, subfolders) and none of
/// the files it owns but did not write this time. Without commit() (an exception, a signal) the folder is left as it
/// was and the staging folder is removed.
class OutputSet {
 public:
  /// Stages the outputs of `dir`. `owned`: names of the files the command may write there ('*' matches any run of
  /// characters: "flexspline_*.vtu"); own() adds more. Throws InputError when `dir` is a file, or the working
  /// directory or above it (the folder is replaced whole when the set is brought in).
  explicit OutputSet(std::filesystem::path dir, std::vector<std::string> owned = {});
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  /// Where the set appears (for messages and for the paths the outputs name).
  const std::filesystem::path& dir() const { return dir_; }
  /// Where the command writes its files until commit().
  const std::filesystem::path& staging() const { return staging_; }
  /// Adds names of files the command owns in dir() (as the constructor's `owned`).
  void own(const std::vector<std::string>& names);
  /// Runs `write` (it writes files under staging()) on a thread of its own while the command goes on: a file only a
  /// reader of the folder needs (the FEM's VTU views) costs the command no time. commit() waits for it first and
  /// throws what it threw; the destructor waits for it too, so no writer outlives the staging folder.
  void write_beside(std::function<void()> write);
  /// `path`, or its staged copy when it names a file of dir() that this set has written: a command reads its own
  /// new outputs, and another command's outputs where they are.
  std::filesystem::path read_path(const std::filesystem::path& path) const;
  /// Brings the set in: the staging folder, completed with the folder's other files (hard links), takes the place of
  /// dir() in one rename (Linux renameat2 RENAME_EXCHANGE), and the earlier folder is removed. Commands that write
  /// into the same folder at once are brought in one after the other (a lock on the parent folder). A set that wrote
  /// nothing and owns nothing leaves the folder alone.
  void commit();

 private:
  bool owns(const std::string& name) const;
  void link_others_into_staging() const;
  void wait_for_writers();

  std::filesystem::path dir_;      ///< as given
  std::filesystem::path folder_;   ///< dir_ resolved (links followed): the folder replaced
  std::filesystem::path staging_;  ///< beside folder_
  std::vector<std::string> owned_;
  std::unique_ptr<TemporaryEntry> temporary_;  ///< the staging folder, removed by a signal
  bool committed_ = false;
  std::vector<std::future<void>> writers_;  ///< write_beside's, in the order started
};

}  // namespace sw
