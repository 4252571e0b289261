// grtrace-render: Ellis wormhole and Eddington-Finkelstein Schwarzschild frames (automatic Christoffel symbols) (see render_request.hpp).
#include "render_request.hpp"

namespace grtrace::render_tool {

std::optional<Frame> render_wormhole_ef(const Request& q, SkyDirections* directions) {
  return render_one_of<AutoEllisWormhole, AutoEddingtonFinkelstein>(q, directions);
}

}  // namespace grtrace::render_tool
