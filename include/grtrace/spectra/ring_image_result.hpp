// grtrace/spectra/ring_image_result.hpp
// What a ring image is (spectra/ring_image.hpp computes it; ring_image_output.hpp draws it): plain data, so that a
// caller holding one (the application library's front door) need not read the code that makes it.
#pragma once

#include <array>
#include <vector>

namespace grtrace {

/// The rings' shape: per order n (index n; index 0 unused: NaN) the mean diameter and width over the cuts, and
/// per cut the width and radius of each order's image (0 where it is not seen).
struct RingGeometry {
  static constexpr int kOrders = 4;
  double centre_alpha = 0.0;  ///< the cuts' centre (on the alpha axis)
  std::array<double, kOrders> diameter{}, width{};
  std::array<int, kOrders> cuts_seen{};
  /// per order channel (n = 1, 2, >= 3; index 0 unused): int I dalpha dbeta over the whole screen, for the orders
  /// integrated along the cuts (measure_rings: n >= 1; ring_image: n >= 2, its mesh takes n = 1), else 0
  std::array<double, kOrders> flux{};
  std::vector<double> cut_angle, critical_radius;                  ///< per cut
  std::vector<std::array<double, kOrders>> cut_width, cut_radius;  ///< per cut, per order (1, 2, 3)
  std::vector<std::array<double, kOrders>> cut_flux;  ///< per cut, per order channel: int I rho drho along the cut
  long rays = 0;
};

struct RingImage {
  static constexpr int kOrderChannels = 4;  ///< n = 0, 1, 2 and >= 3
  int width = 0, height = 0;
  double half_width = 0.0, pixel = 0.0;                       ///< the field's half width and a pixel's side (M)
  std::array<std::vector<double>, kOrderChannels> intensity;  ///< per order: width * height, the top row first
  std::array<double, kOrderChannels> flux{};                  ///< per order: int I dalpha dbeta over the field
  RingGeometry rings;
  long rays = 0, triangles = 0, unresolved = 0, uncovered = 0;  ///< the mesh's (spectra/disk_mesh.hpp)
};

}  // namespace grtrace
