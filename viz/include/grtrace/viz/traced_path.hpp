// grtrace/viz/traced_path.hpp
// The viz frontend's names for the core's traced paths (grtrace/trace/traced_path.hpp): what it draws of a
// geodesic. VTK-free.
#pragma once

#include "grtrace/trace/traced_path.hpp"

#include <limits>

namespace grtrace::viz {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using Rgb8 = PathRgb8;  ///< an 8-bit sRGB colour (the frame's preview colour of a pixel)
using grtrace::PathRecorder;
using grtrace::PathSample;
using grtrace::StepRecord;
using grtrace::trace_path;
using grtrace::TracedPath;

}  // namespace grtrace::viz
