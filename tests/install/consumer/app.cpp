// A user's program on the installed application library (find_package(grtrace COMPONENTS app)): the tools' front
// door, with every tracer of the declared method list compiled already. Exit code 0 when every check holds.
#include <grtrace/app/front_door.hpp>

#include <cstdio>
#include <string>

int main() {
  using namespace grtrace;
  app::RenderRequest q;         // the seed's main camera (r = 200 M), narrowed to the shadow
  q.camera.fov_degrees = 10.0;  // the shadow (angular radius 3 sqrt(3) M / r, 1.5 degrees) fills the middle
  q.camera.width = 16;
  q.camera.height = 12;
  q.threads = 1;
  const app::RenderResult r = app::render(q);
  long pixels = 0;
  for (long n : r.report.stats.status_counts) pixels += n;
  std::printf("app consumer: %s tracer, %ld pixels, %ld escaped, %ld captured\n", r.report.tracer.c_str(), pixels,
              r.report.stats.count(RayStatus::escaped), r.report.stats.count(RayStatus::captured));
  int failures = 0;
  if (pixels != 16 * 12) ++failures;
  if (r.report.tracer != "planar") ++failures;  // auto's choice around a static spherical hole
  if (r.report.stats.count(RayStatus::escaped) == 0 || r.report.stats.count(RayStatus::captured) == 0) ++failures;
  q.camera.r = 1.0;  // inside the horizon: refused before any work, saying what to change
  try {
    (void)app::check_request(q);
    ++failures;
  } catch (const app::RequestError& e) {
    if (std::string(e.what()).find("--camera-r 1 is at or inside the horizon") == std::string::npos) ++failures;
  }
  if (failures) std::printf("app consumer: %d checks failed\n", failures);
  return failures == 0 ? 0 : 1;
}
