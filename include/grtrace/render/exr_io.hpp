// grtrace/render/exr_io.hpp
// OpenEXR output and input of an Image (OpenEXR 3.1 C++ API; link grtrace::render).
//
//   grtrace::write_exr("frame.exr", image);          // whole file or nothing; throws std::runtime_error
//   grtrace::Image back = grtrace::read_exr("frame.exr");
//
// write_exr
// - Every channel of the image, as 32-bit FLOAT, bit-exact (NaN payloads included); ZIP compression (lossless) at
//   level 1, compressed on all cores (ExrWriteOptions::threads), unless ExrWriteOptions says otherwise.
//   exr_compression_from_name() maps the lossless compressions' names ("none", "rle", "zips", "zip", "piz") to
//   Imf::Compression for command lines. Level 1 instead of OpenEXR's default 4 makes a 1024x1024 frame about 4%
//   larger and 20% cheaper to write; any level reads back the same (docs/benchmarks-archive.md, "Outside tracing").
// - ZIP, ZIPS and uncompressed files (the tools' choices by default) are laid out by write_exr_scanlines below and
//   deflated with libdeflate, which compresses the main frame's chunks in 0.6 of zlib's time at level 1 and a
//   little smaller; OpenEXR's header writer, its reader and any other reader see an ordinary scanline file
//   (OpenEXR 2.0 layout). RLE and PIZ go through Imf::OutputFile (OpenEXR's global thread pool, grown to
//   ExrWriteOptions::threads if it is smaller).
// - Every Image::metadata entry becomes a string header attribute of the same name. A key that collides with
//   an attribute OpenEXR itself requires (channels, compression, dataWindow, displayWindow, lineOrder,
//   pixelAspectRatio, screenWindowCenter, screenWindowWidth) or is empty is refused (std::invalid_argument).
// - It also adds, unless metadata already has them: "software" = "grtrace", and legends that make the file
//   self-describing: "status_names" ("0=escaped 1=captured ...") when there is a "status" channel and
//   "object_names" ("0=sky 1=horizon 2=disk 3=star") when there is an "object" channel.
// - Written to an exclusively created temporary sibling and renamed over `path` (output_file.hpp): on any
//   failure (missing or unwritable directory, full disk, OpenEXR error) nothing is left behind and
//   std::runtime_error says which path failed and why. write_exr(set, path, image) writes into an OutputSet.
// read_exr
// - Any scanline or tiled single-part EXR (part 0 of a multi-part file). Every channel is converted to float
//   (HALF and UINT channels too). Channel order: the standard grtrace channels first, in Image's order, then
//   the others alphabetically; a file without the standard channels (a texture with R, G, B, A) gives an
//   Image with only its own channels (see Image::with_channels). The data window's size is the image size.
// - Every string attribute goes into Image::metadata (other attribute types are skipped).
// - Subsampled channels are refused; failures throw std::runtime_error naming the file.
// - Limits, checked before any pixel is allocated: the channels (as floats) must fit memory_limit_bytes()
//   (image.hpp: 4 GiB unless GRTRACE_MEMORY_LIMIT says otherwise; MemoryLimitError, which names the limit and
//   the variable), and the file must be large enough for the offset table its data window needs (a forged
//   header claiming 12000 x 12000 pixels in a few kB is refused as "forged or truncated header"), for all its
//   pixels when uncompressed, and one chunk may not decode to more than max(64 MB, 100 x the file); before
//   OpenEXR parses the header, every attribute's byte count must fit in the file (OpenEXR allocates it first).
//   The pixels are then decoded in bands of chunks (the first about 16 MB, each later one as large as all before
//   it) straight into the channels, whose memory is written only as bands arrive: a file whose chunks are missing
//   costs about one band before it is refused, not the image its header claims.
#pragma once

#include "grtrace/core/ray_status.hpp"
#include "grtrace/render/image.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfTileDescription.h>
#include <OpenEXR/ImfVersion.h>
#include <libdeflate.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

namespace grtrace {

struct ExrWriteOptions {
  Imf::Compression compression = Imf::ZIP_COMPRESSION;  ///< any lossless one keeps floats bit-exact
  int zip_level = 1;  ///< deflate level of ZIP and ZIPS: 1 (fastest) .. 9 (smallest); -1: OpenEXR's default (4)
  int threads = 0;    ///< compression threads: 0 = all hardware threads, 1 = only the calling thread
};

/// The lossless compressions by name, for command lines: none, rle, zips, zip, piz (the lossy ones, and B44 that
/// only compresses HALF channels, are left out: grtrace writes FLOAT channels that must read back bit for bit).
inline constexpr std::array<std::pair<std::string_view, Imf::Compression>, 5> kExrLosslessCompressions = {{
    {"none", Imf::NO_COMPRESSION},
    {"rle", Imf::RLE_COMPRESSION},
    {"zips", Imf::ZIPS_COMPRESSION},
    {"zip", Imf::ZIP_COMPRESSION},
    {"piz", Imf::PIZ_COMPRESSION},
}};

/// The compression of a name in kExrLosslessCompressions; nullopt for any other name.
inline std::optional<Imf::Compression> exr_compression_from_name(std::string_view name) {
  for (const auto& [n, c] : kExrLosslessCompressions)
    if (n == name) return c;
  return std::nullopt;
}

namespace detail {

inline std::string exr_status_legend() {
  std::string s;
  for (std::size_t i = 0; i < kRayStatusCount; ++i) {
    if (i > 0) s += ' ';
    s += std::to_string(i) + "=" + std::string(kRayStatusNames[i]);
  }
  return s;
}

/// An Imf::OStream on any seekable std::ostream (Imf::StdOFStream wants an std::ofstream).
class ExrOStream : public Imf::OStream {
 public:
  ExrOStream(std::ostream& os, const char* name) : Imf::OStream(name), os_(os) {}
  void write(const char c[], int n) override {
    os_.write(c, n);
    check();
  }
  uint64_t tellp() override {
    const auto p = os_.tellp();
    check();
    return static_cast<uint64_t>(static_cast<std::streamoff>(p));
  }
  void seekp(uint64_t pos) override {
    os_.seekp(static_cast<std::streamoff>(pos));
    check();
  }

 private:
  void check() const {
    if (!os_) throw std::runtime_error(std::string("write error on '") + fileName() + "' (disk full?)");
  }
  std::ostream& os_;
};

/// The thread count to give Imf::OutputFile for `requested` (0 = all hardware threads): 0 (write in the calling
/// thread) for one thread, else n, with OpenEXR's global thread pool grown to at least n threads (never shrunk:
/// other OpenEXR users in the process keep theirs).
inline int exr_threads(int requested) {
  const int n = requested > 0 ? requested : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (n <= 1) return 0;
  static std::mutex mutex;
  const std::lock_guard lock(mutex);
  if (Imf::globalThreadCount() < n) Imf::setGlobalThreadCount(n);
  return n;
}

/// Scanlines per chunk of a compression (the offset table has one 8-byte entry per chunk).
inline int exr_lines_per_chunk(Imf::Compression c) {
  switch (c) {
    case Imf::NO_COMPRESSION:
    case Imf::RLE_COMPRESSION:
    case Imf::ZIPS_COMPRESSION: return 1;
    case Imf::ZIP_COMPRESSION:
    case Imf::PXR24_COMPRESSION: return 16;
    case Imf::PIZ_COMPRESSION:
    case Imf::B44_COMPRESSION:
    case Imf::B44A_COMPRESSION:
    case Imf::DWAA_COMPRESSION: return 32;
    default: return 256;  // DWAB and anything newer: the largest chunk
  }
}

/// The compressions write_exr_scanlines writes itself; the others go through Imf::OutputFile.
inline bool exr_written_by_grtrace(Imf::Compression c) {
  return c == Imf::NO_COMPRESSION || c == Imf::ZIP_COMPRESSION || c == Imf::ZIPS_COMPRESSION;
}

/// Row y of a channel plane of the given width.
inline const float* exr_row(const float* channel, int width, int y) {
  return channel + static_cast<std::size_t>(y) * static_cast<std::size_t>(width);
}

/// The raw bytes of the chunk of scanlines [y0, y1): each scanline holds the channels in header order.
inline void exr_pack_chunk(const std::vector<const float*>& channels, int width, int y0, int y1,
                           std::vector<unsigned char>& raw) {
  const std::size_t row_bytes = sizeof(float) * static_cast<std::size_t>(width);
  raw.resize(row_bytes * channels.size() * static_cast<std::size_t>(y1 - y0));
  unsigned char* p = raw.data();
  for (int y = y0; y < y1; ++y)
    for (const float* channel : channels) {
      std::memcpy(p, exr_row(channel, width, y), row_bytes);
      p += row_bytes;
    }
}

/// One chunk of a ZIP or ZIPS file (the OpenEXR format's ZIP compressor): the chunk's raw bytes (exr_pack_chunk)
/// split into those at even and at odd positions, even ones first, each byte after the first replaced by its
/// difference to the one before it plus 128 (mod 256), then deflated into a zlib stream. Split and difference are
/// one pass over the floats (a float's bytes 0 and 2 go to the even half, 1 and 3 to the odd half). When
/// deflating does not make the chunk smaller, the raw bytes are stored instead: a reader takes a chunk whose size
/// is the uncompressed size as stored.
inline void exr_zip_chunk(libdeflate_compressor* compressor, const std::vector<const float*>& channels, int width,
                          int y0, int y1, std::vector<unsigned char>& scratch, std::vector<unsigned char>& out) {
  const std::size_t n = sizeof(float) * static_cast<std::size_t>(width) * channels.size() *
                        static_cast<std::size_t>(y1 - y0);
  scratch.resize(n);
  unsigned char* even = scratch.data();
  unsigned char* odd = scratch.data() + n / 2;  // n is a multiple of 4: the halves are equal
  unsigned char last[4];
  std::memcpy(last, exr_row(channels.back(), width, y1 - 1) + width - 1, 4);
  unsigned prev_even = 128u, prev_odd = last[2];  // the first byte stays as it is; the odd half follows the even
  std::size_t k = 0;
  for (int y = y0; y < y1; ++y)
    for (const float* channel : channels) {
      const float* row = exr_row(channel, width, y);
      for (int x = 0; x < width; ++x, k += 2) {
        unsigned char b[4];
        std::memcpy(b, row + x, 4);
        even[k] = static_cast<unsigned char>(b[0] - prev_even + 128u);
        even[k + 1] = static_cast<unsigned char>(b[2] - b[0] + 128u);
        odd[k] = static_cast<unsigned char>(b[1] - prev_odd + 128u);
        odd[k + 1] = static_cast<unsigned char>(b[3] - b[1] + 128u);
        prev_even = b[2];
        prev_odd = b[3];
      }
    }
  out.resize(libdeflate_zlib_compress_bound(compressor, n));
  const std::size_t size = libdeflate_zlib_compress(compressor, scratch.data(), n, out.data(), out.size());
  if (size == 0 || size >= n) exr_pack_chunk(channels, width, y0, y1, out);
  else out.resize(size);
}

/// Writes a scanline EXR of compression NONE, ZIP or ZIPS (exr_written_by_grtrace) into `os`: magic and version,
/// the header by OpenEXR's own writer, the line offset table, then each chunk as (first line, byte count, bytes),
/// in increasing y. The chunks are packed and deflated on `threads` threads (0: all hardware threads), each with
/// its own libdeflate compressor, and written in order once all are done (the offsets are known before writing:
/// no seeking back). Assumes a little-endian host (the floats are copied as they lie in memory; checked at
/// compile time) and the header's channels all FLOAT, one per image channel. Throws what the stream's checks
/// throw (ExrOStream) and std::bad_alloc when libdeflate cannot allocate a compressor.
inline void write_exr_scanlines(std::ostream& os, const std::string& name, const Imf::Header& header,
                                const Image& image, int level, int threads) {
  static_assert(std::endian::native == std::endian::little,
                "write_exr_scanlines copies floats as stored: a big-endian host needs a byte swap here");
  const Imf::Compression compression = header.compression();
  const int width = image.width(), height = image.height();
  const int lines = exr_lines_per_chunk(compression);
  const int chunks = (height + lines - 1) / lines;
  std::vector<const float*> channels;  // in the header's (sorted) order, which is the order in each scanline
  bool long_names = false;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    channels.push_back(image.channel(it.name()).data());
    long_names |= std::strlen(it.name()) > 31;
  }
  for (auto it = header.begin(); it != header.end(); ++it)
    long_names |= std::strlen(it.name()) > 31 || std::strlen(it.attribute().typeName()) > 31;

  std::vector<std::vector<unsigned char>> packed(static_cast<std::size_t>(chunks));
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto work = [&] {
    try {
      const std::unique_ptr<libdeflate_compressor, decltype(&libdeflate_free_compressor)> compressor(
          compression == Imf::NO_COMPRESSION ? nullptr : libdeflate_alloc_compressor(level), &libdeflate_free_compressor);
      if (compression != Imf::NO_COMPRESSION && !compressor) throw std::bad_alloc();
      std::vector<unsigned char> scratch;
      for (int c = next++; c < chunks; c = next++) {
        const int y0 = c * lines, y1 = std::min(height, y0 + lines);
        auto& out = packed[static_cast<std::size_t>(c)];
        if (compressor) exr_zip_chunk(compressor.get(), channels, width, y0, y1, scratch, out);
        else exr_pack_chunk(channels, width, y0, y1, out);
      }
    } catch (...) {
      const std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
      next = chunks;
    }
  };
  const int n = std::clamp(threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency()), 1, chunks);
  {
    std::vector<std::jthread> pool;
    for (int t = 1; t < n; ++t) pool.emplace_back(work);
    work();
  }
  if (error) std::rethrow_exception(error);

  ExrOStream stream(os, name.c_str());
  auto put32 = [&](std::uint32_t v) {
    const char b[4] = {static_cast<char>(v & 0xff), static_cast<char>(v >> 8 & 0xff), static_cast<char>(v >> 16 & 0xff),
                       static_cast<char>(v >> 24 & 0xff)};
    stream.write(b, 4);
  };
  auto put64 = [&](std::uint64_t v) {
    put32(static_cast<std::uint32_t>(v & 0xffffffffu));
    put32(static_cast<std::uint32_t>(v >> 32));
  };
  put32(static_cast<std::uint32_t>(Imf::MAGIC));
  put32(static_cast<std::uint32_t>(Imf::EXR_VERSION | (long_names ? Imf::LONG_NAMES_FLAG : 0)));
  header.writeTo(stream);
  std::uint64_t offset = stream.tellp() + 8u * static_cast<std::uint64_t>(chunks);
  for (const auto& chunk : packed) {
    put64(offset);
    offset += 8u + chunk.size();
  }
  for (int c = 0; c < chunks; ++c) {
    const auto& chunk = packed[static_cast<std::size_t>(c)];
    put32(static_cast<std::uint32_t>(c * lines));
    put32(static_cast<std::uint32_t>(chunk.size()));
    stream.write(reinterpret_cast<const char*>(chunk.data()), static_cast<int>(chunk.size()));
  }
}

/// Writes the EXR into `os` (seekable: OpenEXR seeks back for its offset table); `name` for messages.
inline void write_exr_stream(std::ostream& os, const std::string& name, const Image& image,
                             const ExrWriteOptions& options) {
  Imf::Header header(image.width(), image.height());
  header.compression() = options.compression;
  if (options.zip_level != -1) {
    if (options.zip_level < 1 || options.zip_level > 9)
      throw std::invalid_argument("write_exr: zip_level must be 1 .. 9 (or -1 for OpenEXR's default), got " +
                                  std::to_string(options.zip_level));
    header.zipCompressionLevel() = options.zip_level;  // a writer setting: not stored in the file
  }

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

  for (const auto& channel : image.channel_names()) header.channels().insert(channel, Imf::Channel(Imf::FLOAT));

  if (exr_written_by_grtrace(options.compression)) {
    header.sanityCheck();
    write_exr_scanlines(os, name, header, image, options.zip_level == -1 ? 4 : options.zip_level, options.threads);
  } else {
    // Only Imf::OutputFile (rle, piz) reads the pixels through a frame buffer.
    Imf::FrameBuffer frame;
    const std::size_t x_stride = sizeof(float);
    const std::size_t y_stride = sizeof(float) * static_cast<std::size_t>(image.width());
    for (const auto& channel : image.channel_names()) {
      // OpenEXR only reads through the pointer while writing; the cast drops const for its API.
      const float* data = image.channel(channel).data();
      frame.insert(channel,
                   Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(data)), x_stride, y_stride));
    }
    ExrOStream stream(os, name.c_str());
    Imf::OutputFile out(stream, header, exr_threads(options.threads));
    out.setFrameBuffer(frame);
    out.writePixels(image.height());
  }  // the OutputFile destructor writes the line offset table: check the stream only after it
  os.flush();
  if (!os) throw std::runtime_error("failed while writing '" + name + "' (disk full?)");
}

inline void write_exr_into(TemporaryOutput& out, const Image& image, const ExrWriteOptions& options) {
  try {
    write_exr_stream(out.stream(), out.target().string(), image, options);
    out.finish();
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot write EXR '" + out.target().string() + "': " + e.what());
  }
}

/// A little-endian 32-bit integer of an EXR file (magic number, version, attribute sizes).
inline std::int32_t exr_le32(const unsigned char* b) {
  return static_cast<std::int32_t>(static_cast<std::uint32_t>(b[0]) | static_cast<std::uint32_t>(b[1]) << 8 |
                                   static_cast<std::uint32_t>(b[2]) << 16 | static_cast<std::uint32_t>(b[3]) << 24);
}

/// Reads an EXR file's first 8 bytes from `file` and returns its version field; throws std::runtime_error for a
/// file too short or without OpenEXR's magic number (before any of its bytes could reach a message).
inline int read_exr_start(std::istream& file) {
  unsigned char start[8] = {};
  file.read(reinterpret_cast<char*>(start), sizeof start);
  if (file.gcount() != 8) throw std::runtime_error("too short for an OpenEXR file");
  if (exr_le32(start) != Imf::MAGIC) throw std::runtime_error("not an OpenEXR file (wrong magic number)");
  return exr_le32(start + 4);
}

/// Walks the header attributes (name, type, byte count) without OpenEXR and refuses any whose byte count exceeds
/// what is left of the file: OpenEXR allocates an attribute's claimed size before reading it, so a 200-byte file
/// claiming a 1.7 GB string attribute would otherwise cost 1.7 GB (found by tests/fuzz/exr_fuzz).
inline void check_exr_attribute_sizes(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::error_code ec;
  const auto file_size = static_cast<long long>(std::filesystem::file_size(path, ec));
  if (!file || ec) throw std::runtime_error("cannot open the file");
  const bool multi_part = (read_exr_start(file) & 0x1000) != 0;  // version flags: bit 12 = multi-part
  // Names go into messages: a byte outside printable ASCII means the header is not one (never echo raw bytes).
  auto printable = [](const std::string& text) {
    return std::all_of(text.begin(), text.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
  };
  auto read_name = [&](std::string& out) {
    out.clear();
    for (int c = file.get(); c != 0; c = file.get()) {
      if (c == std::char_traits<char>::eof()) throw std::runtime_error("the header ends early (truncated file)");
      if (out.size() >= 255) throw std::runtime_error("a header attribute name is longer than 255 characters");
      out += static_cast<char>(c);
    }
  };
  std::string name, type;
  for (;;) {
    read_name(name);
    if (name.empty()) return;  // the empty header that ends a multi-part file's list (or an empty one)
    for (;;) {
      read_name(type);
      if (!printable(name) || !printable(type))
        throw std::runtime_error("a header attribute's name or type is not text: damaged or not an OpenEXR file");
      unsigned char size_bytes[4] = {};
      file.read(reinterpret_cast<char*>(size_bytes), 4);
      if (file.gcount() != 4) throw std::runtime_error("the header ends early (truncated file)");
      const long long size = exr_le32(size_bytes);
      const long long left = file_size - static_cast<long long>(file.tellg());
      if (size < 0 || size > left)
        throw std::runtime_error("header attribute '" + name + "' (" + type + ") claims " + std::to_string(size) +
                                 " bytes but only " + std::to_string(left) +
                                 " are left in the file: forged or truncated header");
      file.seekg(size, std::ios::cur);
      read_name(name);
      if (name.empty()) break;  // end of this header
    }
    if (!multi_part) return;
  }
}

/// The header of part 0, read without the rest of the file (so a forged data window is seen before OpenEXR
/// reads offset tables or pixels).
inline Imf::Header read_exr_header(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error("cannot open the file");
  int version = read_exr_start(file);
  Imf::StdIFStream stream(file, path.c_str());
  Imf::Header header;
  header.readFrom(stream, version);
  return header;
}

/// The largest chunk (decoded) a file smaller than a 100th of it may claim: see check_exr_header.
inline constexpr double kMaxExrChunkBytes = 64.0 * 1024 * 1024;

/// The limits every read_exr() applies before allocating pixels: the data window's size, its channels (as
/// floats) against memory_limit_bytes(), the smallest file that can hold that window (one 8-byte offset-table
/// entry per chunk; every stored pixel when uncompressed), and one chunk's decoded size against
/// max(kMaxExrChunkBytes, 100 x the file).
inline void check_exr_header(const std::filesystem::path& path, const Imf::Header& header) {
  const Imath::Box2i window = header.dataWindow();
  const long w = static_cast<long>(window.max.x) - window.min.x + 1;
  const long h = static_cast<long>(window.max.y) - window.min.y + 1;
  if (w <= 0 || h <= 0 || w > 1L << 30 || h > 1L << 30)
    throw std::runtime_error("unsupported data window " + std::to_string(w) + " x " + std::to_string(h));
  long channel_count = 0;
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) ++channel_count;
  const std::string size_text = std::to_string(w) + " x " + std::to_string(h);
  check_memory(image_bytes(static_cast<double>(w), static_cast<double>(h), static_cast<double>(channel_count)),
               "its data window of " + size_text + " pixels with " + std::to_string(channel_count) + " channels");
  double chunks = 0.0;
  if (header.hasTileDescription()) {
    const Imf::TileDescription& t = header.tileDescription();
    chunks = std::ceil(static_cast<double>(w) / std::max(1u, t.xSize)) *
             std::ceil(static_cast<double>(h) / std::max(1u, t.ySize));
  } else {
    chunks = std::ceil(static_cast<double>(h) / exr_lines_per_chunk(header.compression()));
  }
  std::error_code size_ec;
  const auto file_size = static_cast<double>(std::filesystem::file_size(path, size_ec));
  if (size_ec) return;
  if (file_size < 8.0 * chunks)
    throw std::runtime_error("the header claims " + size_text + " pixels, which needs at least " +
                             describe_bytes(8.0 * chunks) + " of chunk offsets, but the file has only " +
                             describe_bytes(file_size) + ": forged or truncated header");
  double pixel_bytes = 0.0;  // one pixel of every channel as stored (HALF 2 bytes, FLOAT and UINT 4)
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
    pixel_bytes += it.channel().type == Imf::HALF ? 2.0 : 4.0;
  const double stored = static_cast<double>(w) * static_cast<double>(h) * pixel_bytes;
  if (header.compression() == Imf::NO_COMPRESSION && file_size < stored)
    throw std::runtime_error("the header claims " + size_text + " uncompressed pixels (" + describe_bytes(stored) +
                             ") but the file has only " + describe_bytes(file_size) + ": forged or truncated header");
  // One chunk is decoded whole (by OpenEXR, into a buffer of its own): a chunk larger than any real image needs
  // (64 MB is 16 scanlines 1M pixels wide), and larger than 100 times the whole file, is a forged header.
  double chunk_pixels = 0.0;
  if (header.hasTileDescription()) {
    const Imf::TileDescription& t = header.tileDescription();
    chunk_pixels = static_cast<double>(t.xSize) * static_cast<double>(t.ySize);
  } else {
    chunk_pixels = static_cast<double>(w) * exr_lines_per_chunk(header.compression());
  }
  const double chunk_bytes = chunk_pixels * std::max(pixel_bytes, static_cast<double>(channel_count) * 4.0);
  if (chunk_bytes > std::max(kMaxExrChunkBytes, 100.0 * file_size))
    throw std::runtime_error("one chunk of the header's " + size_text + " pixels would decode to " +
                             describe_bytes(chunk_bytes) + ", more than " + describe_bytes(kMaxExrChunkBytes) +
                             " and 100 times the " + describe_bytes(file_size) + " file: forged header");
}

/// read_exr()'s first band: whole chunks, about this many bytes of float channels (later bands double).
inline constexpr double kExrBandBytes = 16.0 * 1024 * 1024;

}  // namespace detail

/// Writes all channels (FLOAT) and all metadata (string attributes) of `image` to `path`, whole or not at all.
/// Throws std::invalid_argument for unusable metadata keys, std::runtime_error for I/O failures.
inline void write_exr(const std::filesystem::path& path, const Image& image, const ExrWriteOptions& options = {}) {
  TemporaryOutput out(path);
  detail::write_exr_into(out, image, options);
  out.commit();
}

/// The same as part of a set of outputs (written now, renamed into place by set.commit()).
inline void write_exr(OutputSet& set, const std::filesystem::path& path, const Image& image,
                      const ExrWriteOptions& options = {}) {
  detail::write_exr_into(set.add(path), image, options);
}

namespace detail {
/// The one way in for every EXR grtrace reads (frames, textures, a flight's frames on disk, the viewer's --frame):
/// a regular file, its header's attributes no larger than the file (check_exr_attribute_sizes), then the header
/// read alone and its sizes checked (check_exr_header), before OpenEXR reads (or trips over) anything else.
/// Throws std::runtime_error or MemoryLimitError saying what is wrong with the file.
inline Imf::Header checked_exr_header(const std::filesystem::path& path) {
  {
    std::error_code ec;
    const std::filesystem::file_status st = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(st)) throw std::runtime_error("no such file");
    if (!std::filesystem::is_regular_file(st))
      throw std::runtime_error(std::string("it is ") + entry_kind_name(st) + ", not an EXR file");
  }
  // Protects OpenEXR's own allocations (offset tables) from absurd data windows: refused by the header check.
  static const bool limited = [] {
    Imf::Header::setMaxImageSize(1 << 20, 1 << 20);
    Imf::Header::setMaxTileSize(1 << 16, 1 << 16);
    return true;
  }();
  (void)limited;
  check_exr_attribute_sizes(path);
  Imf::Header header = read_exr_header(path);
  check_exr_header(path, header);
  return header;
}

/// The message of a failed read of `path`, as read_exr and read_exr_info throw it.
template <class F>
decltype(auto) exr_reading(const std::filesystem::path& path, F&& f) {
  try {
    return f();
  } catch (const MemoryLimitError& e) {
    throw MemoryLimitError("cannot read EXR '" + path.string() + "': " + e.what());
  } catch (const std::bad_alloc&) {
    throw MemoryLimitError("cannot read EXR '" + path.string() + "': out of memory");
  } catch (const std::exception& e) {
    throw std::runtime_error("cannot read EXR '" + path.string() + "': " + e.what());
  }
}
}  // namespace detail

/// What an EXR file holds, from its header alone (checked as read_exr checks it; no pixel is decoded): its size,
/// its channels' names and its string attributes. For a caller that must judge a file before paying for its
/// pixels (is it a frame? has it R, G, B? does it fit in memory with the copies the caller will make?).
struct ExrInfo {
  int width = 0, height = 0;
  std::vector<std::string> channels;
  std::map<std::string, std::string> metadata;
  bool has_channel(std::string_view name) const {
    return std::find(channels.begin(), channels.end(), name) != channels.end();
  }
};

/// The ExrInfo of `path`. Throws std::runtime_error (MemoryLimitError for a header whose pixels would not fit).
inline ExrInfo read_exr_info(const std::filesystem::path& path) {
  return detail::exr_reading(path, [&] {
    const Imf::Header header = detail::checked_exr_header(path);
    const Imath::Box2i window = header.dataWindow();
    ExrInfo info;
    info.width = window.max.x - window.min.x + 1;
    info.height = window.max.y - window.min.y + 1;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
      info.channels.emplace_back(it.name());
    for (auto it = header.begin(); it != header.end(); ++it)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        info.metadata[it.name()] = s->value();
    return info;
  });
}

/// Reads every channel (as float) and every string attribute of an EXR file. Throws std::runtime_error.
inline Image read_exr(const std::filesystem::path& path) {
  return detail::exr_reading(path, [&] {
    (void)detail::checked_exr_header(path);  // before OpenEXR reads anything else
    Imf::InputFile in(path.c_str());
    const Imf::Header& header = in.header();
    const Imath::Box2i window = header.dataWindow();
    // Checked again: this is the header the pixels are read with, from a second open of the file, which may have
    // been replaced since the first check (which is there to keep OpenEXR's own parse from oversized attributes).
    detail::check_exr_header(path, header);
    const long w = static_cast<long>(window.max.x) - window.min.x + 1;
    const long h = static_cast<long>(window.max.y) - window.min.y + 1;

    std::vector<std::string> names;
    for (const char* standard : Image::kStandardChannels)
      if (header.channels().findChannel(standard) != nullptr) names.emplace_back(standard);
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
      const std::string name = it.name();
      if (it.channel().xSampling != 1 || it.channel().ySampling != 1)
        throw std::runtime_error("channel '" + name + "' is subsampled; only full-resolution channels are supported");
      if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
    }

    // The pixels arrive in bands of whole chunks, decoded straight into the channels, which are written (and so
    // backed by memory) only as bands arrive: a header that claims more pixels than the file holds fails at the
    // first missing chunk, having cost about one band, not the claimed image (a forged 8 kB file claiming
    // 8000 x 8000 pixels cost 2.3 GB before it was refused). Each channel reserves its whole size at once (address
    // space, which the memory check above bounds; pages are only touched as bands fill them), so growing never
    // copies. The first band is ~16 MB, each later one as large as all before it: a large file takes a few reads.
    const long chunk_lines = header.hasTileDescription()
                                 ? std::max(1L, static_cast<long>(header.tileDescription().ySize))
                                 : static_cast<long>(detail::exr_lines_per_chunk(header.compression()));
    const double line_bytes = 4.0 * static_cast<double>(w) * static_cast<double>(names.size());
    const long first_chunks =
        std::max(1L, static_cast<long>(detail::kExrBandBytes / (line_bytes * static_cast<double>(chunk_lines))));
    const auto width = static_cast<std::size_t>(w);
    std::vector<std::vector<float>> planes(names.size());
    for (std::vector<float>& plane : planes) plane.reserve(width * static_cast<std::size_t>(h));
    long done = 0;  // lines decoded; bands start on chunk boundaries of the data window (which starts a chunk)
    while (done < h) {
      const long lines = std::min(h - done, std::max(first_chunks * chunk_lines, done));
      const std::size_t values = static_cast<std::size_t>(done + lines) * width;
      for (std::vector<float>& plane : planes) plane.resize(values);
      const int y0 = window.min.y + static_cast<int>(done), y1 = y0 + static_cast<int>(lines) - 1;
      Imf::FrameBuffer frame;  // row y of the window at plane.data() + (y - min.y) * width, as in the image
      for (std::size_t c = 0; c < names.size(); ++c)
        frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, planes[c].data(), window));
      in.setFrameBuffer(frame);
      in.readPixels(y0, y1);
      done += lines;
    }
    Image image = Image::from_planes(static_cast<int>(w), static_cast<int>(h), names, std::move(planes));

    for (auto it = header.begin(); it != header.end(); ++it)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        image.metadata[it.name()] = s->value();
    return image;
  });
}

}  // namespace grtrace
