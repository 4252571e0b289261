// Reference surfaces as polydata (see grtrace/viz/surfaces.hpp).
#include "grtrace/viz/surfaces.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDiskSource.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkSphereSource.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace grtrace::viz {

namespace {

constexpr double kPi = std::numbers::pi;

Vec3 spherical(double r, double theta, double phi) {
  return {r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi), r * std::cos(theta)};
}

void require_positive(double v, const char* what) {
  if (!(v > 0.0) || !std::isfinite(v)) throw std::invalid_argument(std::string(what) + " must be positive and finite");
}

}  // namespace

vtkSmartPointer<vtkPolyData> make_sphere(double radius, int resolution) {
  require_positive(radius, "sphere radius");
  vtkNew<vtkSphereSource> s;
  s->SetRadius(radius);
  s->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  s->SetThetaResolution(resolution);
  s->SetPhiResolution(resolution / 2 + 1);
  s->Update();
  return s->GetOutput();
}

vtkSmartPointer<vtkPolyData> make_checkered_sphere(double radius, int n_theta, int n_phi, Rgb8 a, Rgb8 b,
                                                   int cells_per_square) {
  require_positive(radius, "sphere radius");
  if (n_theta < 1 || n_phi < 1 || cells_per_square < 1)
    throw std::invalid_argument("checkerboard: the square counts must be >= 1");
  // A latitude-longitude grid aligned with the checker squares: every cell lies in exactly one square.
  const int nt = n_theta * cells_per_square, np = n_phi * cells_per_square;
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (int i = 0; i <= nt; ++i)
    for (int j = 0; j <= np; ++j) {
      const Vec3 p = spherical(radius, kPi * i / nt, 2.0 * kPi * j / np);
      pts->InsertNextPoint(p[0], p[1], p[2]);
    }
  vtkNew<vtkCellArray> quads;
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("checker_color");
  colors->SetNumberOfComponents(3);
  auto id = [&](int i, int j) { return static_cast<vtkIdType>(i * (np + 1) + j); };
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < np; ++j) {
      const vtkIdType q[4] = {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      quads->InsertNextCell(4, q);
      const bool even = (i / cells_per_square + j / cells_per_square) % 2 == 0;
      colors->InsertNextTypedTuple((even ? a : b).data());
    }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetPolys(quads);
  poly->GetCellData()->SetScalars(colors);
  return poly;
}

vtkSmartPointer<vtkPolyData> make_ergosphere(double mass, double spin, int n_theta, int n_phi) {
  require_positive(mass, "ergosphere: mass");
  if (!std::isfinite(spin) || !(std::abs(spin) < mass))
    throw std::invalid_argument("ergosphere: the spin must satisfy |a| < M");
  if (n_theta < 2 || n_phi < 3) throw std::invalid_argument("ergosphere: need n_theta >= 2 and n_phi >= 3");
  // A latitude-longitude grid (as make_checkered_sphere) whose radius follows the static limit: the poles are single
  // rows of coincident points, so the quads there degenerate into triangles, which VTK draws as such.
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (int i = 0; i <= n_theta; ++i) {
    const double theta = kPi * i / n_theta, c = std::cos(theta);
    const double r = mass + std::sqrt(mass * mass - spin * spin * c * c);
    for (int j = 0; j <= n_phi; ++j) {
      const Vec3 p = spherical(r, theta, 2.0 * kPi * (j % n_phi) / n_phi);
      pts->InsertNextPoint(p[0], p[1], p[2]);
    }
  }
  vtkNew<vtkCellArray> quads;
  auto id = [&](int i, int j) { return static_cast<vtkIdType>(i * (n_phi + 1) + j); };
  for (int i = 0; i < n_theta; ++i)
    for (int j = 0; j < n_phi; ++j) {
      const vtkIdType q[4] = {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      quads->InsertNextCell(4, q);
    }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetPolys(quads);
  return poly;
}

vtkSmartPointer<vtkPolyData> make_ring(double radius, int segments) {
  require_positive(radius, "ring radius");
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell(segments + 1);
  for (int i = 0; i <= segments; ++i) {
    const double phi = 2.0 * kPi * (i % segments) / segments;
    lines->InsertCellPoint(pts->InsertNextPoint(radius * std::cos(phi), radius * std::sin(phi), 0.0));
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetLines(lines);
  return poly;
}

vtkSmartPointer<vtkPolyData> make_annulus(double r_inner, double r_outer, int segments) {
  require_positive(r_outer, "disk outer radius");
  if (!(r_inner >= 0.0 && r_inner < r_outer)) throw std::invalid_argument("disk: need 0 <= inner radius < outer radius");
  vtkNew<vtkDiskSource> d;
  d->SetInnerRadius(r_inner);
  d->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  d->SetOuterRadius(r_outer);
  d->SetCircumferentialResolution(segments);
  d->SetRadialResolution(8);
  d->Update();
  return d->GetOutput();
}

vtkSmartPointer<vtkPolyData> make_lat_long_sphere(double radius, int parallels, int meridians, int segments) {
  require_positive(radius, "sky radius");
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  for (int i = 1; i <= parallels; ++i) {  // parallels strictly between the poles
    const double theta = kPi * i / (parallels + 1);
    lines->InsertNextCell(segments + 1);
    for (int j = 0; j <= segments; ++j) {
      const Vec3 p = spherical(radius, theta, 2.0 * kPi * (j % segments) / segments);
      lines->InsertCellPoint(pts->InsertNextPoint(p[0], p[1], p[2]));
    }
  }
  for (int j = 0; j < meridians; ++j) {
    const double phi = 2.0 * kPi * j / meridians;
    lines->InsertNextCell(segments / 2 + 1);
    for (int i = 0; i <= segments / 2; ++i) {
      const Vec3 p = spherical(radius, kPi * i / (segments / 2), phi);
      lines->InsertCellPoint(pts->InsertNextPoint(p[0], p[1], p[2]));
    }
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetLines(lines);
  return poly;
}

vtkSmartPointer<vtkPolyData> make_camera_frustum(const CameraGlyph& camera, double length) {
  require_positive(length, "frustum length");
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  const Vec3& o = camera.position;
  const vtkIdType apex = pts->InsertNextPoint(o[0], o[1], o[2]);
  vtkIdType far[4];
  for (std::size_t i = 0; i < 4; ++i) {
    const Vec3 p = o + length * camera.corners[i];
    far[i] = pts->InsertNextPoint(p[0], p[1], p[2]);
    const vtkIdType edge[2] = {apex, far[i]};
    lines->InsertNextCell(2, edge);
  }
  const vtkIdType rect[5] = {far[0], far[1], far[2], far[3], far[0]};
  lines->InsertNextCell(5, rect);
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetLines(lines);
  return poly;
}

vtkSmartPointer<vtkPolyData> make_camera_axes(const CameraGlyph& camera, double length) {
  require_positive(length, "axis length");
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("axis_color");
  colors->SetNumberOfComponents(3);
  const Vec3& o = camera.position;
  auto add = [&](const Vec3& dir, Rgb8 c) {
    if (dir.squaredNorm() == 0.0) return;
    const Vec3 tip = o + length * dir;
    const vtkIdType seg[2] = {pts->InsertNextPoint(o[0], o[1], o[2]), pts->InsertNextPoint(tip[0], tip[1], tip[2])};
    lines->InsertNextCell(2, seg);
    colors->InsertNextTypedTuple(c.data());
  };
  add(camera.forward, {230, 60, 50});
  add(camera.up, {80, 200, 80});
  add(camera.right, {70, 120, 240});
  add(camera.velocity, {240, 210, 60});
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  poly->SetLines(lines);
  poly->GetCellData()->SetScalars(colors);
  return poly;
}

vtkSmartPointer<vtkPolyData> to_kerr_schild(vtkSmartPointer<vtkPolyData> poly, double spin, KerrSchildSlicing slicing) {
  if (!poly || !poly->GetPoints()) return poly;
  const double ea = (slicing == KerrSchildSlicing::ingoing ? 1.0 : -1.0) * spin;
  vtkPoints* pts = poly->GetPoints();
  for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i) {
    double p[3];
    pts->GetPoint(i, p);
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    if (!(r > 0.0)) continue;
    // x + i y = r sin th e^{i ph} in the BL embedding; times (r + i e a) / r gives the KS x + i y.
    const double x = p[0] - ea / r * p[1], y = p[1] + ea / r * p[0];
    pts->SetPoint(i, x, y, p[2]);
  }
  pts->Modified();
  return poly;
}

}  // namespace grtrace::viz
