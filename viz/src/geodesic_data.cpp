// Traced geodesics -> vtkPolyData (see grtrace/viz/geodesic_data.hpp).
#include "grtrace/viz/geodesic_data.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <stdexcept>

namespace grtrace::viz {

std::string_view to_string(ScalarField f) {
  switch (f) {
    case ScalarField::none: return "none";
    case ScalarField::pixel_color: return "pixel";
    case ScalarField::redshift: return "redshift";
    case ScalarField::step_size: return "h";
    case ScalarField::lambda: return "lambda";
    case ScalarField::status: return "status";
  }
  return "none";
}

std::optional<ScalarField> scalar_field_from_string(std::string_view name) {
  for (ScalarField f : {ScalarField::none, ScalarField::pixel_color, ScalarField::redshift, ScalarField::step_size,
                        ScalarField::lambda, ScalarField::status})
    if (to_string(f) == name) return f;
  return std::nullopt;
}

std::string_view array_name(ScalarField f) {
  switch (f) {
    case ScalarField::none: return "";
    case ScalarField::pixel_color: return "pixel_color";
    case ScalarField::redshift: return "redshift";
    case ScalarField::step_size: return "h";
    case ScalarField::lambda: return "lambda";
    case ScalarField::status: return "status";
  }
  return "";
}

std::string_view scalar_title(ScalarField f) {
  switch (f) {
    case ScalarField::none: return "";
    case ScalarField::pixel_color: return "pixel colour";
    case ScalarField::redshift: return "redshift f_obs/f_static";
    case ScalarField::step_size: return "step size h";
    case ScalarField::lambda: return "affine parameter";
    case ScalarField::status: return "status";
  }
  return "";
}

vtkSmartPointer<vtkPolyData> paths_to_polydata(std::span<const TracedPath> paths) {
  bool any_redshift = false, any_color = false;
  vtkIdType total = 0;
  for (const auto& p : paths) {
    any_color = any_color || p.color.has_value();
    for (const auto& s : p.samples) any_redshift = any_redshift || std::isfinite(s.redshift);
    total += static_cast<vtkIdType>(p.samples.size());
  }

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->Allocate(total);
  auto make_double = [&](const char* name) {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->Allocate(total);
    return vtkSmartPointer<vtkDoubleArray>(a.Get());
  };
  auto make_int = [&](const char* name, vtkIdType n) {
    vtkNew<vtkIntArray> a;
    a->SetName(name);
    a->Allocate(n);
    return vtkSmartPointer<vtkIntArray>(a.Get());
  };
  const auto lambda = make_double("lambda");
  const auto h = make_double("h");
  const auto redshift = make_double("redshift");
  const auto step = make_int("step", total);
  const auto status = make_int("status", total);
  vtkNew<vtkUnsignedCharArray> color;
  color->SetName("pixel_color");
  color->SetNumberOfComponents(3);
  color->Allocate(3 * total);

  const auto cell_ray = make_int("ray", static_cast<vtkIdType>(paths.size()));
  const auto cell_status = make_int("status", static_cast<vtkIdType>(paths.size()));
  vtkNew<vtkCellArray> lines, verts;

  int ray_index = 0;
  for (const auto& p : paths) {
    const int index = ray_index++;
    if (p.samples.empty()) continue;
    const Rgb8 c = p.color.value_or(Rgb8{128, 128, 128});
    const int st = static_cast<int>(p.status);
    vtkNew<vtkIdList> ids;
    for (const auto& s : p.samples) {
      ids->InsertNextId(points->InsertNextPoint(s.position[0], s.position[1], s.position[2]));
      lambda->InsertNextValue(s.lambda);
      h->InsertNextValue(s.h);
      redshift->InsertNextValue(s.redshift);
      step->InsertNextValue(s.step);
      status->InsertNextValue(st);
      color->InsertNextTypedTuple(c.data());
    }
    (p.samples.size() >= 2 ? lines : verts)->InsertNextCell(ids);
    cell_ray->InsertNextValue(index);
    cell_status->InsertNextValue(st);
  }

  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  // Cells are numbered verts first, then lines: keep the cell arrays in that order.
  if (verts->GetNumberOfCells() > 0 && lines->GetNumberOfCells() > 0) {
    vtkNew<vtkIntArray> ray_sorted, status_sorted;
    ray_sorted->SetName("ray");
    status_sorted->SetName("status");
    for (int pass = 0; pass < 2; ++pass) {
      vtkIdType cell = 0;
      for (const auto& p : paths) {
        if (p.samples.empty()) continue;
        const bool is_vert = p.samples.size() < 2;
        if (is_vert == (pass == 0)) {
          ray_sorted->InsertNextValue(cell_ray->GetValue(cell));
          status_sorted->InsertNextValue(cell_status->GetValue(cell));
        }
        ++cell;
      }
    }
    cell_ray->DeepCopy(ray_sorted);
    cell_status->DeepCopy(status_sorted);
  }
  poly->SetVerts(verts);
  poly->SetLines(lines);
  vtkPointData* pd = poly->GetPointData();
  pd->AddArray(lambda);
  pd->AddArray(h);
  pd->AddArray(step);
  pd->AddArray(status);
  if (any_redshift) pd->AddArray(redshift);
  if (any_color) pd->AddArray(color);
  poly->GetCellData()->AddArray(cell_ray);
  poly->GetCellData()->AddArray(cell_status);
  return poly;
}

void add_light_array(vtkPolyData* data, std::span<const TracedPath> paths, std::span<const std::vector<double>> light) {
  std::size_t samples = 0;
  for (const TracedPath& p : paths) samples += p.samples.size();
  if (data == nullptr || static_cast<std::size_t>(data->GetNumberOfPoints()) != samples)
    throw std::invalid_argument("add_light_array: the polydata's points must be the paths' samples");
  vtkNew<vtkFloatArray> out;
  out->SetName("light");
  out->SetNumberOfTuples(static_cast<vtkIdType>(samples));
  vtkIdType at = 0;
  for (std::size_t r = 0; r < paths.size(); ++r) {
    const std::vector<double>* l = r < light.size() ? &light[r] : nullptr;
    const double whole = l && !l->empty() ? l->back() : 0.0;
    for (std::size_t i = 0; i < paths[r].samples.size(); ++i)
      out->SetValue(at++, l && i < l->size() && whole > 0.0 ? static_cast<float>((*l)[i] / whole) : 0.0f);
  }
  data->GetPointData()->AddArray(out);
}

}  // namespace grtrace::viz
