// grtrace/spectra/line_profile_result.hpp
// What a line profile is (spectra/line_profile.hpp computes it; line_profile_output.hpp writes it): plain data, so
// that a caller holding one (the application library's front door) need not read the code that makes it.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace grtrace {

struct LineProfile {
  static constexpr int kOrderChannels = 4;  ///< n = 0, 1, 2 and >= 3
  std::vector<double> edges;                ///< bins + 1 energies
  std::vector<double> flux;                 ///< per bin: F_E (see spectra/line_profile.hpp)
  std::array<std::vector<double>, kOrderChannels> flux_by_order;
  std::array<double, kOrderChannels> total_by_order{};  ///< int F_E dE over the bins, per order
  double total = 0.0;                                   ///< int F_E dE over the bins
  double outside = 0.0;          ///< int F_E dE of the light that fell outside the bins asked for (automatic bins: 0)
  double half_width = 0.0;       ///< the image square's half width (M)
  long rays = 0, triangles = 0;  ///< all traced (automatic bins made again where light fell outside: both meshes)
  long unresolved = 0;           ///< triangles left mixed at the finest cell (partial, first-order)
  long uncovered = 0;            ///< rays the map could not follow (KerrDiskMap: exact/kerr_null_geodesic.hpp's limits)
};

/// A picture: 3 * width * height bytes of 8-bit RGB, the top row first (line_profile_output.hpp's plot).
struct LineChart {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

}  // namespace grtrace
