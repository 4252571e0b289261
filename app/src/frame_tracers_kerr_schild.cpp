// Kerr frames in Cartesian Kerr-Schild coordinates (general): see frame_tracers.hpp.
#include "frame_tracers_impl.hpp"

namespace grtrace::app {

template std::unique_ptr<FrameRenderer> make_frame_renderer(const CheckedRequest&, const KerrSchildMetric&);

}  // namespace grtrace::app
