#include "io/atomic_file.hpp"

#include <fstream>
#include <unistd.h>

#include "common/error.hpp"

namespace sw {

namespace fs = std::filesystem;

void write_via_temp(const fs::path& path, const std::function<void(const fs::path&)>& write) {
  if (path.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec) throw InputError(path.parent_path().string() + ": cannot create directory (" + ec.message() + ")");
  }
  fs::path tmp = path;
  tmp += ".tmp" + std::to_string(::getpid());
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

}  // namespace sw
