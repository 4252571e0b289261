// Colour maps for the scalar fields (see lookup_tables.hpp).
#include "lookup_tables.hpp"

#include "grtrace/core/ray_status.hpp"

#include <vtkColorTransferFunction.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkVariant.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace grtrace::viz {

namespace {

struct Stop {
  double t, r, g, b;
};

// Samples of matplotlib's viridis.
constexpr std::array<Stop, 6> kViridis = {{{0.0, 0.267, 0.005, 0.329},
                                           {0.2, 0.254, 0.265, 0.530},
                                           {0.4, 0.164, 0.471, 0.558},
                                           {0.6, 0.134, 0.659, 0.518},
                                           {0.8, 0.478, 0.821, 0.318},
                                           {1.0, 0.993, 0.906, 0.144}}};

void fill(vtkLookupTable* lut, const Stop* stops, std::size_t n) {
  vtkNew<vtkColorTransferFunction> ctf;
  for (std::size_t i = 0; i < n; ++i) ctf->AddRGBPoint(stops[i].t, stops[i].r, stops[i].g, stops[i].b);
  const int count = 256;
  lut->SetNumberOfTableValues(count);
  for (int i = 0; i < count; ++i) {
    double rgb[3];
    ctf->GetColor(static_cast<double>(i) / (count - 1), rgb);
    lut->SetTableValue(i, rgb[0], rgb[1], rgb[2], 1.0);
  }
}

}  // namespace

vtkSmartPointer<vtkLookupTable> make_lookup_table(ScalarField field, vtkDataArray* values) {
  auto lut = vtkSmartPointer<vtkLookupTable>::New();
  lut->SetNanColor(0.5, 0.5, 0.5, 1.0);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i) {
    const double v = values->GetComponent(i, 0);
    if (!std::isfinite(v)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (!(lo <= hi)) lo = hi = 0.0;

  if (field == ScalarField::status) {
    constexpr std::array<std::array<double, 3>, kRayStatusCount> colors = {{{0.35, 0.65, 1.0},   // escaped
                                                                            {0.9, 0.25, 0.2},    // captured
                                                                            {1.0, 0.75, 0.2},    // hit
                                                                            {0.8, 0.4, 0.9},     // max_steps
                                                                            {0.6, 0.6, 0.6},     // step_underflow
                                                                            {1.0, 1.0, 1.0}}};   // non_finite
    lut->SetNumberOfTableValues(static_cast<vtkIdType>(kRayStatusCount));
    lut->IndexedLookupOn();
    for (std::size_t i = 0; i < kRayStatusCount; ++i) {
      const auto idx = static_cast<vtkIdType>(i);
      lut->SetTableValue(idx, colors[i][0], colors[i][1], colors[i][2], 1.0);
      lut->SetAnnotation(vtkVariant(static_cast<int>(i)), std::string(kRayStatusNames[i]).c_str());
    }
    lut->SetRange(0.0, static_cast<double>(kRayStatusCount - 1));
    return lut;
  }

  if (field == ScalarField::redshift) {
    // Symmetric in log(f) around 1: blue = blueshift (f > 1), red = redshift (f < 1).
    const double span = std::max({std::abs(std::log(std::max(lo, 1e-12))), std::abs(std::log(std::max(hi, 1e-12))), 1e-3});
    const std::array<Stop, 3> stops = {{{0.0, 0.75, 0.15, 0.1}, {0.5, 0.95, 0.95, 0.95}, {1.0, 0.15, 0.35, 0.85}}};
    fill(lut, stops.data(), stops.size());
    lut->SetScaleToLog10();
    lut->SetRange(std::exp(-span), std::exp(span));
    return lut;
  }

  fill(lut, kViridis.data(), kViridis.size());
  if (hi <= lo) hi = lo + 1.0;
  if (field == ScalarField::step_size && lo > 0.0 && hi / lo > 10.0) lut->SetScaleToLog10();
  lut->SetRange(lo, hi);
  return lut;
}

}  // namespace grtrace::viz
