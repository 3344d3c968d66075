#pragma once
// The readers of the tool's outputs take a path: the fuzz input is written to one file per process (in TMPDIR),
// rewritten on every call.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "common/error.hpp"

namespace sw::fuzz {

inline std::filesystem::path write_input(const std::uint8_t* data, std::size_t size, const std::string& name) {
  static const std::filesystem::path dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    auto d = std::filesystem::path(tmp != nullptr ? tmp : "/tmp") / ("sw_fuzz_" + std::to_string(getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const auto path = dir / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) std::abort();
  return path;
}

/// What `read` makes of the file at `path`, written by `write` and read again, must write the same text (the reader
/// and the writer share one field table): otherwise abort, a defect. InputError is the readers' answer to bad input.
template <class Read, class Write>
void expect_written_back(const std::filesystem::path& path, Read read, Write write) {
  try {
    const std::string text = write(read(path));
    const auto again = write_input(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), "again.json");
    if (write(read(again)) != text) std::abort();
  } catch (const sw::InputError&) {
  }
}

}  // namespace sw::fuzz
