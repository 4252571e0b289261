// grtrace/app/medium_view.hpp
// What a viewer shows of an emitting medium (a checked request's scene accretion, riaf or torus: the medium the
// frame is drawn from): its emission on a cube of points around the hole, whose iso-surfaces grtrace-view draws
// beside the frame, and the light a traced ray collects along its path, by which it colours a picked ray.
//
// Takes:   a checked request of a medium's scene (check_request); a ray's path as RayTracer traces a camera pixel
//          (from the camera backwards, its samples' chart state and affine parameter) and the camera's 4-velocity.
// Returns: medium_volume: j (the emission coefficient at the request's frequency in the fluid's frame, for light
//          leaving radially outwards there: the direction matters only for the RIAF's synchrotron light) on n^3
//          points of a cube centred on the hole in the picture's x, y, z (Boyer-Lindquist r, theta, phi drawn as
//          spherical polar coordinates, as the rays are), 0 inside the horizon and beyond the medium's outer radius.
//          medium_light_along: at each sample, the intensity the camera receives from the part of the path between
//          it and the camera, I = integral of g^3 j e^-tau dl with tau = integral of alpha dl
//          (trace/emission_system.hpp's integrals), by the trapezoid rule over the samples: its last value is the
//          pixel's intensity to the samples' resolution (the torus's to 4.6e-5 at 64 samples a step), the frame's
//          value being the integration's. Only the gas counts: inside its outer radius and, for a medium with a
//          boundary, inside that (its coefficients are continued beyond it for the tracer's steps).
// Assumes: the request's chart is Boyer-Lindquist (check_request refuses the others for media).
#pragma once

#include "grtrace/app/front_door.hpp"
#include "grtrace/core/types.hpp"
#include "grtrace/trace/traced_path.hpp"

#include <string>
#include <vector>

namespace grtrace::app {

/// A medium's emission on a cube of points (see the top of this file).
struct MediumVolume {
  int n = 0;                    ///< points a side
  double half_width = 0.0;      ///< the cube is [-half_width, half_width]^3 (units of M)
  std::vector<float> emission;  ///< j at point (i, j, k) at index i + n (j + n k): x fastest, z slowest
  double peak = 0.0;            ///< the largest value
  std::string kind;             ///< the medium's kind ("polish-doughnut", "riaf", "spherical-accretion")
  double spacing() const { return n > 1 ? 2.0 * half_width / (n - 1) : 0.0; }
};

/// The request's medium sampled on n^3 points (2 <= n <= 256) of the cube of half width `half_width` (<= 0: the
/// medium's outer radius, at most 40 M, and at least 4 horizon radii). Throws RequestError for a request that is
/// not a medium's scene or an n outside that range.
MediumVolume medium_volume(const CheckedRequest& checked, int n, double half_width = 0.0);

/// The intensity collected from the camera to each sample of `path` (see the top of this file); a path without
/// samples gives none. Throws RequestError for a request that is not a medium's scene.
std::vector<double> medium_light_along(const CheckedRequest& checked, const TracedPath& path,
                                       const Vec4& camera_velocity);

}  // namespace grtrace::app
