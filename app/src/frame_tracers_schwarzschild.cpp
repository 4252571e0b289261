// Schwarzschild frames (auto: the planar tracer's table; general) and flat space (straight lines): see
// frame_tracers.hpp.
#include "frame_tracers_impl.hpp"

namespace grtrace::app {

template std::unique_ptr<FrameRenderer> make_frame_renderer(const CheckedRequest&, const SchwarzschildMetric&);
template std::unique_ptr<FrameRenderer> make_frame_renderer(const CheckedRequest&, const MinkowskiSpherical&);

}  // namespace grtrace::app
