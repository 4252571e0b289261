// grtrace/render/flight_files.hpp
// The files of a camera flight (render/flight.hpp): numbered frame names, the test that lets a re-run skip the
// frames already written whole, and the MP4 assembled from the PNG previews by ffmpeg.
//
//   flight_frame_path("out/orbit.exr", 7, 300)  -> "out/orbit-0007.exr" (at least 4 digits, more for long flights)
//   flight_signature(options)                    -> a hash of everything that decides the frames' content
//   flight_frame_done(exr, png, signature)       -> true when the EXR reads back whole with that signature and its
//                                                   PNG exists (frames are written with OutputSet: temp + rename,
//                                                   so a frame on disk was written whole; a killed run leaves
//                                                   only its own temporaries, which are removed)
//   assemble_mp4(set, pattern, frames, fps, mp4) -> ffmpeg (H.264, yuv420p) into a temporary committed with `set`
//   read_worldline_csv / check_worldline / worldline_csv: a camera path as a CSV of (tau, x, u) rows
#pragma once

#include "grtrace/observer/worldline.hpp"
#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/output_file.hpp"

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <map>
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

/// True when the frame was written whole by a flight with this signature: the PNG exists and the EXR reads back
/// (every pixel: a truncated or damaged file is not "done") with a "flight_signature" attribute equal to it.
inline bool flight_frame_done(const std::filesystem::path& exr, const std::filesystem::path& png,
                              const std::string& signature) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(exr, ec) || !std::filesystem::is_regular_file(png, ec)) return false;
  try {
    const Image image = read_exr(exr);
    const auto it = image.metadata.find("flight_signature");
    return it != image.metadata.end() && it->second == signature;
  } catch (const std::exception&) {
    return false;  // unreadable: rendered again
  }
}

/// ffmpeg's image-sequence pattern for the flight's PNG previews ('%' in the path itself doubled).
inline std::string flight_png_pattern(const std::filesystem::path& out_png, int frames) {
  std::string stem;
  for (const char c : out_png.stem().string()) stem += c == '%' ? std::string("%%") : std::string(1, c);
  std::string dir;
  for (const char c : out_png.parent_path().string()) dir += c == '%' ? std::string("%%") : std::string(1, c);
  const std::string name = stem + "-%0" + std::to_string(flight_frame_digits(frames)) + "d.png";
  return dir.empty() ? name : dir + "/" + name;
}

/// Runs `argv` (argv[0] looked up on PATH), waits, and returns its exit status (127: it could not be started).
inline int run_program(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  if (::posix_spawnp(&pid, args[0], nullptr, nullptr, args.data(), environ) != 0) return 127;
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return 127;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
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
  const int status = run_program({"ffmpeg", "-hide_banner", "-loglevel", "error", "-nostdin", "-y", "-framerate",
                                  rate, "-start_number", "0", "-i", png_pattern, "-frames:v", std::to_string(frames),
                                  "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-c:v", "libx264", "-pix_fmt", "yuv420p",
                                  "-movflags", "+faststart", "-f", "mp4", out.temporary().string()});
  if (status == 127)
    throw std::runtime_error("cannot run ffmpeg to assemble " + mp4.string() +
                             " (install it: bash cmake/install-deps.sh, or leave out --mp4)");
  if (status != 0)
    throw std::runtime_error("ffmpeg failed (exit status " + std::to_string(status) + ") assembling " + mp4.string());
  out.finish();
}

}  // namespace grtrace

namespace grtrace {

/// A camera path from a CSV file: a header line, then one row per frame with nine numbers
///   tau, t, r, theta, phi, u^t, u^r, u^theta, u^phi
/// (proper time, the event in the metric's spherical chart, angles in radians, and the 4-velocity). Blank lines and
/// lines starting with '#' are skipped. Throws std::invalid_argument naming the line and what is wrong: a missing
/// file, no rows, a row without nine finite numbers, proper times that do not increase.
/// The 4-velocities are checked against a metric by the caller (check_worldline below).
inline Worldline read_worldline_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("cannot read the camera path '" + path.string() + "'");
  Worldline w;
  std::string line;
  int number = 0;
  bool header = true;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t\r") == std::string::npos) continue;
    if (header) {  // the first non-blank line names the columns
      header = false;
      continue;
    }
    std::array<double, 9> v{};
    std::stringstream row(line);
    std::string cell;
    int n = 0;
    while (std::getline(row, cell, ',')) {
      if (n == 9) {
        n = 10;
        break;
      }
      try {
        std::size_t used = 0;
        v[static_cast<std::size_t>(n)] = std::stod(cell, &used);
        if (cell.find_first_not_of(" \t\r", used) != std::string::npos) throw std::invalid_argument(cell);
      } catch (const std::exception&) {
        throw std::invalid_argument(path.string() + " line " + std::to_string(number) + ": '" + cell +
                                    "' is not a number (columns: tau,t,r,theta,phi,ut,ur,utheta,uphi)");
      }
      if (!std::isfinite(v[static_cast<std::size_t>(n)]))
        throw std::invalid_argument(path.string() + " line " + std::to_string(number) + ": non-finite number");
      ++n;
    }
    if (n != 9)
      throw std::invalid_argument(path.string() + " line " + std::to_string(number) +
                                  ": need 9 numbers (tau,t,r,theta,phi,ut,ur,utheta,uphi), got " +
                                  (n == 10 ? std::string("more") : std::to_string(n)));
    if (!w.samples.empty() && !(v[0] > w.samples.back().tau))
      throw std::invalid_argument(path.string() + " line " + std::to_string(number) +
                                  ": proper time tau must increase from row to row");
    w.samples.push_back({v[0], Vec4(v[1], v[2], v[3], v[4]), Vec4(v[5], v[6], v[7], v[8])});
  }
  if (w.samples.empty()) throw std::invalid_argument(path.string() + ": no camera states (a header line, then rows)");
  return w;
}

/// Checks every sample of a camera path against the metric: u future-directed with |g(u, u) - 1| <= 1e-6, the
/// event outside the horizon. Throws std::invalid_argument naming the first bad sample (0-based).
template <MetricPolicy M>
void check_worldline(const M& metric, const Worldline& w) {
  for (std::size_t i = 0; i < w.samples.size(); ++i) {
    const WorldlineSample& s = w.samples[i];
    const double norm = inner_product(metric, s.x, s.u, s.u);
    if (!(std::abs(norm - 1.0) <= 1e-6) || !(s.u[0] > 0.0))
      throw std::invalid_argument("camera state " + std::to_string(i) + ": g(u, u) = " + std::to_string(norm) +
                                  ", u^t = " + std::to_string(s.u[0]) +
                                  "; a camera's 4-velocity must be future-directed with g(u, u) = 1");
    if (const double rh = metric.horizon_radius(); rh > 0.0 && !(metric.radius(s.x) > rh))
      throw std::invalid_argument("camera state " + std::to_string(i) + ": r = " + std::to_string(metric.radius(s.x)) +
                                  " is on or inside the horizon");
  }
}

/// Writes a camera path in read_worldline_csv's format (%.17g: reads back to the same doubles).
inline std::string worldline_csv(const Worldline& w) {
  std::string out = "tau,t,r,theta,phi,ut,ur,utheta,uphi\n";
  char buf[64];
  for (const WorldlineSample& s : w.samples) {
    const double v[9] = {s.tau, s.x[0], s.x[1], s.x[2], s.x[3], s.u[0], s.u[1], s.u[2], s.u[3]};
    for (int i = 0; i < 9; ++i) {
      std::snprintf(buf, sizeof buf, i ? ",%.17g" : "%.17g", v[i]);
      out += buf;
    }
    out += "\n";
  }
  return out;
}

}  // namespace grtrace
