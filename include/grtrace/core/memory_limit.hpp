// grtrace/core/memory_limit.hpp
// One memory limit for everything whose size comes from input (image sizes, EXR data windows, PNGs): checked
// before allocating, so a forged header or a mistyped --width is refused with a message that says the limit and
// how to raise it, instead of std::bad_alloc or a machine brought to its knees.
#pragma once

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <iterator>
#include <stdexcept>
#include <string>

namespace grtrace {

/// Thrown when an image (or anything sized by input) would need more memory than memory_limit_bytes().
struct MemoryLimitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The most memory (bytes) one image or input file may claim: the environment variable GRTRACE_MEMORY_LIMIT
/// (a number of bytes with an optional K, M, G or T suffix, powers of 1024: "16G") if set, else 4 GiB.
/// Checked before allocating, so a forged or mistyped size is refused with a message instead of std::bad_alloc.
/// A value that is not such a size throws MemoryLimitError saying so (a mistyped limit is not silently 4 GiB).
inline std::size_t memory_limit_bytes() {
  constexpr std::size_t kDefault = std::size_t{4} << 30;
  const char* env = std::getenv("GRTRACE_MEMORY_LIMIT");
  if (env == nullptr || *env == '\0') return kDefault;
  char* end = nullptr;
  const double v = std::strtod(env, &end);
  double scale = 1.0;
  switch (*end) {
    case 'k': case 'K': scale = 1024.0; ++end; break;
    case 'm': case 'M': scale = 1024.0 * 1024.0; ++end; break;
    case 'g': case 'G': scale = 1024.0 * 1024.0 * 1024.0; ++end; break;
    case 't': case 'T': scale = 1024.0 * 1024.0 * 1024.0 * 1024.0; ++end; break;
    default: break;
  }
  if (end == env || *end != '\0' || !(v > 0.0) || !(v * scale < 1.8e19))
    throw MemoryLimitError("GRTRACE_MEMORY_LIMIT='" + std::string(env) +
                           "' is not a memory size: give bytes with an optional K, M, G or T suffix (e.g. 16G), "
                           "or unset it for the default of 4 GiB");
  return static_cast<std::size_t>(v * scale);
}

/// "1.73 GB" (decimal units, as a user reads them).
inline std::string describe_bytes(double bytes) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
  std::size_t u = 0;
  while (bytes >= 1000.0 && u + 1 < std::size(units)) {
    bytes /= 1000.0;
    ++u;
  }
  char buf[64];
  if (u == 0) std::snprintf(buf, sizeof buf, "%.0f %s", bytes, units[u]);
  else std::snprintf(buf, sizeof buf, "%.2f %s", bytes, units[u]);
  return buf;
}

/// Throws MemoryLimitError when `bytes` exceeds memory_limit_bytes(); `what` says what needs it
/// ("a 16384 x 16384 image with 9 channels").
inline void check_memory(double bytes, const std::string& what) {
  const auto limit = static_cast<double>(memory_limit_bytes());
  if (!(bytes <= limit))
    throw MemoryLimitError(what + " needs " + describe_bytes(bytes) + ", above the memory limit of " +
                           describe_bytes(limit) + " (set the environment variable GRTRACE_MEMORY_LIMIT, e.g. " +
                           "GRTRACE_MEMORY_LIMIT=16G, to raise it)");
}

/// Bytes of an image of float channels.
inline double image_bytes(double width, double height, double channels) { return width * height * channels * 4.0; }

}  // namespace grtrace
