// grtrace/observer/worldline_csv.hpp
// A camera path (observer/worldline.hpp) as a CSV file of (tau, x, u) rows, read, checked and written:
//   read_worldline_csv(path)      the rows, or std::invalid_argument naming the line and what is wrong
//   check_worldline(metric, w)    every u future-directed unit timelike, every event outside the horizon
//   worldline_csv(w)              the text (%.17g: reads back to the same doubles)
#pragma once

#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/observer/worldline.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace grtrace {

/// Bounds on a camera-path file, checked before and while it is read: a row is a frame, and a flight has at most
/// as many frames as --frames allows.
inline constexpr std::size_t kMaxWorldlineRows = 100000;
inline constexpr std::size_t kMaxWorldlineLineBytes = 4096;
inline constexpr std::uintmax_t kMaxWorldlineFileBytes = std::uintmax_t{64} << 20;

/// A camera path from a CSV file: a header line, then one row per frame with nine numbers
///   tau, t, r, theta, phi, u^t, u^r, u^theta, u^phi
/// (proper time, the event in the metric's spherical chart, angles in radians, and the 4-velocity). Blank lines and
/// lines starting with '#' are skipped. Throws std::invalid_argument naming the line and what is wrong: a missing
/// file, one that is not a regular file (a device such as /dev/zero, a FIFO), larger than 64 MiB, a line longer
/// than 4096 bytes, more than 100 000 rows, no rows, a row without nine finite numbers, proper times that do not
/// increase. The 4-velocities are checked against a metric by the caller (check_worldline below).
inline Worldline read_worldline_csv(const std::filesystem::path& path) {
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
    if (w.samples.size() == kMaxWorldlineRows)
      throw std::invalid_argument(path.string() + " line " + std::to_string(number) + ": more than " +
                                  std::to_string(kMaxWorldlineRows) + " camera states (a flight has at most " +
                                  std::to_string(kMaxWorldlineRows) + " frames)");
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
