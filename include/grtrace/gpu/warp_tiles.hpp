// grtrace/gpu/warp_tiles.hpp
// Which pixel each GPU thread traces: a warp (32 threads, which run in lockstep) takes a tile of 4 columns x 8 rows.
//
// Why tiles: a warp's step ends only when the slowest of its rays has taken it, and a warp is busy until its last
// ray ends. Rays of neighbouring pixels take similar paths, similar numbers of steps and the same branches, so a
// compact tile keeps more of a warp's threads doing work than 32 pixels of one row do (a row's strip crosses the
// shadow's edge, the disk's edge and the Einstein ring more often). Measured on an H200, 1024 x 1024, rkf78 + i,
// kernels alone (docs/benchmarks.md, "GPU"): Kerr disk frame (kerr-mino) 18.9 ms with rows of 32, 14.8 ms with
// 16 x 2 tiles, 12.5 ms with 8 x 4, 11.2 ms with 4 x 8; the main frame (general tracer) 16.9, 14.1, 12.4, 11.5 ms.
//
// Takes:   the traced block's width and height in pixels.
// Returns: for thread t of thread_count() threads, the pixel it traces, or nothing for a thread of the padding
//          beyond the right or bottom edge (the block's sides need not be multiples of the tile's).
// Assumes: threads 32k .. 32k+31 form one warp (CUDA's numbering of a one-dimensional launch with blocks of a
//          multiple of 32 threads).
#pragma once

#include "grtrace/core/host_device.hpp"

namespace grtrace::gpu {

/// A pixel of the traced block: its column and row.
struct PixelIndex {
  int col = 0, row = 0;
};

class WarpTiles {
 public:
  static constexpr int warp_size = 32;
  static constexpr int tile_width = 4, tile_height = 8;
  static_assert(tile_width * tile_height == warp_size, "a tile is one warp's pixels");

  GRTRACE_HD WarpTiles(int width, int height)
      : width_(width), height_(height), tiles_per_row_((width + tile_width - 1) / tile_width) {}

  /// Threads to launch: a whole warp for every tile that holds at least one pixel.
  GRTRACE_HD long thread_count() const {
    const long tile_rows = (height_ + tile_height - 1) / tile_height;
    return static_cast<long>(tiles_per_row_) * tile_rows * warp_size;
  }

  /// The traced block's width: a pixel's outcome is stored at row * width() + col.
  GRTRACE_HD int width() const { return width_; }

  /// The pixel of thread t (t >= 0); false for a thread beyond the block's edge, which every t >= thread_count() is.
  GRTRACE_HD bool pixel_of(long t, PixelIndex& p) const {
    const long tile = t / warp_size;
    const int lane = static_cast<int>(t % warp_size);
    p.col = static_cast<int>(tile % tiles_per_row_) * tile_width + lane % tile_width;
    p.row = static_cast<int>(tile / tiles_per_row_) * tile_height + lane / tile_width;
    return p.col < width_ && p.row < height_;
  }

 private:
  int width_, height_, tiles_per_row_;
};

}  // namespace grtrace::gpu
