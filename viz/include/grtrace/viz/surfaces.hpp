// grtrace/viz/surfaces.hpp
// Reference surfaces of a Schwarzschild scene as VTK polydata, in the Cartesian embedding
// (x, y, z) = (r sin th cos ph, r sin th sin ph, r cos th), so the equatorial plane theta = pi/2 is z = 0.
//
//   make_sphere             triangulated sphere (horizon r = 2M, photon sphere r = 3M)
//   make_ergosphere         Kerr's static limit r_E(theta) = M + sqrt(M^2 - a^2 cos^2 theta) as a closed
//                           latitude-longitude surface (oblate: 2M on the equator, r_+ at the poles), its points in
//                           the Boyer-Lindquist embedding above (KerrMetric::to_cartesian)
//   make_checkered_sphere   sphere whose cells carry "checker_color" (uint8 x 3): the theta-phi checkerboard,
//                           n_theta bands in theta in [0, pi] and n_phi sectors in phi in [0, 2 pi]; the cell with
//                           floor(theta / (pi/n_theta)) + floor(phi / (2 pi/n_phi)) even gets colour a
//   make_ring               circle of radius r in z = 0 (the ISCO r = 6M), a closed polyline
//   make_annulus            flat ring r_in <= rho <= r_out in z = 0 (the disk)
//   make_lat_long_sphere    wireframe of parallels and meridians (the outer sky sphere)
//   make_camera_frustum     the four corner rays from the camera position (length `length`) and the far rectangle
//   make_camera_axes        line segments along forward, up, right (and the velocity, if any), with cell colours
//                           "axis_color": forward red, up green, right blue, velocity yellow
//   to_kerr_schild          moves a surface above (points in the Boyer-Lindquist embedding, r = |p|) into the
//                           Cartesian Kerr-Schild coordinates where KerrSchildMetric draws its rays:
//                           x + i y = (r + i e a) sin th e^{i ph}, z = r cos th (e = +1 ingoing, -1 outgoing), so a
//                           sphere r = const becomes the oblate spheroid of KS radius r (semi-axes sqrt(r^2 + a^2), r)
#pragma once

#include "grtrace/viz/camera_glyph.hpp"
#include "grtrace/metric/kerr_schild.hpp"
#include "grtrace/viz/traced_path.hpp"

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

namespace grtrace::viz {

vtkSmartPointer<vtkPolyData> make_sphere(double radius, int resolution = 96);
vtkSmartPointer<vtkPolyData> make_checkered_sphere(double radius, int n_theta, int n_phi, Rgb8 a, Rgb8 b,
                                                   int cells_per_square = 6);
/// Takes M > 0 and |a| < M (throws std::invalid_argument otherwise); n_theta bands in [0, pi], n_phi sectors.
vtkSmartPointer<vtkPolyData> make_ergosphere(double mass, double spin, int n_theta = 48, int n_phi = 96);
vtkSmartPointer<vtkPolyData> make_ring(double radius, int segments = 256);
vtkSmartPointer<vtkPolyData> make_annulus(double r_inner, double r_outer, int segments = 192);
vtkSmartPointer<vtkPolyData> make_lat_long_sphere(double radius, int parallels = 11, int meridians = 24,
                                                  int segments = 128);
vtkSmartPointer<vtkPolyData> make_camera_frustum(const CameraGlyph& camera, double length);
vtkSmartPointer<vtkPolyData> make_camera_axes(const CameraGlyph& camera, double length);
/// Takes polydata in the Boyer-Lindquist embedding and the Kerr-Schild chart (spin, slicing); moves its points
/// in place (a point at the centre stays) and returns it. Azimuth is kept as the chart's own phi: a BL surface of
/// revolution (horizon, ergosphere, ISCO ring, sky) lands exactly on the KS surface of the same r and theta.
vtkSmartPointer<vtkPolyData> to_kerr_schild(vtkSmartPointer<vtkPolyData> poly, double spin, KerrSchildSlicing slicing);

}  // namespace grtrace::viz
