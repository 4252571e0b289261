// examples/common/atomic_file.hpp
// Outputs are written whole or not at all: write to "<path>.tmp-<pid>", then rename over the target.
#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <unistd.h>

namespace grtrace::tools {

inline std::filesystem::path temporary_sibling(const std::filesystem::path& target) {
  return target.string() + ".tmp-" + std::to_string(::getpid());
}

/// Throws std::runtime_error (and leaves nothing behind) when the directory is missing or not writable.
inline void check_writable_target(const std::filesystem::path& target) {
  const auto dir = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(dir))
    throw std::runtime_error("cannot write '" + target.string() + "': directory '" + dir.string() +
                             "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error("cannot write '" + target.string() + "': directory '" + dir.string() +
                             "' is not writable");
}

/// Calls write(temporary path), then renames it to `target`; removes the temporary on any failure.
inline void write_atomically(const std::filesystem::path& target,
                             const std::function<void(const std::filesystem::path&)>& write) {
  const auto tmp = temporary_sibling(target);
  try {
    write(tmp);
    std::filesystem::rename(tmp, target);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

/// Text files (CSV, JSON): the stream is checked after flushing so a full disk is an error, not a short file.
inline void write_text_atomically(const std::filesystem::path& target,
                                  const std::function<void(std::ostream&)>& write) {
  write_atomically(target, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp);
    if (!out) throw std::runtime_error("cannot open '" + tmp.string() + "' for writing");
    write(out);
    out.flush();
    if (!out) throw std::runtime_error("failed while writing '" + tmp.string() + "'");
  });
}

}  // namespace grtrace::tools
