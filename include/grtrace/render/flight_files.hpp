// grtrace/render/flight_files.hpp
// The files of a camera flight (render/flight.hpp): numbered frame names, the test that lets a re-run skip the
// frames already written whole, and the MP4 assembled from the PNG previews by ffmpeg.
//
//   flight_frame_path("out/orbit.exr", 7, 300)  -> "out/orbit-0007.exr" (at least 4 digits, more for long flights)
//   flight_signature(options)                    -> a hash of everything that decides the frames' content
//   parse_flight_frame_range("30:60", 300)       -> frames 30 .. 59, one part of a flight split over a cluster
//   flight_frame_done(exr, png, signature)       -> true when the EXR reads back whole with that signature and its
//                                                   PNG's chunks are whole, of the same size (frames are written
//                                                   with OutputSet: temp + rename, so a frame on disk was written
//                                                   whole; a killed run leaves only its own temporaries, which
//                                                   are removed; a frame damaged later is rendered again)
//   assemble_mp4(set, pattern, frames, fps, mp4) -> ffmpeg (H.264, yuv420p) into a temporary committed with `set`
// (Camera paths as CSV files: observer/worldline_csv.hpp.)
#pragma once

#include "grtrace/core/number_text.hpp"
#include "grtrace/observer/worldline_csv.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/output_file.hpp"
#include "grtrace/render/png_preview.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

extern char** environ;

namespace grtrace {

/// Digits of the frame numbers of a flight of `frames` frames: 4, or more when 10000 frames or more.
inline int flight_frame_digits(int frames) {
  int digits = 1;
  for (int n = frames > 1 ? frames - 1 : 1; n >= 10; n /= 10) ++digits;
  return std::max(4, digits);
}

/// "<dir>/<stem>-<index, zero-padded>.<ext>" from the flight's output name "<dir>/<stem>.<ext>".
inline std::filesystem::path flight_frame_path(const std::filesystem::path& out, int index, int frames) {
  char number[32];
  std::snprintf(number, sizeof number, "-%0*d", flight_frame_digits(frames), index);
  std::filesystem::path p = out;
  p.replace_filename(out.stem().string() + number + out.extension().string());
  return p;
}

/// A part of a flight's frames, frames first .. end - 1 (half-open, 0-based): one task of a cluster's job array
/// renders one part, and the frames are the same as from one run (each frame depends on its index only).
struct FlightFrameRange {
  int first = 0;
  int end = 0;
  bool contains(int i) const { return i >= first && i < end; }
  int count() const { return end - first; }
  /// "A:B" as given.
  std::string text() const { return std::to_string(first) + ":" + std::to_string(end); }
};

/// The range "A:B" of a flight of `frames` frames: whole numbers with 0 <= A < B <= frames (B = frames: to the
/// last frame). Throws std::invalid_argument saying what to change.
inline FlightFrameRange parse_flight_frame_range(const std::string& text, int frames) {
  const auto colon = text.find(':');
  const ParsedWholeNumber a = parse_whole_number(text.substr(0, colon));
  const ParsedWholeNumber b =
      colon == std::string::npos ? ParsedWholeNumber{} : parse_whole_number(text.substr(colon + 1));
  if (a.result != NumberText::ok || b.result != NumberText::ok)
    throw std::invalid_argument("--frame-range expects A:B, two whole numbers (frames A to B - 1), got '" + text + "'");
  if (!(a.value >= 0 && a.value < b.value && b.value <= frames))
    throw std::invalid_argument("--frame-range " + text + " must satisfy 0 <= A < B <= " + std::to_string(frames) +
                                " (the flight's frame count; B is one past the last frame rendered)");
  return {static_cast<int>(a.value), static_cast<int>(b.value)};
}

/// 64-bit FNV-1a of "key=value\n" for every entry (ordered by key), as 16 hex digits. Takes the options that
/// decide the frames' content (the caller leaves out those that do not, e.g. threads, progress, the mp4 request).
inline std::string flight_signature(const std::map<std::string, std::string>& options) {
  std::uint64_t h = 14695981039346656037ull;
  auto mix = [&](const std::string& s) {
    for (const char ch : s) {
      const auto c = static_cast<unsigned char>(ch);
      h ^= c;
      h *= 1099511628211ull;
    }
  };
  for (const auto& [key, value] : options) mix(key + "=" + value + "\n");
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
}

/// The header of the scanline EXR at `path` when the file holds every chunk that header promises, else nothing;
/// read without decompressing a pixel, after the checks every EXR read gets (nothing for a file they refuse): the
/// magic number and version, the header, then the offsets
/// of its ceil(height / lines per chunk) chunks; each chunk starts with its first line's y and its byte count, and
/// every chunk must lie inside the file. A tiled or multi-part file is not one grtrace writes: nothing.
/// Throws what OpenEXR throws for a header it cannot parse.
inline std::optional<Imf::Header> whole_scanline_exr_header(const std::filesystem::path& path) {
  // Checked as every EXR grtrace reads is (exr_io.hpp checked_exr_header) before OpenEXR parses it here: a file
  // planted among the frames that claims a 2 GiB attribute is refused, not allocated.
  try {
    (void)detail::checked_exr_header(path);
  } catch (const std::runtime_error&) {
    return std::nullopt;
  }
  std::ifstream file(path, std::ios::binary | std::ios::ate);
  if (!file) return std::nullopt;
  const auto size = static_cast<std::uint64_t>(file.tellg());
  file.seekg(0);
  auto read_le = [&](int bytes) {
    unsigned char b[8] = {};
    file.read(reinterpret_cast<char*>(b), bytes);
    std::uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = v << 8 | b[i];
    return v;
  };
  int version = 0;  // readFrom may adjust it
  try {
    version = detail::read_exr_start(file);
  } catch (const std::runtime_error&) {
    return std::nullopt;  // too short, or not an EXR
  }
  // Parsed a second time (the check above read the header through OpenEXR's own file): here it is the stream's
  // position after it that matters, where the chunk table starts.
  Imf::StdIFStream stream(file, path.c_str());
  Imf::Header header;
  header.readFrom(stream, version);
  if (header.hasTileDescription()) return std::nullopt;
  const Imath::Box2i window = header.dataWindow();
  const long height = static_cast<long>(window.max.y) - window.min.y + 1;
  const long per_chunk = detail::exr_lines_per_chunk(header.compression());
  const long chunks = (height + per_chunk - 1) / per_chunk;
  const auto table_end = static_cast<std::uint64_t>(file.tellg()) + 8u * static_cast<std::uint64_t>(chunks);
  if (!file || table_end > size) return std::nullopt;
  std::vector<std::uint64_t> offsets(static_cast<std::size_t>(chunks));
  for (auto& o : offsets) o = read_le(8);
  if (!file) return std::nullopt;
  for (const std::uint64_t o : offsets) {
    if (o < table_end || o + 8 > size) return std::nullopt;
    file.seekg(static_cast<std::streamoff>(o) + 4);  // skip the chunk's first y
    const std::uint64_t bytes = read_le(4);
    if (!file || o + 8 + bytes > size) return std::nullopt;
  }
  return header;
}

/// True when the frame was written whole by a flight with this signature: the EXR holds every chunk of pixels its
/// header promises with a "flight_signature" attribute equal to it, and the PNG's chunks are whole (whole_png_size)
/// with the EXR's size (a truncated or damaged file, or another flight's frame, is rendered again). Reads headers
/// and chunk tables only: a resumed 300-frame flight checks its frames in well under a second instead of decoding
/// each one.
inline bool flight_frame_done(const std::filesystem::path& exr, const std::filesystem::path& png,
                              const std::string& signature) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(exr, ec) || !std::filesystem::is_regular_file(png, ec)) return false;
  try {
    const std::optional<Imf::Header> header = whole_scanline_exr_header(exr);
    const auto* recorded = header ? header->findTypedAttribute<Imf::StringAttribute>("flight_signature") : nullptr;
    if (!recorded || recorded->value() != signature) return false;
    const Imath::Box2i window = header->dataWindow();
    const std::optional<std::array<int, 2>> png_size = whole_png_size(png);
    return png_size && (*png_size)[0] == window.max.x - window.min.x + 1 &&
           (*png_size)[1] == window.max.y - window.min.y + 1;
  } catch (const std::exception&) {
    return false;  // unreadable: rendered again
  }
}

/// ffmpeg's image-sequence pattern for the flight's PNG previews ('%' in the path itself doubled).
inline std::string flight_png_pattern(const std::filesystem::path& out_png, int frames) {
  auto escaped = [](const std::string& text) {
    std::string out;
    for (const char c : text) out += c == '%' ? std::string("%%") : std::string(1, c);
    return out;
  };
  const std::string dir = escaped(out_png.parent_path().string());
  const std::string name = escaped(out_png.stem().string()) + "-%0" + std::to_string(flight_frame_digits(frames)) + "d.png";
  return dir.empty() ? name : dir + "/" + name;
}

/// Runs `argv` (argv[0] looked up on PATH), waits, and returns its exit status (127: it could not be started).
/// With `error_output`, the program's standard error goes there (its last 64 kB) instead of to ours, so the caller
/// can word it (e.g. name the file the user asked for, not the temporary the program wrote).
inline int run_program(const std::vector<std::string>& argv, std::string* error_output = nullptr) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  int pipe_fds[2] = {-1, -1};
  posix_spawn_file_actions_t actions;
  ::posix_spawn_file_actions_init(&actions);
  if (error_output) {
    if (::pipe2(pipe_fds, O_CLOEXEC) != 0) {
      ::posix_spawn_file_actions_destroy(&actions);
      return 127;
    }
    ::posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], 2);  // dup2 clears close-on-exec on fd 2
  }
  // The child is registered (detail::g_writing_child) with the cleanup signals blocked, so that a signal ending this
  // process kills and reaps it before removing the temporary it writes; it starts with no signal blocked.
  sigset_t block, old;
  ::sigemptyset(&block);
  for (const int sig : detail::kCleanupSignals) ::sigaddset(&block, sig);
  posix_spawnattr_t attributes;
  ::posix_spawnattr_init(&attributes);
  sigset_t none;
  ::sigemptyset(&none);
  ::posix_spawnattr_setsigmask(&attributes, &none);
  ::posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  ::pthread_sigmask(SIG_BLOCK, &block, &old);
  pid_t pid = 0;
  const int spawned = ::posix_spawnp(&pid, args[0], &actions, &attributes, args.data(), environ);
  if (spawned == 0) detail::g_writing_child.store(pid);
  ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
  ::posix_spawnattr_destroy(&attributes);
  ::posix_spawn_file_actions_destroy(&actions);
  struct Unregister {  // on any way out: never killed by pid again
    ~Unregister() { detail::g_writing_child.store(0); }
  } unregister;
  if (error_output) {
    ::close(pipe_fds[1]);
    if (spawned == 0) {
      char buffer[4096];
      for (;;) {
        const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        error_output->append(buffer, static_cast<std::size_t>(n));
        if (error_output->size() > 65536) error_output->erase(0, error_output->size() - 65536);
      }
    }
    ::close(pipe_fds[0]);
  }
  if (spawned != 0) return 127;
  // Waited for without reaping it first (WNOWAIT): unregistered while it is a zombie, whose pid is not reused, so a
  // signal in between cannot kill another process that got the pid.
  siginfo_t info{};
  while (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOWAIT) < 0) {
    if (errno != EINTR) return 127;
  }
  detail::g_writing_child.store(0);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return 127;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

/// True when `name` is an executable file in one of the directories of $PATH (what execvp would run): a command
/// that needs a program (--mp4: ffmpeg) checks it before any work instead of failing after the frames.
inline bool program_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::string dirs(path);
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = end > start ? dirs.substr(start, end - start) : std::string(".");
    const std::filesystem::path candidate = std::filesystem::path(dir) / name;
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

/// Encodes the flight's PNG previews (pattern from flight_png_pattern, frames 0 .. frames - 1) as an H.264 MP4 at
/// `fps` frames per second, written into a temporary of `set` (committed, with the rest, by the caller).
/// Throws std::runtime_error when ffmpeg is missing (install it: cmake/install-deps.sh) or fails.
inline void assemble_mp4(OutputSet& set, const std::string& png_pattern, int frames, double fps,
                         const std::filesystem::path& mp4) {
  TemporaryOutput& out = set.add(mp4);
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.17g", fps);
  // Even sizes for yuv420p (x264 refuses odd ones): pad by one pixel where needed.
  std::string said;  // ffmpeg's messages, which name the temporary it writes: reworded with the target's name
  const std::string temporary = out.temporary().string();
  const int status = run_program({"ffmpeg", "-hide_banner", "-loglevel", "error", "-nostdin", "-y", "-framerate",
                                  rate, "-start_number", "0", "-i", png_pattern, "-frames:v", std::to_string(frames),
                                  "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p",
                                  "-movflags", "+faststart", "-f", "mp4", temporary},
                                 &said);
  if (status == 127)
    throw std::runtime_error("cannot run ffmpeg to assemble " + mp4.string() +
                             " (install it: bash cmake/install-deps.sh, or leave out --mp4)");
  if (status != 0) {
    for (std::size_t at = said.find(temporary); at != std::string::npos; at = said.find(temporary, at))
      said.replace(at, temporary.size(), mp4.string());
    while (!said.empty() && (said.back() == '\n' || said.back() == '\r')) said.pop_back();
    throw std::runtime_error("ffmpeg failed (exit status " + std::to_string(status) + ") assembling " +
                             mp4.string() + (said.empty() ? std::string() : ": " + said));
  }
  out.finish();
}

}  // namespace grtrace

