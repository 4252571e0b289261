// grtrace-render: Reissner-Nordstrom and Schwarzschild-de Sitter frames (automatic Christoffel symbols) (see render_request.hpp).
#include "render_request.hpp"

namespace grtrace::render_tool {

std::optional<Frame> render_rn_sds(const Request& q, SkyDirections* directions, TracerReport& table) {
  return render_one_of<AutoReissnerNordstrom, AutoSchwarzschildDeSitter>(q, directions, &table);
}

}  // namespace grtrace::render_tool
