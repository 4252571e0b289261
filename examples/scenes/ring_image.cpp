// examples/scenes/ring_image.cpp
// The photon ring of a thin disk around a Kerr hole, order by order (spectra/ring_image.hpp): the direct image
// n = 0 and the rings n = 1, 2, >= 3, each integrated across its width however thin and taken into the pixels with
// its flux kept; the rings' diameters and widths, each ring e^-gamma as wide as the one before. Writes the EXR
// (channels I, I_n0 .. I_n3_up), its PNG preview (the total) and NAME-orders.png (each order on its own scale).
//   ring_image [--out ring.exr] [--size 512] [--spin 0.9] [--inclination 17] [--r-in 0 (the ISCO)] [--r-out 1000]
//              [--index 3] [--power 3] [--field 8] [--transparent 1]
#include "grtrace/spectra/ring_image.hpp"

#include "example_cli.hpp"
#include "grtrace/exact/kerr_exact.hpp"
#include "grtrace/spectra/ring_image_output.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

int main(int argc, char** argv) {
  using namespace grtrace;
  return run_example("ring_image", [&] {
    ExampleArgs defaults;
    defaults.out = "ring.exr";
    defaults.numbers = {{"spin", 0.9},  {"inclination", 17.0}, {"r-in", 0.0},  {"r-out", 1000.0},
                        {"index", 3.0}, {"power", 3.0},        {"field", 8.0}, {"transparent", 1.0}};
    defaults.more_pictures = {"-orders"};
    const ExampleArgs a = parse_example_args(argc, argv, defaults);
    const double spin = a.numbers.at("spin"), inclination = a.numbers.at("inclination");
    if (!(std::abs(spin) < 1.0)) throw std::invalid_argument("--spin must lie in (-1, 1)");
    if (!(inclination > 0.01 && inclination < 179.99))
      throw std::invalid_argument("--inclination must lie in (0.01, 179.99) degrees");
    const double r_in =
        a.numbers.at("r-in") > 0.0 ? a.numbers.at("r-in") : exact::isco_radius(spin, exact::Orbit::prograde);
    RingImageSpec spec;
    spec.width = spec.height = a.size;
    spec.half_width = a.numbers.at("field");
    spec.emissivity.index_inner = spec.emissivity.index_outer = a.numbers.at("index");
    spec.redshift_power = a.numbers.at("power");
    spec.transparent = a.numbers.at("transparent") != 0.0;
    check_ring_image(spec, RingImageSampling{});
    KerrMetric metric;
    metric.spin = spin;
    const KerrDiskMap map(metric, 1e7, inclination * std::numbers::pi / 180.0, r_in, a.numbers.at("r-out"));

    const auto start = std::chrono::steady_clock::now();
    const RingImage ring = ring_image(map, spec);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    write_example_image(a, ring_image_channels(ring), {ring_orders_picture(ring)});
    const RingGeometry& g = ring.rings;
    std::printf(
        "{\"seconds\": %.3f, \"rays\": %ld, \"flux\": [%.6g, %.6g, %.6g, %.6g], \"ring_diameter\": [%.6g, %.6g, "
        "%.6g], \"ring_width\": [%.6g, %.6g, %.6g], \"out\": \"%s\"}\n",
        seconds, ring.rays, ring.flux[0], ring.flux[1], ring.flux[2], ring.flux[3], g.diameter[1], g.diameter[2],
        g.diameter[3], g.width[1], g.width[2], g.width[3], a.out.c_str());
  });
}
