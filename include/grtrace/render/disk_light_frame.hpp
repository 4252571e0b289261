// grtrace/render/disk_light_frame.hpp
// A camera's frame of a thin disk's light, split by the order of its images: per pixel the ray's crossings of the
// equatorial plane (a disk map of rays: KerrDiskRays, spectra/kerr_disk_map.hpp, in closed form), each crossing
// between the disk's radii seen with intensity g^p eps(r) (DiskLight, spectra/disk_mesh.hpp). An opaque disk
// ends the ray at its first such crossing; a transparent one (AART's model of an optically thin disk) lets every
// crossing emit and the ray go on, so a pixel of the photon ring adds the light of the orders behind it.
//
// Takes:   a camera (any radius and velocity outside the disk's photon orbit; Boyer-Lindquist), the rays' map (a type
//          with `DiskRaySample sample(const GeodesicState&) const`, called from several threads at once), the
//          light, render options, and the picture's exponent (1: linear; 1/2 lifts the faint outer disk).
// Returns: a Frame whose image holds, besides the standard channels,
//            intensity                              the sum over orders, intensity_n0 + n1 + n2 + n3_up exactly
//                                                   (the same float additions)
//            intensity_n0, _n1, _n2, _n3_up         by order: the direct image, the first and second photon rings,
//                                                   and the rest
//            object, status, redshift, order        of the first crossing that emits (the disk, status hit); else
//                                                   the sky (escaped) or the horizon (captured), which are not
//                                                   drawn (order -1, redshift and sky direction NaN)
//            R, G, B                                the intensity in the hot-gas map (render/medium_frame.hpp)
//          and the statistics; the frame's flux per order is flux_by_order
//          (render/medium_frame.hpp).
// Pixels whose ray the map does not follow (DiskRaySample::covered false; KerrDiskRays: vortical rays, which never
// reach the plane, and rays from a camera inside their potential barrier) are dark, counted in the returned
// `uncovered` and marked status max_steps (a failure the loop counts, in the frame's status map), never NaN.
// Sampling: one ray through each pixel's centre, as every frame: an order's ring thinner than a pixel is sampled,
// not integrated (for that, the adaptive ring image of a distant observer: spectra/ring_image.hpp).
#pragma once

#include "grtrace/observer/camera.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/render/medium_frame.hpp"
#include "grtrace/render/parallel_render.hpp"
#include "grtrace/spectra/disk_mesh.hpp"

#include <array>
#include <string>

namespace grtrace {

template <class Rays>
concept DiskRays = requires(const Rays& rays, const GeodesicState& y) {
  { rays.sample(y) } -> std::same_as<DiskRaySample>;
};

struct DiskLightFrame {
  Frame frame;
  long uncovered = 0;  ///< pixels whose ray the map does not follow (dark: the frame's max_steps count)
};

template <DiskRays Rays>
DiskLightFrame render_disk_light_frame(const Camera& camera, const Rays& rays, const DiskLight& light,
                                       const RenderOptions& options = {}, double exponent = 0.5) {
  DiskLightFrame out{Frame{Image(camera.width(), camera.height()), {}}, 0};
  Image& image = out.frame.image;
  float* const total = image.add_channel("intensity").data();
  const std::array<float*, kOrderIntensityChannels.size()> by_order = add_order_channels(image);
  const int orders = std::min(light.orders, DiskRaySample::kOrders);
  out.frame.stats = render_image(
      image,
      [&](int x, int y) {
        const DiskRaySample ray = rays.sample(camera.pixel_state(x, y));
        const std::size_t i = image.index(x, y);
        PixelSample s;
        if (!ray.covered) {  // counted by the loop as max_steps
          s.status = RayStatus::max_steps;
          s.rgb = {0.0f, 0.0f, 0.0f};
          return s;
        }
        std::array<double, kOrderIntensityChannels.size()> light_of{};
        bool lit = false;  // an opaque disk has stopped the ray
        for (int n = 0; n < DiskRaySample::kOrders && !lit; ++n) {
          const auto k = static_cast<std::size_t>(n);
          if (ray.where[k] == DiskRaySample::nothing) break;
          if (ray.where[k] != DiskRaySample::on_disk || n >= orders) continue;
          light_of[disk_mesh::order_channel(k)] += light.intensity(ray.redshift[k], ray.radius[k]);
          if (s.status != RayStatus::hit) {  // the first that emits names the pixel
            s.status = RayStatus::hit;
            s.object = kFirstSceneObject;
            s.order = n;
            s.redshift = static_cast<float>(ray.redshift[k]);
          }
          lit = !light.transparent;
        }
        total[i] = store_by_order(by_order, i, light_of);
        if (s.status != RayStatus::hit) {
          s.status = ray.escaped ? RayStatus::escaped : RayStatus::captured;
          s.object = ray.escaped ? kSkyObject : kHorizonObject;
        }
        return s;
      },
      options);
  shade_intensity(image, exponent);
  out.uncovered = out.frame.stats.count(RayStatus::max_steps);
  image.metadata["disk_transparent"] = light.transparent ? "true" : "false";
  image.metadata["redshift_power"] = exact_number(light.redshift_power);
  image.metadata["uncovered_rays"] = std::to_string(out.uncovered);
  return out;
}

}  // namespace grtrace
