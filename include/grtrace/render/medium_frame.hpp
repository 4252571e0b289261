// grtrace/render/medium_frame.hpp
// A camera's frame of an emitting medium (trace/medium_tracers.hpp), drawn through the parallel image loop: the
// channels a user analyses and a picture to look at.
//
// Takes:   a camera, a medium tracer (GeneralMediumTracer, SphericalMediumTracer, or any type with
//          `MediumSample trace(const GeodesicState&) const`, called from several threads at once), render options.
// Returns: a Frame whose image holds
//            intensity       I_nu at nu_obs (the medium's units times a length: geometric, per the tracer's frequency)
//            optical_depth   tau along the ray
//            redshift        the emission-weighted g = nu_obs / nu_fluid of the light (NaN where there is none)
//            intensity_n0, _n1, _n2, _n3_up   by image order (trace/emission_system.hpp), where the tracer splits
//                            it (splits_by_order: the general tracer); `intensity` is then their sum, the same
//                            float additions
//            status, steps   as every frame's (object: 0 escaped, 1 captured; sky direction NaN), and order (the
//                            ray's crossings of the equatorial plane, where the tracer counts them)
//            R, G, B         the intensity over the frame's brightest pixel, raised to `exponent` (1: linear, as
//                            the EHT shows images; 1/2 lifts the faint gas), in a black-red-yellow-white map
//          and in its metadata the peak intensity the picture is scaled to ("intensity_peak").
// render_medium_spectrum: the same for a tracer at several observing frequencies in one pass, a channel of each.
// A failed ray keeps the light it had collected where it failed (finite), its status says so, render_image counts
// it and its pixel keeps the loop's error colour (RenderOptions::error_rgb).
#pragma once

#include "grtrace/observer/camera.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/trace/medium_tracers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace grtrace {

/// The channels of the intensity by image order n = 0, 1, 2 and >= 3, in that order (a medium's and a disk's light).
inline constexpr std::array<const char*, 4> kOrderIntensityChannels = {"intensity_n0", "intensity_n1", "intensity_n2",
                                                                       "intensity_n3_up"};

/// Adds the order channels (kOrderIntensityChannels) to an image; their data, in that order.
inline std::array<float*, kOrderIntensityChannels.size()> add_order_channels(Image& image) {
  std::array<float*, kOrderIntensityChannels.size()> out{};
  for (std::size_t c = 0; c < out.size(); ++c) out[c] = image.add_channel(kOrderIntensityChannels[c]).data();
  return out;
}

/// Writes a pixel's light by order into the order channels and returns their float sum, the same additions in
/// the same order for every frame, so that `intensity` (this sum) equals the order channels added up exactly.
inline float store_by_order(const std::array<float*, kOrderIntensityChannels.size()>& channels, std::size_t i,
                            const std::array<double, kOrderIntensityChannels.size()>& pieces) {
  float sum = 0.0f;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    channels[c][i] = static_cast<float>(pieces[c]);
    sum += channels[c][i];
  }
  return sum;
}

/// Colours R, G, B from the image's "intensity" channel (see the top of this file); records intensity_peak.
inline void shade_intensity(Image& image, double exponent = 1.0) {
  const std::vector<float>& intensity = image.channel("intensity");
  float peak = 0.0f;
  for (const float v : intensity)
    if (std::isfinite(v)) peak = std::max(peak, v);
  const std::vector<float>& status = image.channel("status");
  std::vector<float>&red = image.channel("R"), &green = image.channel("G"), &blue = image.channel("B");
  for (std::size_t i = 0; i < intensity.size(); ++i) {
    if (is_failure(static_cast<RayStatus>(static_cast<int>(status[i])))) continue;  // keeps the error colour
    const double x = peak > 0.0f && std::isfinite(intensity[i]) ? static_cast<double>(intensity[i] / peak) : 0.0;
    // The common exponents without pow (a fifth of its time, over every pixel of a frame).
    const double v = exponent == 1.0 ? x : exponent == 0.5 ? std::sqrt(x) : std::pow(x, exponent);
    const std::array<float, 3> c = hot_gas_colour(v);
    red[i] = c[0];
    green[i] = c[1];
    blue[i] = c[2];
  }
  image.metadata["intensity_peak"] = exact_number(peak);
}

/// The width of a pixel at the centre of the camera's image, in radians: the pinhole's horizontal pitch on the
/// image plane at unit distance, 2 tan(fov / 2) / (width - 1) (one pixel wide: the whole field, 2 tan(fov / 2)).
inline double camera_pixel_pitch(const Camera& camera) {
  return 2.0 * camera.tan_half_fov() / std::max(1, camera.width() - 1);
}

/// The frame's flux in the camera's sky: every pixel's intensity (the channel named, "intensity" unless said) times
/// the solid angle the camera sees it under (a pinhole: the pixel's area on the image plane at unit distance, du dv,
/// over (1 + u^2 + v^2)^(3/2)); NaN for a frame one pixel wide or high (no pitch). In janskys at a telescope:
/// SourceScale::janskys (core/physical_units.hpp).
inline double medium_frame_flux(const Camera& camera, const Image& image, const std::string& channel = "intensity") {
  const int w = camera.width(), h = camera.height();
  if (w < 2 || h < 2) return std::nan("");
  const double t = camera.tan_half_fov();
  const double du = camera_pixel_pitch(camera), dv = 2.0 * t * h / (static_cast<double>(w) * (h - 1));
  const std::vector<float>& intensity = image.channel(channel);
  double flux = 0.0;
  for (int row = 0; row < h; ++row) {
    const double v = t * (2.0 * row / (h - 1) - 1.0) * h / w;
    for (int col = 0; col < w; ++col) {
      const double u = t * (2.0 * col / (w - 1) - 1.0), q = 1.0 + u * u + v * v;
      flux += static_cast<double>(intensity[image.index(col, row)]) * du * dv / (q * std::sqrt(q));
    }
  }
  return flux;
}

/// The flux of each order channel (kOrderIntensityChannels) in the camera's sky: medium_frame_flux of each.
inline std::array<double, 4> flux_by_order(const Camera& camera, const Image& image) {
  std::array<double, 4> flux{};
  for (std::size_t c = 0; c < flux.size(); ++c) flux[c] = medium_frame_flux(camera, image, kOrderIntensityChannels[c]);
  return flux;
}

template <class Tracer>
Frame render_medium_frame(const Camera& camera, const Tracer& tracer, const RenderOptions& options = {},
                          double exponent = 1.0) {
  Frame frame{Image(camera.width(), camera.height()), {}};
  float* const intensity = frame.image.add_channel("intensity").data();
  float* const depth = frame.image.add_channel("optical_depth").data();
  constexpr bool by_order = splits_by_order<Tracer>();
  std::array<float*, kOrderIntensityChannels.size()> order_light{};
  if constexpr (by_order) order_light = add_order_channels(frame.image);
  const Image& image = frame.image;
  frame.stats = render_image(
      frame.image,
      [&](int x, int y) {
        const MediumSample m = tracer.trace(camera.pixel_state(x, y));
        const std::size_t i = image.index(x, y);
        if constexpr (by_order) intensity[i] = store_by_order(order_light, i, m.intensity_by_order);
        else intensity[i] = static_cast<float>(m.intensity);
        depth[i] = static_cast<float>(m.optical_depth);
        PixelSample s;
        s.status = m.status;
        s.object = m.status == RayStatus::captured ? 1 : 0;
        s.steps = m.steps;
        s.order = m.order;
        s.redshift = static_cast<float>(m.redshift);
        return s;
      },
      options);
  shade_intensity(frame.image, exponent);
  return frame;
}

/// A frame of a tracer at several observing frequencies (RayMediumTracer with Bands > 1, SpectralMediumSample),
/// each pixel's ray traced once: for the first names.size() bands b the channels intensity_<names[b]> and
/// optical_depth_<names[b]> (names such as "230GHz"; a tracer may carry more bands than are kept); "intensity",
/// "redshift" and R, G, B (as render_medium_frame's) of band `shown`.
template <class Tracer>
Frame render_medium_spectrum(const Camera& camera, const Tracer& tracer, const std::vector<std::string>& names,
                             std::size_t shown, const RenderOptions& options = {}, double exponent = 1.0) {
  constexpr std::size_t Bands = std::tuple_size_v<typename Tracer::Frequencies>;
  if (names.empty() || names.size() > Bands || shown >= names.size())
    throw std::invalid_argument("render_medium_spectrum: name 1 to " + std::to_string(Bands) +
                                " bands, the band shown one of them");
  Frame frame{Image(camera.width(), camera.height()), {}};
  const std::size_t kept = names.size();
  std::array<float*, Bands> intensity{}, depth{};
  for (std::size_t b = 0; b < kept; ++b) {
    intensity[b] = frame.image.add_channel("intensity_" + names[b]).data();
    depth[b] = frame.image.add_channel("optical_depth_" + names[b]).data();
  }
  float* const picture = frame.image.add_channel("intensity").data();
  const Image& image = frame.image;
  frame.stats = render_image(
      frame.image,
      [&](int x, int y) {
        const SpectralMediumSample<Bands> m = tracer.trace(camera.pixel_state(x, y));
        const std::size_t i = image.index(x, y);
        for (std::size_t b = 0; b < kept; ++b) {
          intensity[b][i] = static_cast<float>(m.intensity[b]);
          depth[b][i] = static_cast<float>(m.optical_depth[b]);
        }
        picture[i] = intensity[shown][i];
        PixelSample s;
        s.status = m.status;
        s.object = m.status == RayStatus::captured ? 1 : 0;
        s.steps = m.steps;
        s.order = m.order;
        s.redshift = static_cast<float>(m.redshift[shown]);
        return s;
      },
      options);
  shade_intensity(frame.image, exponent);
  return frame;
}

}  // namespace grtrace
