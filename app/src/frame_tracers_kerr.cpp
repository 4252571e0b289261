// Kerr frames in Boyer-Lindquist coordinates (auto: kerr-mino; general): see frame_tracers.hpp.
#include "frame_tracers_impl.hpp"

namespace grtrace::app {

template std::unique_ptr<FrameRenderer> make_frame_renderer(const CheckedRequest&, const KerrMetric&);

}  // namespace grtrace::app
