// grtrace/viz/geodesic_data.hpp
// Traced geodesics as VTK data: one polyline per path in the Cartesian embedding of the chart.
//
// Takes:   TracedPaths (traced_path.hpp: dense-output samples, several per accepted step).
// Returns: vtkPolyData with one polyline cell per path (paths with fewer than two samples give a vertex cell),
//          points = the samples' embedding positions, and arrays
//            point data  "lambda"       affine parameter (double)
//                        "h"            size of the accepted step the point lies on (double)
//                        "step"         accepted-step index (int)
//                        "status"       how the path ended, RayStatus as a number (int)
//                        "redshift"     f_obs / f_static(x) (double), only when some path recorded it
//                        "pixel_color"  the path's pixel colour (3 x uint8), only when some path has one
//                                       (paths without a colour get mid grey)
//            cell data   "ray"          index of the path in the input (int)
//                        "status"       RayStatus as a number (int)
//          Empty paths are skipped (no cell), so "ray" maps cells back to inputs. add_light_array adds a medium's
//          light collected along each path ("light", float).
#pragma once

#include "grtrace/viz/traced_path.hpp"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace grtrace::viz {

/// What colours a geodesic layer. The names are the tool's --color-by values.
enum class ScalarField { none, pixel_color, redshift, step_size, lambda, status };

/// "none", "pixel", "redshift", "h", "lambda", "status".
std::string_view to_string(ScalarField f);
std::optional<ScalarField> scalar_field_from_string(std::string_view name);
/// Name of the point-data array holding the field ("" for none).
std::string_view array_name(ScalarField f);
/// Human title for a colour bar ("step size h", ...).
std::string_view scalar_title(ScalarField f);

vtkSmartPointer<vtkPolyData> paths_to_polydata(std::span<const TracedPath> paths);

/// Adds the point array "light" (float) to polydata made from `paths` (paths_to_polydata's or an export's: every
/// path's samples as points, in order): at each point the light the path collected from a medium between the camera
/// and it over the path's whole, 0 to 1, from light[i] (app::medium_light_along's, one value per sample of paths[i]);
/// 0 along a path without an entry or without light. Throws std::invalid_argument when the points are not the
/// paths' samples.
void add_light_array(vtkPolyData* data, std::span<const TracedPath> paths, std::span<const std::vector<double>> light);

}  // namespace grtrace::viz
