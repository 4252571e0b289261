// grtrace-render: Kerr frames in Boyer-Lindquist or Kerr-Schild coordinates (see render_request.hpp).
#include "render_request.hpp"

namespace grtrace::render_tool {

std::optional<Frame> render_kerr(const Request& q, SkyDirections* directions) {
  return render_one_of<KerrMetric, KerrSchildMetric>(q, directions);
}

}  // namespace grtrace::render_tool
