#pragma once
// Outputs are written to a temporary name beside the target and renamed, so an interrupted run never leaves a half
// file. Directories are created as needed. Throws InputError when the path cannot be written.
#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace sw {

/// Writes `content` to `path` atomically (temp file + rename).
void write_file_atomic(const std::filesystem::path& path, const std::string& content);

/// Calls `write(tmp_path)` to produce the file under a temporary name, then renames it to `path`
/// (for writers that insist on a file name, like VTK's).
void write_via_temp(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write);

}  // namespace sw
