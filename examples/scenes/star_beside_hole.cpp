// examples/scenes/star_beside_hole.cpp
// A glowing star beside a Schwarzschild black hole. The star is one struct of our own (glowing_star.hpp: its shape,
// how its matter moves, its colour); everything else is the library's. The hole bends the star's light around
// both sides: the direct image, and on the far side of the shadow the thin secondary image.
//   star_beside_hole [--out star.exr] [--size 512]       writes star.exr (all data channels) and star.png
#include "example_cli.hpp"
#include "star_beside_hole.hpp"

#include "grtrace/render/frame.hpp"
#include "grtrace/tableau/tsitouras54.hpp"

int main(int argc, char** argv) {
  using namespace grtrace;
  return run_example("star_beside_hole", [&] {
    const ExampleArgs args = parse_example_args(argc, argv, {"star.exr", 512, {}});
    const auto [camera, tracer] = star_beside_hole_view<Tsitouras54>(args.size);
    write_example_frame(args, render_frame(camera, tracer));
  });
}
