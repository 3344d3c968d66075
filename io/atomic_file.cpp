#include "io/atomic_file.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <mutex>
#include <utility>

#include "common/error.hpp"

namespace sw {

namespace fs = std::filesystem;

namespace {

// The process's temporaries (temporary files, staging folders), removed by the handler of the signals that end a
// run. The handler calls only async-signal-safe functions on fixed storage: no allocation, no locks.

constexpr int kTerminatingSignals[] = {SIGINT, SIGTERM, SIGHUP};

struct Temporary {
  std::atomic<int> state{0};  ///< 0 free, 1 being entered, 2 holds a path to remove
  char path[4096];
};
Temporary g_temporaries[64];

/// Working: a signal removes the temporaries and ends the process. Committing: a set is being brought in; the signal
/// waits in g_pending_signal until it is in. CleaningUp: a signal is ending the process.
enum Phase : int { kWorking, kCommitting, kCleaningUp };
std::atomic<int> g_phase{kWorking};
std::atomic<int> g_pending_signal{0};

bool is_dot_entry(const char* name) { return name[0] == '.' && (name[1] == 0 || (name[1] == '.' && name[2] == 0)); }

/// Removes a folder of files (a staging folder holds files until its commit) and the folder; async-signal-safe.
/// Listed again while files appear in it meanwhile.
void remove_folder_of_files(const char* path) {
  for (int attempt = 0; attempt < 8; ++attempt) {
    const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return;
    alignas(dirent64) char buffer[4096];
    for (long n; (n = ::getdents64(fd, buffer, sizeof buffer)) > 0;)
      for (long at = 0; at < n;) {
        const auto* entry = reinterpret_cast<const dirent64*>(buffer + at);
        if (!is_dot_entry(entry->d_name)) ::unlinkat(fd, entry->d_name, 0);
        at += entry->d_reclen;
      }
    ::close(fd);
    if (::rmdir(path) == 0 || errno == ENOENT) return;
  }
}

void on_terminating_signal(int signal) {
  const int saved_errno = errno;
  int phase = kWorking;
  if (g_phase.compare_exchange_strong(phase, kCleaningUp)) {
    for (Temporary& t : g_temporaries)
      if (t.state.load(std::memory_order_acquire) == 2 && ::unlink(t.path) != 0 && (errno == EISDIR || errno == EPERM))
        remove_folder_of_files(t.path);
    ::signal(signal, SIG_DFL);
    ::raise(signal);  // delivered when the handler returns: the process ends with the signal's status
  } else if (phase == kCommitting) {
    g_pending_signal.store(signal);
  }
  errno = saved_errno;
}

/// Installs the handler once, for each signal the process does not ignore (a background job's SIGINT, nohup's
/// SIGHUP stay ignored).
void install_signal_handler() {
  static std::once_flag once;
  std::call_once(once, [] {
    struct sigaction action {};
    action.sa_handler = on_terminating_signal;
    sigemptyset(&action.sa_mask);
    for (int s : kTerminatingSignals) sigaddset(&action.sa_mask, s);
    action.sa_flags = SA_RESTART;
    for (int s : kTerminatingSignals) {
      struct sigaction previous {};
      if (::sigaction(s, nullptr, &previous) != 0) continue;
      if (!(previous.sa_flags & SA_SIGINFO) && previous.sa_handler == SIG_IGN) continue;
      ::sigaction(s, &action, nullptr);
    }
  });
}

/// Holds a signal's clean-up off while a set is brought in; a signal that came meanwhile is raised again after.
class CommitPhase {
 public:
  CommitPhase() {
    for (int phase = kWorking; !g_phase.compare_exchange_weak(phase, kCommitting); phase = kWorking)
      if (phase == kCleaningUp)
        for (;;) ::pause();  // a signal is ending the process
  }
  ~CommitPhase() {
    g_phase.store(kWorking);
    if (const int signal = g_pending_signal.exchange(0)) ::raise(signal);
  }
  CommitPhase(const CommitPhase&) = delete;
  CommitPhase& operator=(const CommitPhase&) = delete;
};

/// An exclusive lock (flock) on a folder while it lives.
class FolderLock {
 public:
  explicit FolderLock(const fs::path& folder) : fd_(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ >= 0 && ::flock(fd_, LOCK_EX) == 0) return;
    const std::string reason = std::strerror(errno);
    if (fd_ >= 0) ::close(fd_);
    throw InputError(folder.string() + ": cannot lock the folder to bring outputs in (" + reason + ")");
  }
  ~FolderLock() { ::close(fd_); }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_;
};

/// Puts the folder `staged` in the place of `folder` in one rename; the earlier folder ends under `staged`'s name.
void exchange_folders(const fs::path& staged, const fs::path& folder) {
  if (::renameat2(AT_FDCWD, staged.c_str(), AT_FDCWD, folder.c_str(), RENAME_EXCHANGE) == 0) return;
  if (errno != EINVAL && errno != ENOSYS)
    throw InputError(folder.string() + ": cannot bring the outputs in (" + std::strerror(errno) + ")");
  // A file system without the exchange: the earlier folder moves aside first (absent for a moment, never mixed).
  const fs::path aside = staged.string() + "-earlier";
  fs::rename(folder, aside);
  fs::rename(staged, folder);
  fs::rename(aside, staged);
}

bool matches(const std::string& pattern, const std::string& name) {
  const auto star = pattern.find('*');
  if (star == std::string::npos) return pattern == name;
  const std::string head = pattern.substr(0, star), tail = pattern.substr(star + 1);
  return name.size() >= head.size() + tail.size() && name.starts_with(head) && name.ends_with(tail);
}

}  // namespace

/// An entry in the process's temporaries for as long as it lives.
class TemporaryEntry {
 public:
  explicit TemporaryEntry(const fs::path& path) {
    install_signal_handler();
    const std::string p = fs::absolute(path).string();
    if (p.size() >= sizeof(Temporary::path)) throw InputError(p + ": path too long for an output");
    for (int i = 0; i < static_cast<int>(std::size(g_temporaries)) && slot_ < 0; ++i) {
      int free_slot = 0;
      if (!g_temporaries[i].state.compare_exchange_strong(free_slot, 1)) continue;
      std::memcpy(g_temporaries[i].path, p.c_str(), p.size() + 1);
      g_temporaries[i].state.store(2, std::memory_order_release);
      slot_ = i;
    }
    if (slot_ < 0) throw std::logic_error("more temporaries at once than " + std::to_string(std::size(g_temporaries)));
  }
  ~TemporaryEntry() { g_temporaries[slot_].state.store(0, std::memory_order_release); }
  TemporaryEntry(const TemporaryEntry&) = delete;
  TemporaryEntry& operator=(const TemporaryEntry&) = delete;

 private:
  int slot_ = -1;
};

void write_via_temp(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  if (path.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw InputError(path.parent_path().string() + ": cannot create directory (" + ec.message() + ")");
  }
  fs::path tmp = path;
  tmp += ".tmp" + std::to_string(::getpid());
  const TemporaryEntry temporary(tmp);
  try {
    write(tmp);
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError(path.string() + ": cannot write (" + ec.message() + ")");
  }
}

void write_file_atomic(const fs::path& path, const std::string& content) {
  write_via_temp(path, [&](const fs::path& tmp) {
    std::ofstream out(tmp, std::ios::binary);
    out << content;
    out.close();
    if (!out) throw InputError(path.string() + ": cannot write (disk full or no permission?)");
  });
}

OutputSet::OutputSet(fs::path dir, std::vector<std::string> owned)
    : dir_(dir.lexically_normal()), owned_(std::move(owned)) {
  if (!dir_.has_filename()) dir_ = dir_.parent_path();  // "out/x/"
  folder_ = fs::weakly_canonical(fs::absolute(dir_));
  const fs::path here = fs::weakly_canonical(fs::current_path());
  if (std::mismatch(folder_.begin(), folder_.end(), here.begin(), here.end()).first == folder_.end())
    throw InputError(dir_.string() + ": the working directory or above it cannot take outputs (the output folder is "
                                     "replaced whole when a run's files are brought in); name a folder of its own");
  if (fs::exists(folder_) && !fs::is_directory(folder_))
    throw InputError(dir_.string() + ": not a folder; the outputs need a folder");
  static std::atomic<int> sets{0};
  staging_ = folder_.parent_path() / ("." + folder_.filename().string() + ".staging-" + std::to_string(::getpid()) +
                                      "-" + std::to_string(sets++));
  temporary_ = std::make_unique<TemporaryEntry>(staging_);
  std::error_code ec;
  fs::create_directories(staging_, ec);
  if (ec) throw InputError(dir_.string() + ": cannot create the folder's staging folder (" + ec.message() + ")");
}

OutputSet::~OutputSet() {
  for (std::future<void>& w : writers_)
    if (w.valid()) w.wait();  // what it threw is moot: the set is not brought in
  std::error_code ec;
  if (!committed_) fs::remove_all(staging_, ec);
}

void OutputSet::write_beside(std::function<void()> write) {
  writers_.push_back(std::async(std::launch::async, std::move(write)));
}

void OutputSet::wait_for_writers() {
  for (std::future<void>& w : writers_) w.get();
  writers_.clear();
}

void OutputSet::own(const std::vector<std::string>& names) { owned_.insert(owned_.end(), names.begin(), names.end()); }

bool OutputSet::owns(const std::string& name) const {
  return std::any_of(owned_.begin(), owned_.end(), [&](const std::string& p) { return matches(p, name); });
}

fs::path OutputSet::read_path(const fs::path& path) const {
  if (fs::absolute(path).lexically_normal().parent_path() != fs::absolute(dir_).lexically_normal()) return path;
  const fs::path staged = staging_ / path.filename();
  return fs::exists(staged) ? staged : path;
}

void OutputSet::link_others_into_staging() const {
  for (const fs::directory_entry& e : fs::directory_iterator(folder_)) {
    const fs::path name = e.path().filename(), to = staging_ / name;
    if (owns(name.string()) || fs::exists(fs::symlink_status(to))) continue;
    try {
      fs::copy(e.path(), to, fs::copy_options::recursive | fs::copy_options::create_hard_links |
                                 fs::copy_options::copy_symlinks);
    } catch (const fs::filesystem_error&) {  // a file another user owns, a mount inside: copied instead
      fs::remove_all(to);
      fs::copy(e.path(), to, fs::copy_options::recursive | fs::copy_options::copy_symlinks);
    }
  }
}

void OutputSet::commit() {
  wait_for_writers();
  const CommitPhase phase;
  try {
    const FolderLock lock(folder_.parent_path());
    if (owned_.empty() && fs::is_empty(staging_)) {  // nothing written, nothing to remove: the folder stays as it is
    } else if (fs::exists(folder_)) {
      link_others_into_staging();
      exchange_folders(staging_, folder_);
    } else {
      fs::rename(staging_, folder_);
    }
  } catch (const fs::filesystem_error& e) {
    throw InputError(dir_.string() + ": cannot bring the outputs in (" + e.code().message() + ")");
  }
  committed_ = true;
  std::error_code ec;
  fs::remove_all(staging_, ec);  // the earlier folder, under the staging folder's name
  temporary_.reset();
}

}  // namespace sw
