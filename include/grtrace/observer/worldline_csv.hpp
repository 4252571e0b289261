// grtrace/observer/worldline_csv.hpp
// A camera path (observer/worldline.hpp) as a CSV file of (tau, x, u) rows, read, checked and written:
//   read_worldline_csv(path)      the rows, or std::invalid_argument naming the line and what is wrong
//   read_worldline_csv(path, &source)   the same, and where each row came from (file and line)
//   check_worldline(metric, w [, &source])   every u future-directed unit timelike, every event outside the
//                                            horizon and off the polar axis; errors name the file's line
//   worldline_csv(w)              the text (%.17g: reads back to the same doubles)
#pragma once

#include "grtrace/core/number_text.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/observer/worldline.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace grtrace {

/// Bounds on a camera-path file, checked before and while it is read: a row is a frame, and a flight has at most
/// as many frames as --frames allows.
inline constexpr std::size_t kMaxWorldlineRows = 100000;
inline constexpr std::size_t kMaxWorldlineLineBytes = 4096;
inline constexpr std::uintmax_t kMaxWorldlineFileBytes = std::uintmax_t{64} << 20;

/// Where each sample of a camera path read from a file came from, so that errors found later (check_worldline)
/// name the line to change.
struct WorldlineSource {
  std::filesystem::path file;
  std::vector<int> lines;  ///< lines[i]: the 1-based line of sample i
  /// "<file> line <n>" for sample i (or "camera state i" when the line is unknown).
  std::string where(std::size_t i) const {
    if (i < lines.size()) return file.string() + " line " + std::to_string(lines[i]);
    return "camera state " + std::to_string(i);
  }
};

/// A camera path from a CSV file: a header line, then one row per frame with nine numbers
///   tau, t, r, theta, phi, u^t, u^r, u^theta, u^phi
/// (proper time, the event in the metric's spherical chart, angles in radians, and the 4-velocity). Blank lines and
/// lines starting with '#' are skipped. Throws std::invalid_argument naming the line and what is wrong: a missing
/// file, one that is not a regular file (a device such as /dev/zero, a FIFO), larger than 64 MiB, a line longer
/// than 4096 bytes, more than 100 000 rows, no rows, a row without nine finite numbers, proper times that do not
/// increase. Numbers are read as the tools read their options (core/number_text.hpp). The 4-velocities are checked
/// against a metric by the caller (check_worldline below); `source`, when given, receives each row's line for it.
inline Worldline read_worldline_csv(const std::filesystem::path& path, WorldlineSource* source = nullptr) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status))
    throw std::invalid_argument("cannot read the camera path '" + path.string() + "': no such file");
  if (!fs::is_regular_file(status))
    throw std::invalid_argument("the camera path '" + path.string() + "' is not a regular file (a directory, device or "
                                "pipe); name a CSV file");
  if (const std::uintmax_t bytes = fs::file_size(path, ec); ec || bytes > kMaxWorldlineFileBytes)
    throw std::invalid_argument("the camera path '" + path.string() + "' is larger than 64 MiB (at most " +
                                std::to_string(kMaxWorldlineRows) + " rows of nine numbers are read)");
  std::ifstream in(path);
  if (!in) throw std::invalid_argument("cannot read the camera path '" + path.string() + "'");
  Worldline w;
  std::string line;
  int number = 0;
  bool header = true;
  while (std::getline(in, line)) {
    ++number;
    if (line.size() > kMaxWorldlineLineBytes)
      throw std::invalid_argument(path.string() + " line " + std::to_string(number) + ": longer than " +
                                  std::to_string(kMaxWorldlineLineBytes) + " bytes (a row is nine numbers)");
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
      const ParsedNumber parsed = parse_finite_number(cell);
      if (parsed.result != NumberText::ok)
        throw std::invalid_argument(path.string() + " line " + std::to_string(number) + ": '" + cell + "' " +
                                    number_text_problem(parsed.result) + " (column " + std::to_string(n + 1) +
                                    " of tau,t,r,theta,phi,ut,ur,utheta,uphi)");
      v[static_cast<std::size_t>(n)] = parsed.value;
      ++n;
    }
    if (n != 9)
      throw std::invalid_argument(path.string() + " line " + std::to_string(number) +
                                  ": need 9 numbers (tau,t,r,theta,phi,ut,ur,utheta,uphi), got " +
                                  (n == 10 ? std::string("more") : std::to_string(n)));
    if (!w.samples.empty() && !(v[0] > w.samples.back().tau))
      throw std::invalid_argument(path.string() + " line " + std::to_string(number) +
                                  ": proper time tau must increase from row to row");
    if (w.samples.size() == kMaxWorldlineRows)
      throw std::invalid_argument(path.string() + " line " + std::to_string(number) + ": more than " +
                                  std::to_string(kMaxWorldlineRows) + " camera states (a flight has at most " +
                                  std::to_string(kMaxWorldlineRows) + " frames)");
    w.samples.push_back({v[0], Vec4(v[1], v[2], v[3], v[4]), Vec4(v[5], v[6], v[7], v[8])});
    if (source) source->lines.push_back(number);
  }
  if (source) source->file = path;
  if (w.samples.empty()) throw std::invalid_argument(path.string() + ": no camera states (a header line, then rows)");
  return w;
}

/// Checks every sample of a camera path against the metric (spherical chart): theta strictly between 0 and pi
/// (the chart, and so a camera's frame, is singular on the polar axis), the event outside the horizon, u
/// future-directed with |g(u, u) - 1| <= 1e-6. Throws std::invalid_argument naming the first bad sample: its file and
/// line when `source` says (read_worldline_csv), else "camera state i" (0-based).
template <MetricPolicy M>
void check_worldline(const M& metric, const Worldline& w, const WorldlineSource* source = nullptr) {
  const WorldlineSource unknown;
  const WorldlineSource& from = source ? *source : unknown;
  for (std::size_t i = 0; i < w.samples.size(); ++i) {
    const WorldlineSample& s = w.samples[i];
    if (!(s.x[2] > 0.0 && s.x[2] < std::numbers::pi))
      throw std::invalid_argument(from.where(i) + ": theta = " + std::to_string(s.x[2]) +
                                  " rad is on or beyond the polar axis, where the spherical chart is singular; a "
                                  "camera needs 0 < theta < pi (radians; a flight's camera-path file may put a row "
                                  "on the axis, 0 or pi, which is placed 1e-9 rad off it)");
    if (const double rh = metric.horizon_radius(); rh > 0.0 && !(metric.radius(s.x) > rh))
      throw std::invalid_argument(from.where(i) + ": r = " + std::to_string(metric.radius(s.x)) +
                                  " is on or inside the horizon");
    const double norm = inner_product(metric, s.x, s.u, s.u);
    if (!(std::abs(norm - 1.0) <= 1e-6) || !(s.u[0] > 0.0))
      throw std::invalid_argument(from.where(i) + ": g(u, u) = " + std::to_string(norm) +
                                  ", u^t = " + std::to_string(s.u[0]) +
                                  "; a camera's 4-velocity must be future-directed with g(u, u) = 1");
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
