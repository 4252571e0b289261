// Reissner-Nordstrom and Schwarzschild-de Sitter frames, automatic Christoffels (auto: the planar tracer for
// Reissner-Nordstrom; general): see frame_tracers.hpp.
#include "frame_tracers_impl.hpp"

namespace grtrace::app {

template std::unique_ptr<FrameRenderer> make_frame_renderer(const CheckedRequest&, const AutoReissnerNordstrom&);
template std::unique_ptr<FrameRenderer> make_frame_renderer(const CheckedRequest&, const AutoSchwarzschildDeSitter&);

}  // namespace grtrace::app
