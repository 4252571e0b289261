// grtrace/scene/sky.hpp
// The celestial sphere: what an escaped ray sees in its asymptotic direction (theta, phi).
// Three kinds: a theta-phi checkerboard (seed Fig. 4), a procedural star field (the default), and an
// equirectangular texture (R, G, B channels of an image: theta down the rows, phi across the columns).
// Shading runs once per pixel, after the integration, so a runtime choice costs nothing in the hot loop.
// AnySky (the command-line tools' sky) may carry a second sky for the far side of a two-sided chart: the other
// universe of a wormhole, where rays end with radial coordinate x^1 < 0 (Ellis: l < 0).
#pragma once

#include "grtrace/core/rounding.hpp"
#include "grtrace/scene/colour_maps.hpp"
#include "grtrace/trace/ray_outcome.hpp"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>
#include <variant>
#include <vector>

namespace grtrace {

struct CheckerSky {
  int squares = 18;  ///< squares along theta (2x along phi)
  Rgb light{1.0f, 0.62f, 0.15f}, dark{0.08f, 0.22f, 0.55f};
  Rgb operator()(double theta, double phi) const { return checker_parity(theta, phi, squares) ? light : dark; }
};

/// Stars on a dark sky with a faint band along the equator; deterministic (a hash of the sky cell). A different
/// cells_theta gives a different pattern; tint multiplies every colour (1, 1, 1: untinted).
struct StarFieldSky {
  int cells_theta = 1024;  ///< star density grid
  Rgb tint{1.0f, 1.0f, 1.0f};
  Rgb operator()(double theta, double phi) const { return tinted(starfield(theta, phi)); }

 private:
  Rgb tinted(const Rgb& c) const { return {c[0] * tint[0], c[1] * tint[1], c[2] * tint[2]}; }
  Rgb starfield(double theta, double phi) const {
    const double band = std::exp(-std::pow((theta - std::numbers::pi / 2) / 0.18, 2));
    Rgb c{static_cast<float>(0.01 + 0.05 * band), static_cast<float>(0.012 + 0.045 * band),
          static_cast<float>(0.03 + 0.06 * band)};
    const double cell = std::numbers::pi / cells_theta;
    const auto i = static_cast<std::uint64_t>(floor_to_long(theta / cell));
    const auto j = static_cast<std::uint64_t>(floor_to_long((phi + std::numbers::pi) / cell));
    std::uint64_t h = (i * 0x9E3779B97F4A7C15ULL) ^ (j * 0xC2B2AE3D27D4EB4FULL);
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ULL;
    h ^= h >> 29;
    const double u = static_cast<double>(h % 100000) / 100000.0;
    // About 1 cell in 60 holds a star, a little denser in the band; brightness from the same hash.
    if (u < 0.016 * (1.0 + 2.0 * band)) {
      const double b = 0.35 + 0.65 * std::pow(static_cast<double>((h >> 20) % 1000) / 1000.0, 3.0);
      const double warm = static_cast<double>((h >> 40) % 100) / 100.0;
      c = {static_cast<float>(b * (0.85 + 0.15 * warm)), static_cast<float>(b * 0.9),
           static_cast<float>(b * (1.0 - 0.2 * warm))};
    }
    return c;
  }
};

/// Equirectangular RGB texture (row 0 = theta 0, column 0 = phi -pi), bilinear, wrapping in phi.
/// The planes are shared, not copied, when the sky is: a scene is copied into every request and tracer that draws it,
/// and a texture can be most of a process's memory (an 8k x 4k texture is 400 MB of floats).
struct TextureSky {
  int width = 0, height = 0;
  std::shared_ptr<const std::vector<float>> r, g, b;  ///< row-major planes, width x height each

  TextureSky() = default;
  /// Takes the planes (moved in: pass std::move of an image's channels to hold the texels once).
  TextureSky(int w, int h, std::vector<float> red, std::vector<float> green, std::vector<float> blue)
      : width(w), height(h), r(std::make_shared<const std::vector<float>>(std::move(red))),
        g(std::make_shared<const std::vector<float>>(std::move(green))),
        b(std::make_shared<const std::vector<float>>(std::move(blue))) {}

  Rgb operator()(double theta, double phi) const {
    const double x = (phi + std::numbers::pi) / (2 * std::numbers::pi) * width - 0.5;
    const double y = std::clamp(theta / std::numbers::pi * height - 0.5, 0.0, height - 1.0);
    const long x0 = floor_to_long(x), y0 = floor_to_long(y);
    const double fx = x - static_cast<double>(x0), fy = y - static_cast<double>(y0);
    auto at = [&](const std::vector<float>& p, long xi, long yi) {
      xi = ((xi % width) + width) % width;
      yi = std::clamp(yi, 0L, static_cast<long>(height) - 1);
      return static_cast<double>(p[static_cast<std::size_t>(yi * width + xi)]);
    };
    auto sample = [&](const std::vector<float>& p) {
      return static_cast<float>((1 - fy) * ((1 - fx) * at(p, x0, y0) + fx * at(p, x0 + 1, y0)) +
                                fy * ((1 - fx) * at(p, x0, y0 + 1) + fx * at(p, x0 + 1, y0 + 1)));
    };
    return {sample(*r), sample(*g), sample(*b)};
  }
};

/// Refuses (std::invalid_argument, naming the texel and the channel) a texture whose planes do not match its size
/// or hold a non-finite value: a NaN texel would make every ray that sees it non_finite.
inline void check_texture(const TextureSky& t) {
  const auto n = static_cast<std::size_t>(t.width) * static_cast<std::size_t>(t.height);
  if (t.width < 1 || t.height < 1 || !t.r || !t.g || !t.b || t.r->size() != n || t.g->size() != n || t.b->size() != n)
    throw std::invalid_argument("sky texture: the R, G, B planes do not match its size");
  const std::array<const std::vector<float>*, 3> planes{t.r.get(), t.g.get(), t.b.get()};
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite((*planes[c])[i]))
        throw std::invalid_argument("sky texture: texel (x " + std::to_string(i % static_cast<std::size_t>(t.width)) +
                                    ", y " + std::to_string(i / static_cast<std::size_t>(t.width)) + ") of channel " +
                                    "RGB"[c] + " is not finite; fix the texture");
}

/// A sky chosen at run time (a command-line flag): one of the three above. Painting runs once per pixel after the
/// integration, so the visit costs nothing that matters.
/// With far_side set, rays that end at x^1 < 0 get that sky instead: the other universe of a chart whose radial
/// coordinate runs through zero (the Ellis wormhole's l). Set it only for such a chart: in a Cartesian chart x^1 is
/// the x coordinate, in an ordinary spherical chart x^1 = r > 0 and far_side is never used.
struct AnySky {
  using Sky = std::variant<CheckerSky, StarFieldSky, TextureSky>;
  Sky sky = StarFieldSky{};
  std::optional<Sky> far_side;  ///< the sky seen by rays ending at x^1 < 0; none: `sky` everywhere

  Rgb operator()(double theta, double phi) const { return paint(sky, theta, phi); }
  /// The scene's choice (scene/scene.hpp OutcomePainter): the side from the end state, the colour at o.where.
  [[gnu::always_inline]] Rgb operator()(const RayOutcome& o) const {  // once per sky pixel (Scene::shade)
    const bool far = far_side && o.state[1] < 0.0;
    return paint(far ? *far_side : sky, o.where.theta, o.where.phi);
  }

 private:
  static Rgb paint(const Sky& s, double theta, double phi) {
    return std::visit([&](const auto& p) { return p(theta, phi); }, s);
  }
};

}  // namespace grtrace
