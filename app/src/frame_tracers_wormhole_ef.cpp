// The Ellis wormhole and Schwarzschild in Eddington-Finkelstein coordinates (general): see frame_tracers.hpp.
#include "frame_tracers_impl.hpp"

namespace grtrace::app {

template std::unique_ptr<FrameRenderer> make_frame_renderer(const CheckedRequest&, const AutoEllisWormhole&);
template std::unique_ptr<FrameRenderer> make_frame_renderer(const CheckedRequest&, const AutoEddingtonFinkelstein&);

}  // namespace grtrace::app
