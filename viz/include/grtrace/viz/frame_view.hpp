// grtrace/viz/frame_view.hpp
// The 2D half of grtrace-view: the rendered frame, shown pixel for pixel (nearest-neighbour, no lighting,
// no colour mapping: a shown texel has exactly the frame's 8-bit colour), scaled uniformly to fit its
// viewport and centred, with the bundle's pixels marked by small squares (white over black, visible on any picture).
//
// The fit is recomputed before every render, so it follows window resizes. placement() is the fit (pick.hpp's
// FrameFit: frame pixel <-> viewport position, for picking, tests and overlays). Picked pixels are marked apart
// from the bundle's (magenta over black).
#pragma once

#include "grtrace/viz/frame_image.hpp"
#include "grtrace/viz/pick.hpp"

#include <array>
#include <memory>
#include <span>

class vtkRenderer;

namespace grtrace::viz {

class FrameView {
 public:
  FrameView();
  ~FrameView();
  FrameView(const FrameView&) = delete;
  FrameView& operator=(const FrameView&) = delete;

  vtkRenderer* renderer() const;

  void set_frame(const Rgb8Image& frame);
  const Rgb8Image& frame() const;

  /// Marks these frame pixels (x = column, y = row from the top).
  void set_markers(std::span<const std::array<int, 2>> pixels);
  /// Marks the picked pixels (magenta squares; an empty span clears them). Shown whatever set_markers_visible says.
  void set_pick_markers(std::span<const std::array<int, 2>> pixels);
  void set_markers_visible(bool on);
  bool markers_visible() const;

  /// Fits the frame into a viewport of this many pixels (done automatically before each render).
  void fit(int viewport_width, int viewport_height);
  /// Screen pixels per frame pixel after the last fit.
  double scale() const;
  /// Where the frame sits in its viewport after the last fit (frame pixel <-> viewport position).
  FrameFit placement() const;
  /// Centre of frame pixel (x, y from the top) in viewport pixel coordinates (origin bottom-left), after the
  /// last fit. Window coordinates add the viewport's origin.
  std::array<double, 2> frame_to_viewport(double x, double y) const;

  static constexpr std::array<double, 3> kBackground{0.04, 0.04, 0.05};

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace grtrace::viz
