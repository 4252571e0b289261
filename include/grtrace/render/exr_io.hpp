// grtrace/render/exr_io.hpp
// OpenEXR output and input of an Image (OpenEXR 3.1 C++ API; link grtrace::render).
//
//   grtrace::write_exr("frame.exr", image);          // whole file or nothing; throws std::runtime_error
//   grtrace::Image back = grtrace::read_exr("frame.exr");
//
// write_exr
// - Every channel of the image, as 32-bit FLOAT, bit-exact (NaN payloads included); ZIP compression (lossless)
//   unless ExrWriteOptions says otherwise.
// - Every Image::metadata entry becomes a string header attribute of the same name. A key that collides with
//   an attribute OpenEXR itself requires (channels, compression, dataWindow, displayWindow, lineOrder,
//   pixelAspectRatio, screenWindowCenter, screenWindowWidth) or is empty is refused (std::invalid_argument).
// - It also adds, unless metadata already has them: "software" = "grtrace", and legends that make the file
//   self-describing: "status_names" ("0=escaped 1=captured ...") when there is a "status" channel and
//   "object_names" ("0=sky 1=horizon 2=disk 3=star") when there is an "object" channel.
// - Written to a temporary sibling and renamed over `path` (write_file_atomically in image.hpp): on any failure
//   (missing or unwritable directory, full disk, OpenEXR error) nothing is left behind and std::runtime_error
//   says which path failed and why.
// read_exr
// - Any scanline or tiled single-part EXR (part 0 of a multi-part file). Every channel is converted to float
//   (HALF and UINT channels too). Channel order: the standard grtrace channels first, in Image's order, then
//   the others alphabetically; a file without the standard channels (a texture with R, G, B, A) gives an
//   Image with only its own channels (see Image::with_channels). The data window's size is the image size.
// - Every string attribute goes into Image::metadata (other attribute types are skipped).
// - Subsampled channels are refused; failures throw std::runtime_error naming the file.
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/render/image.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cstddef>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace grtrace {

struct ExrWriteOptions {
  Imf::Compression compression = Imf::ZIP_COMPRESSION;  ///< any lossless one keeps floats bit-exact
};

namespace detail {

inline std::string exr_status_legend() {
  std::string s;
  for (std::size_t i = 0; i < kRayStatusCount; ++i) {
    if (i > 0) s += ' ';
    s += std::to_string(i) + "=" + std::string(kRayStatusNames[i]);
  }
  return s;
}

/// Writes the file at `file` directly (no temporary); the caller makes it atomic.
inline void write_exr_direct(const std::filesystem::path& file, const Image& image, const ExrWriteOptions& options) {
  Imf::Header header(image.width(), image.height());
  header.compression() = options.compression;

  for (const auto& [key, value] : image.metadata) {
    if (key.empty()) throw std::invalid_argument("write_exr: empty metadata key");
    if (header.find(key) != header.end())
      throw std::invalid_argument("write_exr: metadata key '" + key +
                                  "' collides with an attribute OpenEXR requires; rename it");
    header.insert(key, Imf::StringAttribute(value));
  }
  auto add_default = [&](const char* key, const std::string& value) {
    if (header.find(key) == header.end()) header.insert(key, Imf::StringAttribute(value));
  };
  add_default("software", "grtrace");
  if (image.has_channel("status")) add_default("status_names", exr_status_legend());
  if (image.has_channel("object")) add_default("object_names", "0=sky 1=horizon 2=disk 3=star");

  Imf::FrameBuffer frame;
  const std::size_t x_stride = sizeof(float);
  const std::size_t y_stride = sizeof(float) * static_cast<std::size_t>(image.width());
  for (const auto& name : image.channel_names()) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    // OpenEXR only reads through the pointer while writing; the cast drops const for its API.
    const float* data = image.channel(name).data();
    frame.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(data)), x_stride, y_stride));
  }

  std::ofstream os(file, std::ios::binary | std::ios::trunc);
  if (!os) throw std::runtime_error("cannot open '" + file.string() + "' for writing");
  {
    Imf::StdOFStream stream(os, file.c_str());
    Imf::OutputFile out(stream, header);
    out.setFrameBuffer(frame);
    out.writePixels(image.height());
  }  // the OutputFile destructor writes the line offset table: check the stream only after it
  os.flush();
  os.close();
  if (os.fail()) throw std::runtime_error("failed while writing '" + file.string() + "' (disk full?)");
}

}  // namespace detail

/// Writes all channels (FLOAT) and all metadata (string attributes) of `image` to `path`, whole or not at all.
/// Throws std::invalid_argument for unusable metadata keys, std::runtime_error for I/O failures.
inline void write_exr(const std::filesystem::path& path, const Image& image, const ExrWriteOptions& options = {}) {
  write_file_atomically(path, [&](const std::filesystem::path& tmp) {
    try {
      detail::write_exr_direct(tmp, image, options);
    } catch (const std::invalid_argument&) {
      throw;
    } catch (const std::exception& e) {
      throw std::runtime_error("cannot write EXR '" + path.string() + "': " + e.what());
    }
  });
}

/// Reads every channel (as float) and every string attribute of an EXR file. Throws std::runtime_error.
inline Image read_exr(const std::filesystem::path& path) {
  try {
    if (!std::filesystem::is_regular_file(path)) throw std::runtime_error("no such file");
    Imf::InputFile in(path.c_str());
    const Imf::Header& header = in.header();
    const Imath::Box2i window = header.dataWindow();
    const long w = static_cast<long>(window.max.x) - window.min.x + 1;
    const long h = static_cast<long>(window.max.y) - window.min.y + 1;
    if (w <= 0 || h <= 0 || w > 1L << 30 || h > 1L << 30 || w * h > 1L << 34)
      throw std::runtime_error("unsupported data window " + std::to_string(w) + " x " + std::to_string(h));

    std::vector<std::string> names;
    for (const char* standard : Image::kStandardChannels)
      if (header.channels().findChannel(standard) != nullptr) names.emplace_back(standard);
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
      const std::string name = it.name();
      if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
        throw std::runtime_error("channel '" + name + "' is subsampled; only full-resolution channels are supported");
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }

    Image image = Image::with_channels(static_cast<int>(w), static_cast<int>(h), names);
    Imf::FrameBuffer frame;
    for (const auto& name : names) frame.insert(name, Imf::Slice::Make(Imf::FLOAT, image.channel(name).data(), window));
    in.setFrameBuffer(frame);
    in.readPixels(window.min.y, window.max.y);

    for (auto it = header.begin(); it != header.end(); ++it)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        image.metadata[it.name()] = s->value();
    return image;
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot read EXR '" + path.string() + "': " + e.what());
  }
}

}  // namespace grtrace
