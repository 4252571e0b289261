// The application library's insides (private to grtrace_app): how a checked request becomes a concrete tracer.
//
// Each named metric's tracers are compiled in one unit (make_frame_renderer<M> and make_ray_tracer<M>, explicitly
// instantiated there), so that the units compile in parallel and no other unit sees their templates:
//   frame_tracers_schwarzschild.cpp  SchwarzschildMetric (auto/planar, general), MinkowskiSpherical (straight lines)
//   frame_tracers_kerr.cpp           KerrMetric, Boyer-Lindquist (auto/kerr-mino, general)
//   frame_tracers_kerr_schild.cpp    KerrSchildMetric (general)
//   frame_tracers_rn_sds.cpp         AutoReissnerNordstrom, AutoSchwarzschildDeSitter (auto/planar, general)
//   frame_tracers_wormhole_ef.cpp    AutoEllisWormhole, AutoEddingtonFinkelstein (general)
//   medium_frames.cpp                emitting media (--scene accretion) in the static spherical metrics
// and the rays of grtrace-view and the Python module in ray_tracers.cpp (all of them, a unit of their own).
// A metric added to the named metrics (metric/named_metrics.hpp) is named in one of these units: the front door
// (front_door.cpp) reaches it through with_named_metric, and a metric no unit instantiates is a link error.
#pragma once

#include "grtrace/app/front_door.hpp"
#include "grtrace/metric/metric_concept.hpp"
#include "grtrace/render/frame.hpp"
#include "grtrace/trace/tracer_report.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace grtrace {
struct SourceScale;
struct RiafParameters;
struct KerrMetric;
template <MetricPolicy Metric>
class PolishDoughnut;
}  // namespace grtrace

namespace grtrace {
class KerrDiskRays;  // spectra/kerr_disk_map.hpp
struct DiskLight;    // spectra/disk_mesh.hpp
struct ThinDisk;     // scene/thin_disk.hpp
}  // namespace grtrace

namespace grtrace::app {

/// f(), a std::invalid_argument it throws (a library refusal) as a RequestError with `prefix` before its message.
template <class F>
decltype(auto) refusal_as_request_error(const std::string& prefix, F&& f) {
  try {
    return f();
  } catch (const RequestError&) {
    throw;
  } catch (const std::invalid_argument& e) {
    throw RequestError(prefix + e.what());
  }
}

/// Refuses a method the tools do not offer, tolerances outside (0, 1) and [0, 1), a negative step, a fixed step
/// without a step; `prefix` names a second integration's options (grtrace-view's "orbit-"). The step budget is
/// check_request's.
void check_method(const MethodRequest& m, const std::string& prefix = "");

/// Refuses (RequestError) a camera polar angle outside [0, 180] degrees or a field of view outside (0, 180), quoting
/// the values as given (an option's text, or a request's number): read_camera and check_request share the words.
void check_camera_angles(const CameraRequest& camera, const std::string& theta_text, const std::string& fov_text);

/// Whether the planar table tracer draws the named metric (front_door.cpp): static, spherically symmetric, with a
/// horizon.
bool planar_tracer_metric(const MetricSpec& metric);

/// The frame renderer of a checked request in metric M (defined in frame_tracers_impl.hpp, instantiated per unit).
template <MetricPolicy M>
std::unique_ptr<FrameRenderer> make_frame_renderer(const CheckedRequest& checked, const M& metric);

/// The scale and the flow of --scene riaf (the source's presets, the request's accretion rate; medium/riaf.hpp).
SourceScale source_scale(const RenderRequest& q);
RiafParameters riaf_parameters(const RenderRequest& q);
/// The torus of --scene torus (std::invalid_argument where none exists for its radii).
PolishDoughnut<KerrMetric> polish_doughnut(const RenderRequest& q);

/// The frame renderer of an emitting medium's scene (is_medium_scene; medium_frames.cpp, the default method only).
std::unique_ptr<FrameRenderer> make_medium_renderer(const CheckedRequest& checked);

/// A disk drawn by its light (RenderRequest::disk_light; draws_light): its rays' crossings in closed form, of the
/// checked disk (std::invalid_argument where the disk reaches the photon orbit or the sky sphere); its light
/// (emissivity, redshift power, transparency); its frame renderer (medium_frames.cpp).
KerrDiskRays disk_light_rays(const RenderRequest& q, const ThinDisk& disk, double sky_radius);
DiskLight disk_light_of(const RenderRequest& q);
std::unique_ptr<FrameRenderer> make_disk_light_renderer(const CheckedRequest& checked);

/// The ray tracer of a checked request in metric M (defined in ray_tracers.cpp).
template <MetricPolicy M>
std::unique_ptr<RayTracer> make_ray_tracer(const CheckedRequest& checked, const M& metric);

/// What the concrete tracer tells about a frame it drew (the rest of the report comes from the frame's statistics).
struct FrameFacts {
  TracerReport tracer;  ///< name, table statistics, fallback rays of this frame
  std::optional<ContinuationEstimate> continuation_error;
  std::string mirrors;
  std::string device = "cpu";  ///< cpu or cuda
  std::optional<double> gpu_trace_seconds, gpu_seconds;
  double trace_seconds = 0.0;  ///< the wall time of the frame's tracing and shading
  std::optional<double> flux;  ///< an emitting medium's frame: the intensity summed over the pixels' solid angles
  std::optional<double> flux_jy, microarcseconds_per_pixel;  ///< the same in physical units (riaf)
  std::optional<std::array<double, 4>> flux_by_order;        ///< n = 0, 1, 2, >= 3: a disk's light, a medium's
  std::optional<long> uncovered_rays;                        ///< a disk drawn by its light: pixels not followed
  std::vector<RenderReport::BandFlux> band_fluxes;           ///< a medium at several frequencies: each band's
};

/// The render loop's options of a request and a control (threads, mirrors, progress, cancel).
RenderOptions render_options(const CheckedRequest& checked, const RenderControl& control);

/// The result of a frame a concrete tracer drew: the typed report, the error channel (error_map), the header's
/// record (describe_request, the report). Compiled once (front_door.cpp), not once per tracer.
RenderResult finish_render(const CheckedRequest& checked, Frame&& frame, const FrameFacts& facts, double setup_seconds,
                           const std::vector<SkyDirection>& directions);

}  // namespace grtrace::app
