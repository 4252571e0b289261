// grtrace/observer/camera.hpp
// A pinhole camera: an event, a tetrad, a size in pixels and a horizontal field of view.
// Pixel (col, row) -> past-directed null momentum with unit energy in the camera frame, exactly seed eq. (5)-(6):
//   r = tan(F/2) (2 col / (W - 1) - 1),  u = tan(F/2) (2 y / (H - 1) - 1) H / W,  y = H - 1 - row,
//   k = (e_1 + u e_2 + r e_3) / sqrt(1 + u^2 + r^2) - e_0.
// Row 0 is the top of the picture and column 0 the left. g(e_0, k) = -1: unit energy, past-directed, so the
// tracer follows the light back to where it came from.
#pragma once

#include "grtrace/core/host_device.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/observer/tetrad.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace grtrace {

class Camera {
 public:
  /// Refuses sizes below 1 and a field of view outside (0, 180) degrees.
  Camera(const Vec4& position, const Tetrad& tetrad, int width, int height, double fov_degrees)
      : position_(position), tetrad_(tetrad), width_(width), height_(height), fov_degrees_(fov_degrees) {
    if (width < 1 || height < 1)
      throw std::invalid_argument("camera: width and height must be at least 1 pixel, got " + std::to_string(width) +
                                  "x" + std::to_string(height));
    if (!(fov_degrees > 0.0 && fov_degrees < 180.0))
      throw std::invalid_argument("camera: --fov must lie strictly between 0 and 180 degrees");
    tan_half_ = std::tan(fov_degrees * std::numbers::pi / 360.0);
  }

  /// Direction of the pixel in the camera frame: (forward, up, right) components of the unit 3-vector the
  /// light arrives against (the way the camera looks), seed eq. (6).
  GRTRACE_HD Vec3 pixel_direction(double col, double row) const {
    const double y = (height_ - 1) - row;
    const double r = width_ > 1 ? tan_half_ * (2.0 * col / (width_ - 1) - 1.0) : 0.0;
    const double u =
        height_ > 1 ? tan_half_ * (2.0 * y / (height_ - 1) - 1.0) * static_cast<double>(height_) / width_ : 0.0;
    // Each component divided on its own (the same divisions as Vec3(1, u, r) / n): a Vec3 built in memory and then
    // divided as a packed pair reads 16 bytes just stored as two 8-byte halves, a store-forwarding stall that perf put
    // at a quarter of grtrace-render's pixel loop.
    const double n = std::sqrt(1.0 + u * u + r * r);
    return Vec3(1.0 / n, u / n, r / n);
  }

  /// Initial null momentum for the pixel (seed eq. 5).
  GRTRACE_HD Vec4 pixel_momentum(double col, double row) const {
    const Vec3 d = pixel_direction(col, row);
    return d[0] * tetrad_.e[1] + d[1] * tetrad_.e[2] + d[2] * tetrad_.e[3] - tetrad_.e[0];
  }

  GRTRACE_HD GeodesicState pixel_state(double col, double row) const {
    return make_state(position_, pixel_momentum(col, row));
  }

  GRTRACE_HD const Vec4& position() const { return position_; }
  GRTRACE_HD const Tetrad& tetrad() const { return tetrad_; }
  GRTRACE_HD int width() const { return width_; }
  GRTRACE_HD int height() const { return height_; }
  GRTRACE_HD double tan_half_fov() const { return tan_half_; }
  GRTRACE_HD double fov_degrees() const { return fov_degrees_; }

 private:
  Vec4 position_;
  Tetrad tetrad_;
  int width_, height_;
  double fov_degrees_;
  double tan_half_ = 1.0;
};

}  // namespace grtrace
