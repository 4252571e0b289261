// grtrace/render/frame_files.hpp
// A frame's two files, the EXR (all channels) and its 8-bit PNG preview, written at the same time: the preview is
// converted and encoded on a thread of its own while the calling thread (and OpenEXR's pool) writes the EXR, so
// the preview costs no wall time on a machine with a spare core (docs/benchmarks.md, "Outside tracing": the time
// grtrace-render spends outside tracing).
//
//   grtrace::OutputSet files;
//   grtrace::write_exr_and_preview(files, "frame.exr", "frame.png", frame.image);   // + ExrWriteOptions, exposure
//   files.commit();                                                                 // both new, or both as they were
//
// The same files, bytes and errors as write_exr(set, ...) followed by write_png_preview(set, ...) (exr_io.hpp,
// png_preview.hpp): both go into `set` (the EXR first), nothing is renamed before set.commit(), and if either
// fails the exception propagates (the EXR's first) and the set's temporaries are removed with it.
#pragma once

#include "grtrace/render/exr_io.hpp"
#include "grtrace/render/image.hpp"
#include "grtrace/render/output_file.hpp"
#include "grtrace/render/png_preview.hpp"

#include <cstdint>
#include <exception>
#include <filesystem>
#include <thread>
#include <vector>

namespace grtrace {

inline void write_exr_and_preview(OutputSet& set, const std::filesystem::path& exr_path,
                                  const std::filesystem::path& png_path, const Image& image,
                                  const ExrWriteOptions& options = {}, float exposure = 1.0f) {
  std::vector<std::uint8_t> png;
  std::exception_ptr png_error;
  std::thread preview([&] {  // reads `image` only, as write_exr does: no data race
    try {
      png = detail::encode_png_rgb8(png_path.string(), image.width(), image.height(),
                                    detail::preview_rgb8(image, exposure));
    } catch (...) {
      png_error = std::current_exception();
    }
  });
  try {
    write_exr(set, exr_path, image, options);
  } catch (...) {
    preview.join();
    throw;
  }
  preview.join();
  if (png_error) std::rethrow_exception(png_error);
  TemporaryOutput& out = set.add(png_path);
  out.write(png.data(), png.size());
  out.finish();
}

}  // namespace grtrace
