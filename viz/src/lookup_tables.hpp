// Colour maps for the scalar fields (private to grtrace_viz).
#pragma once

#include "grtrace/viz/geodesic_data.hpp"

#include <vtkLookupTable.h>
#include <vtkSmartPointer.h>

class vtkDataArray;

namespace grtrace::viz {

/// A lookup table for `field` over the finite values of `values`: viridis-like for continuous fields
/// (log scale for the step size when it spans more than a decade), named categories for the status,
/// a blue-white-red map centred on 1 for the redshift. NaN maps to grey.
vtkSmartPointer<vtkLookupTable> make_lookup_table(ScalarField field, vtkDataArray* values);

}  // namespace grtrace::viz
